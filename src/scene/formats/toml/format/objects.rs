//! Objects and their repeat grids, as written.

use super::transforms::TransformEntry;
use super::values::Vec3;
use serde::Deserialize;

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
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub corner: Option<Vec3>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub u: Option<Vec3>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub v: Option<Vec3>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub center: Option<Vec3>,
    pub radius: Option<f64>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub min: Option<Vec3>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
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
    #[serde(deserialize_with = "super::values::exact")]
    pub count: [u32; 3],
    #[serde(deserialize_with = "super::values::exact")]
    pub spacing: Vec3,
}
