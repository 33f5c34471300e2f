//! The scene file as written: serde structs for the TOML format. Every struct denies unknown
//! keys. Objects and lights are flat structs (one optional field per key any type uses)
//! rather than internally tagged enums, because serde buffers tagged enums and toml then
//! loses the line of the offending key; `convert` checks which fields each type takes.

use serde::Deserialize;
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use std::collections::BTreeMap;
use std::fmt;

pub(crate) type Vec3 = [f64; 3];

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
    pub lights: Vec<LightToml>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct CameraToml {
    pub lookfrom: Vec3,
    pub lookat: Vec3,
    pub up: Option<Vec3>,
    pub vfov: f64,
    pub resolution: [u32; 2],
    /// Lens diameter (side for a square lens); excludes `f_number`/`focal_length`.
    pub aperture: Option<f64>,
    /// With `focal_length`: aperture = focal_length / f_number.
    pub f_number: Option<f64>,
    pub focal_length: Option<f64>,
    pub lens: Option<LensToml>,
    pub focus_distance: Option<f64>,
    /// Lens shift (off-axis projection): the window centre at unit distance.
    pub shift: Option<[f64; 2]>,
    /// A pixel's width over its height (default 1, square pixels).
    pub pixel_aspect: Option<f64>,
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
    pub background: Option<Vec3>,
    pub light_samples: Option<u32>,
    pub integrator: Option<IntegratorToml>,
    pub tonemap: Option<TonemapToml>,
    pub background_texture: Option<TextureToml>,
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

#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum MaterialKind {
    #[default]
    Diffuse,
    Mirror,
    Conductor,
    Dielectric,
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

/// A material; like objects, one flat struct whose fields `materials` checks per type.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct MaterialToml {
    #[serde(rename = "type")]
    pub kind: Option<MaterialKind>,
    pub albedo: Option<Vec3>,
    pub emission: Option<Vec3>,
    pub reflectance: Option<Vec3>,
    pub roughness: Option<f64>,
    pub eta: Option<Vec3>,
    pub k: Option<Vec3>,
    pub preset: Option<MetalPreset>,
    pub ior: Option<f64>,
    pub absorption: Option<Vec3>,
    pub texture: Option<TextureToml>,
    pub specular_texture: Option<TextureToml>,
    pub normal_map: Option<TextureToml>,
    pub bump_map: Option<TextureToml>,
    pub phong: Option<PhongToml>,
    pub brdf: Option<BrdfToml>,
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
    pub interpolation: Option<InterpolationToml>,
    pub encoding: Option<ImageEncodingToml>,
    pub normalizer: Option<f64>,
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

#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum ObjectKind {
    Quad,
    Sphere,
    Box,
    Mesh,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ObjectToml {
    #[serde(rename = "type")]
    pub kind: ObjectKind,
    pub material: Option<String>,
    pub corner: Option<Vec3>,
    pub u: Option<Vec3>,
    pub v: Option<Vec3>,
    pub center: Option<Vec3>,
    pub radius: Option<f64>,
    pub min: Option<Vec3>,
    pub max: Option<Vec3>,
    pub file: Option<String>,
    pub smooth: Option<bool>,
    pub transform: Option<Vec<TransformEntry>>,
    pub transform_end: Option<Vec<TransformEntry>>,
    pub repeat: Option<RepeatToml>,
}

/// `repeat = { count = [nx, ny, nz], spacing = [dx, dy, dz] }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RepeatToml {
    pub count: [u32; 3],
    pub spacing: Vec3,
}

