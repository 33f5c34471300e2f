//! Materials, their course reflectance models and textures, as written.

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
    pub albedo: Option<Vec3>,
    pub emission: Option<Vec3>,
    pub two_sided_emission: Option<bool>,
    pub reflectance: Option<Vec3>,
    pub roughness: Option<RoughnessToml>,
    pub distribution: Option<DistributionToml>,
    pub nonlinear: Option<bool>,
    pub opacity: Option<OpacityToml>,
    pub one_sided: Option<bool>,
    pub eta: Option<Vec3>,
    pub k: Option<Vec3>,
    pub preset: Option<MetalPreset>,
    pub ior: Option<f64>,
    pub absorption: Option<Vec3>,
    /// The parameters of a `principled` or `principledthin` material.
    pub principled: Option<super::principled::PrincipledToml>,
    pub texture: Option<TextureToml>,
    pub specular_texture: Option<TextureToml>,
    pub normal_map: Option<TextureToml>,
    pub bump_map: Option<TextureToml>,
    pub bump_shadowing: Option<bool>,
    pub phong: Option<PhongToml>,
    pub brdf: Option<BrdfToml>,
    /// A blend's share of its second material: a number or a texture's mean channel.
    pub weight: Option<OpacityToml>,
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
/// the sRGB curve to linear [0, 1]; `raw` divides the file's own values by `normalizer`.
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
    pub even: Option<Vec3>,
    pub odd: Option<Vec3>,
    pub offset: Option<f64>,
    pub black: Option<Vec3>,
    pub white: Option<Vec3>,
    pub conversion: Option<NoiseConversionToml>,
    pub file: Option<String>,
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

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PhongToml {
    pub ambient: Option<Vec3>,
    pub specular: Option<Vec3>,
    pub exponent: Option<f64>,
}
