//! Texture tables, as written.

use super::values::Vec3;
use serde::Deserialize;

#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum TextureKind {
    Checker2d,
    Checker3d,
    /// The course's checkerboard (`scale`, `offset`, `black`, `white`).
    Checker,
    Perlin,
    Image,
    /// One `value` everywhere, as it is (a normal map's flat normal is [0.5, 0.5, 1]).
    Constant,
    /// The hit mesh's attribute `name` (a PLY file's `face_color`, `vertex_color`, …).
    MeshAttribute,
}

#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum TextureModeToml {
    Replace,
    Blend,
    ReplaceAll,
}

#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum NoiseConversionToml {
    Absval,
    Linear,
}

#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum InterpolationToml {
    Nearest,
    Bilinear,
    BilinearCentered,
}

/// How an image's texel values become colours: `srgb` decodes 8- and 16-bit values through
/// the sRGB curve to linear [0, 1]; `raw` divides the values, in 0–255 whatever the file's
/// depth, by `normalizer`.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum ImageEncodingToml {
    Srgb,
    Raw,
}

/// `texture = { type = "image", file = "wood.png" }` and the procedural patterns; each
/// type takes only its own fields (checked in `materials`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct TextureToml {
    #[serde(rename = "type")]
    pub kind: TextureKind,
    pub mode: Option<TextureModeToml>,
    pub scale: Option<f64>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub even: Option<Vec3>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub odd: Option<Vec3>,
    pub offset: Option<f64>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub black: Option<Vec3>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub white: Option<Vec3>,
    pub conversion: Option<NoiseConversionToml>,
    pub file: Option<String>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub value: Option<Vec3>,
    /// A `mesh_attribute` texture's attribute.
    pub name: Option<String>,
    pub interpolation: Option<InterpolationToml>,
    pub encoding: Option<ImageEncodingToml>,
    pub normalizer: Option<f64>,
    /// The image's v runs up (OBJ/MTL's convention) instead of down.
    pub flip_v: Option<bool>,
    /// A bump map's height per unit of texture value.
    pub factor: Option<f64>,
    /// What a bump map's heights are measured in.
    pub heights: Option<BumpHeightsToml>,
}

/// `heights` of a bump map: `scene` (scene units, slopes per unit of texture coordinate) or
/// `course_texels` (the CENG795 course's `bump_normal`; see `BumpScale`).
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum BumpHeightsToml {
    Scene,
    CourseTexels,
}
