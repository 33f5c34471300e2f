//! Lights and environment maps, as written.

use super::materials::ImageEncodingToml;
use super::transforms::TransformEntry;
use super::values::Vec3;
use serde::Deserialize;

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
