//! Materials and their course reflectance models, as written.

use super::textures::TextureToml;
use super::values::Vec3;
use serde::Deserialize;

#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum MaterialKind {
    #[default]
    Diffuse,
    Mirror,
    Conductor,
    Dielectric,
    Plastic,
    /// A thin sheet of glass (Mitsuba's `thindielectric`).
    #[serde(rename = "thindielectric")]
    ThinDielectric,
    /// `weight` of the second of two named `materials`, the rest of the first.
    Blend,
    Principled,
    #[serde(rename = "principledthin")]
    PrincipledThin,
}

#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum DistributionToml {
    Ggx,
    Beckmann,
}

/// `opacity = 0.5` or `opacity = { type = "image", file = "leaf.png" }` (its mean channel).
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(crate) enum OpacityToml {
    Constant(f64),
    Texture(Box<TextureToml>),
}

/// Named metals for `preset` (conductor materials).
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum MetalPreset {
    Gold,
    Silver,
    Copper,
    #[serde(alias = "aluminum")]
    Aluminium,
}

/// `roughness = 0.2`, or `roughness = [0.3, 0.05]`: anisotropic, α along ∂p/∂u, then along
/// the bitangent; or a texture (α its mean channel per hit), or two.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(crate) enum RoughnessToml {
    Isotropic(f64),
    Anisotropic([f64; 2]),
    Texture(Box<TextureToml>),
    Textures(Box<[TextureToml; 2]>),
}

/// A material; like objects, one flat struct whose fields `materials` checks per type.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct MaterialToml {
    #[serde(rename = "type")]
    pub kind: Option<MaterialKind>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub albedo: Option<Vec3>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub emission: Option<Vec3>,
    pub two_sided_emission: Option<bool>,
    /// What `emission` is multiplied by per point (a pattern of texture coordinates).
    pub emission_texture: Option<Box<TextureToml>>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub reflectance: Option<Vec3>,
    /// What a thin dielectric lets through is scaled by.
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub transmittance: Option<Vec3>,
    pub roughness: Option<RoughnessToml>,
    pub distribution: Option<DistributionToml>,
    /// A rough mirror's or conductor's masking-shadowing: "height-correlated" or
    /// "separable".
    pub shadowing: Option<String>,
    pub nonlinear: Option<bool>,
    pub opacity: Option<Box<OpacityToml>>,
    pub one_sided: Option<bool>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub eta: Option<Vec3>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub k: Option<Vec3>,
    pub preset: Option<MetalPreset>,
    pub ior: Option<f64>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub absorption: Option<Vec3>,
    /// The parameters of a `principled` or `principledthin` material.
    pub principled: Option<Box<super::principled::PrincipledToml>>,
    pub texture: Option<Box<TextureToml>>,
    pub specular_texture: Option<Box<TextureToml>>,
    pub normal_map: Option<Box<TextureToml>>,
    pub bump_map: Option<Box<TextureToml>>,
    pub bump_shadowing: Option<bool>,
    pub phong: Option<Box<PhongToml>>,
    pub brdf: Option<Box<BrdfToml>>,
    /// A blend's share of its second material: a number or a texture's mean channel.
    pub weight: Option<Box<OpacityToml>>,
    /// A blend's two materials, by name.
    pub materials: Option<Vec<String>>,
}

/// The CENG795 hw6 reflectance models, for the Whitted (course) integrator.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum BrdfModelToml {
    OriginalBlinnPhong,
    OriginalPhong,
    ModifiedBlinnPhong,
    ModifiedPhong,
    TorranceSparrow,
}

/// `brdf = { model = "torrance_sparrow", exponent = 50, kd_fresnel = true, eta = 0.37,
/// k = 2.82 }`: the model, its exponent, `normalized` (the modified models) or
/// `kd_fresnel`, `eta` and `k` (Torrance-Sparrow's conductor Fresnel).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BrdfToml {
    pub model: BrdfModelToml,
    pub exponent: Option<f64>,
    pub normalized: Option<bool>,
    pub kd_fresnel: Option<bool>,
    pub eta: Option<f64>,
    pub k: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PhongToml {
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub ambient: Option<Vec3>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub specular: Option<Vec3>,
    pub exponent: Option<f64>,
}
