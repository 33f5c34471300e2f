//! The scene file and its camera, render and tone-mapping tables.

use super::materials::MaterialToml;
use super::objects::ObjectToml;
use super::textures::TextureToml;
use super::values::Vec3;
use serde::Deserialize;
use std::collections::BTreeMap;
use toml::Table;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SceneFile {
    pub camera: CameraToml,
    pub render: Option<RenderToml>,
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialToml>,
    #[serde(default)]
    pub objects: Vec<ObjectToml>,
    #[serde(default)]
    pub lights: Vec<Table>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct CameraToml {
    #[serde(deserialize_with = "super::values::exact")]
    pub lookfrom: Vec3,
    #[serde(deserialize_with = "super::values::exact")]
    pub lookat: Vec3,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub up: Option<Vec3>,
    pub vfov: f64,
    #[serde(deserialize_with = "super::values::exact")]
    pub resolution: [u32; 2],
    /// Lens diameter (side for a square lens); excludes `f_number`/`focal_length`.
    pub aperture: Option<f64>,
    /// With `focal_length`: aperture = focal_length / f_number.
    pub f_number: Option<f64>,
    pub focal_length: Option<f64>,
    pub lens: Option<LensToml>,
    pub focus_distance: Option<f64>,
    /// Lens shift (off-axis projection): the window centre at unit distance.
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub shift: Option<[f64; 2]>,
    /// A pixel's width over its height (default 1, square pixels).
    pub pixel_aspect: Option<f64>,
    /// Near and far clip distances along the view axis (Mitsuba's `near_clip`, `far_clip`).
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub clip: Option<[f64; 2]>,
    /// The image flipped left to right (a camera whose transform mirrors).
    pub mirrored: Option<bool>,
}

#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum LensToml {
    Disk,
    Square,
}

#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum IntegratorToml {
    Path,
    Whitted,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RenderToml {
    pub spp: Option<u32>,
    pub max_depth: Option<u32>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub background: Option<Vec3>,
    pub light_samples: Option<u32>,
    pub integrator: Option<IntegratorToml>,
    pub tonemap: Option<TonemapToml>,
    pub background_texture: Option<TextureToml>,
    pub filter: Option<FilterToml>,
    pub hide_emitters: Option<bool>,
    /// Which normal decides a surface's side: "both" (the shading normal and the
    /// triangle) or "shading" (the shading normal alone, as Mitsuba).
    pub sides: Option<SidesToml>,
    pub rr_depth: Option<u32>,
    /// `[x0, y0, x1, y1]`: the window of the image rendered (the second corner excluded).
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub crop: Option<[u32; 4]>,
    /// The seed of the render's random numbers (`--seed` overrides it).
    pub seed: Option<u64>,
    /// Whether sample positions are jittered within their strata (`--no-jitter`: false).
    pub jitter: Option<bool>,
}

/// `filter = { type = "gaussian", stddev = 0.5 }`: the pixel reconstruction filter.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct FilterToml {
    #[serde(rename = "type")]
    pub kind: FilterKindToml,
    pub stddev: Option<f64>,
    pub radius: Option<f64>,
    pub b: Option<f64>,
    pub c: Option<f64>,
    pub lobes: Option<f64>,
}

#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum FilterKindToml {
    Box,
    Gaussian,
    Tent,
    Mitchell,
    Catmullrom,
    Lanczos,
}

/// `tonemap = { operator = "photographic", key = 0.18, burn_out = 1, saturation = 1,
/// gamma = 2.2 }`: how the scene wants its PNG (each number optional, those the defaults).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct TonemapToml {
    pub operator: TonemapOperatorToml,
    pub key: Option<f64>,
    pub burn_out: Option<f64>,
    pub saturation: Option<f64>,
    pub gamma: Option<f64>,
}

#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum TonemapOperatorToml {
    Photographic,
}

#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum SidesToml {
    Both,
    Shading,
}
