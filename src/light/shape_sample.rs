//! What sampling a point on an emitter gives, and the density conversions and stability
//! bounds every emitter shape shares.

use glam::Vec3;

/// Below this solid angle (sr) a light is sampled by area: the spherical excess loses
/// precision and the light is far enough that area sampling is as good (pbrt-v4's bound).
const MIN_SOLID_ANGLE: f64 = 3e-4;
/// Above it, by area too: a triangle covering nearly a hemisphere makes Arvo's construction
/// unstable.
const MAX_SOLID_ANGLE: f64 = 6.22;

/// A point sampled on an emitter's surface, and its density per unit solid angle at the
/// shading point it was sampled from.
#[derive(Clone, Copy, Debug)]
pub struct ShapeSample {
    pub point: Vec3,
    /// Rounding-error bound of `point`.
    pub error: Vec3,
    /// Unit normal at `point`.
    pub normal: Vec3,
    pub pdf: f32,
}

/// Density per unit solid angle at `reference` of a density per unit area `pdf_area` at
/// `point` (normal `normal`).
pub fn solid_angle_density(pdf_area: f32, reference: Vec3, point: Vec3, normal: Vec3) -> f32 {
    let to_point = point - reference;
    let dist2 = to_point.length_squared();
    let cos = normal.dot(to_point).abs() / dist2.sqrt();
    if cos > 0.0 && dist2 > 0.0 { pdf_area * dist2 / cos } else { 0.0 }
}

/// Whether solid-angle sampling is stable for this solid angle.
pub fn by_solid_angle(omega: f64) -> bool {
    (MIN_SOLID_ANGLE..=MAX_SOLID_ANGLE).contains(&omega)
}

/// 1 − cos θ for the cone of half-angle θ, without cancellation for tiny cones.
pub fn one_minus_cos(sin2: f32) -> f32 {
    sin2 / (1.0 + (1.0 - sin2).sqrt())
}
