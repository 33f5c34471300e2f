//! An emitting sphere: sampled uniformly in the cone it subtends from a shading point outside
//! it (pbrt-v4's construction), else uniformly by area.

use super::shape_sample::{ShapeSample, one_minus_cos, solid_angle_density};
use crate::float_error::sphere_point_from_local;
use crate::sampling::frame_from_normal;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereShape {
    pub center: Vec3,
    pub radius: f32,
}

impl SphereShape {
    pub fn area(&self) -> f32 {
        4.0 * PI * self.radius * self.radius
    }

    /// The sine² of the half-angle of the cone the sphere subtends from `reference`, where
    /// sampling that cone is stable (outside the sphere, not grazing it).
    fn cone(&self, reference: Vec3) -> Option<f32> {
        let sin2_max = self.radius * self.radius / (self.center - reference).length_squared();
        (sin2_max < 0.9999).then_some(sin2_max)
    }

    fn cone_pdf(sin2_max: f32) -> f32 {
        1.0 / (2.0 * PI * one_minus_cos(sin2_max))
    }

    /// A point sampled from `reference` with `u`.
    pub fn sample_from(&self, reference: Vec3, u: Vec2) -> Option<ShapeSample> {
        let Some(sin2_max) = self.cone(reference) else {
            return self.sample_by_area(reference, u);
        };
        let normal = cone_normal(self.center, reference, sin2_max, u);
        let (point, error) = sphere_point(self.center, self.radius, normal);
        Some(ShapeSample { point, error, normal, pdf: Self::cone_pdf(sin2_max) })
    }

    /// A point sampled uniformly by area (its density still per unit solid angle at
    /// `reference`).
    pub fn sample_by_area(&self, reference: Vec3, u: Vec2) -> Option<ShapeSample> {
        let z = 1.0 - 2.0 * u.x;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let (sin_phi, cos_phi) = (2.0 * PI * u.y).sin_cos();
        let normal = Vec3::new(r * cos_phi, r * sin_phi, z);
        let (point, error) = sphere_point(self.center, self.radius, normal);
        let pdf = solid_angle_density(1.0 / self.area(), reference, point, normal);
        (pdf > 0.0).then_some(ShapeSample { point, error, normal, pdf })
    }

    /// The density per unit solid angle with which `sample_from(reference, ..)` picks
    /// `point` (normal `normal`) on the sphere.
    pub fn pdf_from(&self, reference: Vec3, point: Vec3, normal: Vec3) -> f32 {
        match self.cone(reference) {
            Some(sin2_max) => Self::cone_pdf(sin2_max),
            None => solid_angle_density(1.0 / self.area(), reference, point, normal),
        }
    }
}

/// The point at unit normal `normal` of a sphere, with its rounding-error bound.
fn sphere_point(center: Vec3, radius: f32, normal: Vec3) -> (Vec3, Vec3) {
    sphere_point_from_local(center, radius, radius * normal)
}

/// Uniform direction in the cone a sphere subtends from `reference`, returned as the
/// sphere's unit normal at the visible point it reaches (the angle at the centre follows
/// from the angle at the shading point, as in pbrt-v4).
fn cone_normal(center: Vec3, reference: Vec3, sin2_max: f32, u: Vec2) -> Vec3 {
    let sin_max = sin2_max.sqrt();
    let one_minus_cos_theta = u.x * one_minus_cos(sin2_max);
    let cos_theta = 1.0 - one_minus_cos_theta;
    let sin2_theta = one_minus_cos_theta * (2.0 - one_minus_cos_theta);
    let cos_alpha =
        sin2_theta / sin_max + cos_theta * (1.0 - sin2_theta / sin2_max).max(0.0).sqrt();
    let sin_alpha = (1.0 - cos_alpha * cos_alpha).max(0.0).sqrt();
    let (sin_phi, cos_phi) = (2.0 * PI * u.y).sin_cos();
    let frame = frame_from_normal((center - reference).normalize());
    (frame * Vec3::new(sin_alpha * cos_phi, sin_alpha * sin_phi, -cos_alpha)).normalize()
}
