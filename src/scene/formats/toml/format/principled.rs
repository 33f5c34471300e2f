//! The `principled` table of a `principled` or `principledthin` material: Mitsuba's
//! parameter names, each weight a number or a texture table.

use super::textures::TextureToml;
use serde::Deserialize;

/// `metallic = 0.5`, or `metallic = { type = "checker2d", … }` (its mean channel).
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(crate) enum ParamToml {
    Number(f64),
    Texture(Box<TextureToml>),
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PrincipledToml {
    pub roughness: Option<ParamToml>,
    pub anisotropic: Option<ParamToml>,
    pub metallic: Option<ParamToml>,
    pub spec_tint: Option<ParamToml>,
    pub specular: Option<f64>,
    pub eta: Option<ParamToml>,
    pub sheen: Option<ParamToml>,
    pub sheen_tint: Option<ParamToml>,
    pub clearcoat: Option<ParamToml>,
    pub clearcoat_gloss: Option<ParamToml>,
    pub spec_trans: Option<ParamToml>,
    pub flatness: Option<ParamToml>,
    pub diff_trans: Option<ParamToml>,
    pub main_specular_sampling_rate: Option<f64>,
    pub clearcoat_sampling_rate: Option<f64>,
    pub diffuse_reflectance_sampling_rate: Option<f64>,
    pub specular_reflectance_sampling_rate: Option<f64>,
    pub specular_transmittance_sampling_rate: Option<f64>,
    pub diffuse_transmittance_sampling_rate: Option<f64>,
}
