//! Emissive shapes written as `[[lights]]` (quad, sphere and mesh lights): objects with an
//! emission, read as objects are. Every other `type` is a kind of `light::kinds`, which
//! reads its own parameters.

use super::transforms::TransformEntry;
use super::values::Vec3;
use serde::Deserialize;

#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub(crate) enum EmissiveShapeKind {
    Quad,
    Sphere,
    Mesh,
}

impl EmissiveShapeKind {
    pub(crate) const NAMES: [&str; 3] = ["quad", "sphere", "mesh"];
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct EmissiveShapeToml {
    #[serde(rename = "type")]
    pub kind: EmissiveShapeKind,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub corner: Option<Vec3>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub u: Option<Vec3>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub v: Option<Vec3>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub emission: Option<Vec3>,
    /// Emits on both sides (a quad emits only towards u × v, a mesh towards its
    /// counter-clockwise side, a sphere outwards).
    pub two_sided: Option<bool>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub center: Option<Vec3>,
    pub radius: Option<f64>,
    pub file: Option<String>,
    pub transform: Option<Vec<TransformEntry>>,
}