#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum LightKind {
    Point,
    /// A point light shining into a cone (`direction`, `coverage_angle`, `falloff_angle`).
    Spot,
    Quad,
    Directional,
    Ambient,
    Sphere,
    Mesh,
    /// The CENG795 area light: an invisible emitting square (`center`, `normal`, `size`,
    /// `radiance`).
    Area,
    /// Light from every direction far away: a latitude-longitude `file` (EXR, PNG or JPEG)
    /// or a constant `radiance`, times `scale`.
    Environment,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct LightToml {
    #[serde(rename = "type")]
    pub kind: LightKind,
    pub position: Option<Vec3>,
    pub intensity: Option<Vec3>,
    pub corner: Option<Vec3>,
    pub u: Option<Vec3>,
    pub v: Option<Vec3>,
    pub emission: Option<Vec3>,
    pub direction: Option<Vec3>,
    pub irradiance: Option<Vec3>,
    pub radiance: Option<Vec3>,
    pub center: Option<Vec3>,
    pub radius: Option<f64>,
    pub file: Option<String>,
    pub transform: Option<Vec<TransformEntry>>,
    pub normal: Option<Vec3>,
    pub size: Option<f64>,
    pub coverage_angle: Option<f64>,
    pub falloff_angle: Option<f64>,
    pub scale: Option<Vec3>,
    pub encoding: Option<ImageEncodingToml>,
    pub mapping: Option<EnvironmentMappingToml>,
}

#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum EnvironmentMappingToml {
    Latlong,
    Probe,
}

/// One entry of a transform list as written: an inline table that should have exactly one
/// of these keys (checked in `convert`, which then makes a `TransformOp`).
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct TransformEntry {
    pub scale: Option<Scale>,
    pub rotate: Option<Rotate>,
    pub translate: Option<Vec3>,
    pub matrix: Option<[[f64; 4]; 4]>,
}

impl TransformEntry {
    /// The operation if exactly one key is set, else the keys that are set.
    pub(crate) fn op(&self) -> Result<TransformOp, Vec<&'static str>> {
        let ops = [
            self.scale.map(|s| ("scale", TransformOp::Scale(s))),
            self.rotate.clone().map(|r| ("rotate", TransformOp::Rotate(r))),
            self.translate.map(|t| ("translate", TransformOp::Translate(t))),
            self.matrix.map(|m| ("matrix", TransformOp::Matrix(m))),
        ];
        let mut set: Vec<(&'static str, TransformOp)> = ops.into_iter().flatten().collect();
        if set.len() == 1 {
            Ok(set.remove(0).1)
        } else {
            Err(set.into_iter().map(|(name, _)| name).collect())
        }
    }
}

/// One transform operation.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum TransformOp {
    Scale(Scale),
    Rotate(Rotate),
    Translate(Vec3),
    /// Row-major 4×4; the last row must be 0 0 0 1.
    Matrix([[f64; 4]; 4]),
}

#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct Rotate {
    pub axis: Vec3,
    pub degrees: f64,
}

/// `scale = 2.0` or `scale = [1.0, 2.0, 1.0]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Scale {
    Uniform(f64),
    PerAxis(Vec3),
}

impl Scale {
    pub(crate) fn factors(self) -> Vec3 {
        match self {
            Scale::Uniform(s) => [s; 3],
            Scale::PerAxis(v) => v,
        }
    }
}

impl<'de> Deserialize<'de> for Scale {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct ScaleVisitor;

        impl<'de> Visitor<'de> for ScaleVisitor {
            type Value = Scale;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a number or an array of 3 numbers")
            }

            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Scale, E> {
                Ok(Scale::Uniform(v))
            }

            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Scale, E> {
                Ok(Scale::Uniform(v as f64))
            }

            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Scale, E> {
                Ok(Scale::Uniform(v as f64))
            }

            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Scale, A::Error> {
                let mut v = [0.0; 3];
                for (i, slot) in v.iter_mut().enumerate() {
                    *slot =
                        seq.next_element()?.ok_or_else(|| de::Error::invalid_length(i, &self))?;
                }
                if seq.next_element::<de::IgnoredAny>()?.is_some() {
                    return Err(de::Error::invalid_length(4, &self));
                }
                Ok(Scale::PerAxis(v))
            }
        }

        deserializer.deserialize_any(ScaleVisitor)
    }
}
