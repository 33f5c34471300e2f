//! Path tracing with next-event estimation: at every diffuse hit, one shadow ray per point
//! light and one to a point sampled on the emitters; then a cosine-weighted bounce. Emission
//! is counted only where a camera ray sees it directly, since every later bounce already
//! sampled the emitters explicitly.

use crate::accel::{Accel, Ray};
use crate::render_scene::RenderScene;
use crate::sampling::{SampleStream, cosine_hemisphere};
use crate::spawn::SurfacePoint;
use crate::stats::RenderStats;
use crate::surface::{SurfaceInteraction, interaction};
use glam::{Mat3, Quat, Vec3};
use std::f32::consts::FRAC_1_PI;

/// What one camera sample contributes to a pixel.
#[derive(Clone, Copy, Debug, Default)]
pub struct PathSample {
    pub radiance: Vec3,
    /// Distance to the first hit along the (unit) camera ray.
    pub depth: Option<f32>,
    /// World-space shading normal at the first hit.
    pub normal: Option<Vec3>,
}

pub struct PathTracer<'a> {
    scene: &'a RenderScene,
    accel: &'a dyn Accel,
    /// Number of surface interactions that gather light (1 = direct lighting only).
    max_depth: u32,
    /// Rotation into the space where bounce directions are sampled (see `sampling_space`).
    sampling_from_render: Mat3,
}

/// A fixed rotation of world space in which no common surface normal lies on the
/// discontinuity of `frame_from_normal` (normals with z = 0): it maps a generic direction to
/// +Z, so axis-aligned walls (world normals ±X, ±Y, ±Z) are far from it. Sampling in a
/// world-fixed frame makes every render space turn the same random numbers into the same
/// directions; render spaces then differ by rounding only, not by noise pattern.
fn sampling_from_world() -> Mat3 {
    let generic = Vec3::new(0.267_261_24, 0.534_522_5, 0.801_783_7);
    Mat3::from_quat(Quat::from_rotation_arc(generic, Vec3::Z))
}

/// Orthonormal basis whose Z axis is `n` (Duff et al. 2017, branchless).
fn frame_from_normal(n: Vec3) -> Mat3 {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    Mat3::from_cols(
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
        n,
    )
}

impl<'a> PathTracer<'a> {
    pub fn new(scene: &'a RenderScene, accel: &'a dyn Accel, max_depth: u32) -> Self {
        let sampling_from_render = sampling_from_world() * scene.camera.world_from_render;
        PathTracer { scene, accel, max_depth, sampling_from_render }
    }

    pub fn scene(&self) -> &RenderScene {
        self.scene
    }

    fn occluded(&self, ray: &Ray, stats: &mut RenderStats) -> bool {
        if !ray.is_valid() {
            return true;
        }
        stats.shadow.rays += 1;
        let blocked = self.accel.occluded(ray, &mut stats.traversal);
        stats.shadow.hits += blocked as u64;
        blocked
    }

    /// Light arriving directly from lights at `si`, reflected towards the viewer, for a
    /// Lambertian surface of reflectance `albedo`.
    fn direct_light(
        &self,
        si: &SurfaceInteraction,
        albedo: Vec3,
        time: f32,
        stream: &mut SampleStream,
        stats: &mut RenderStats,
    ) -> Vec3 {
        let brdf = albedo * FRAC_1_PI;
        let p = si.surface.point;
        let mut sum = Vec3::ZERO;
        for light in &self.scene.lights.points {
            let to_light = light.position - p;
            let dist2 = to_light.length_squared();
            let wi = to_light / dist2.sqrt();
            let cos = si.shading_normal.dot(wi);
            if cos <= 0.0 || si.surface.normal.dot(wi) <= 0.0 || dist2 == 0.0 {
                continue;
            }
            let shadow = si.surface.spawn_ray_to(&SurfacePoint::exact(light.position), time);
            if !self.occluded(&shadow, stats) {
                sum += brdf * light.intensity * (cos / dist2);
            }
        }
        if self.scene.lights.has_emitters() {
            let pick = stream.next_1d();
            let on_surface = stream.next_2d();
            if let Some(sample) = self.scene.lights.sample_emitter(pick, on_surface) {
                let to_light = sample.point - p;
                let dist2 = to_light.length_squared();
                let wi = to_light / dist2.sqrt();
                let cos_surface = si.shading_normal.dot(wi);
                let cos_light = sample.normal.dot(wi).abs();
                if cos_surface > 0.0
                    && si.surface.normal.dot(wi) > 0.0
                    && cos_light > 0.0
                    && dist2 > 0.0
                    && sample.geom_id != si.geom_id
                {
                    let target = SurfacePoint {
                        point: sample.point,
                        error: sample.error,
                        normal: sample.normal,
                    };
                    let shadow = si.surface.spawn_ray_to(&target, time);
                    if !self.occluded(&shadow, stats) {
                        let pdf_solid_angle = sample.pdf_area * dist2 / cos_light;
                        sum += brdf * sample.emission * (cos_surface / pdf_solid_angle);
                    }
                }
            }
        }
        sum
    }

    /// Traces one camera path.
    pub fn trace(
        &self,
        camera_ray: Ray,
        stream: &mut SampleStream,
        stats: &mut RenderStats,
    ) -> PathSample {
        let mut result = PathSample::default();
        let mut ray = camera_ray;
        let mut throughput = Vec3::ONE;
        for depth in 0..self.max_depth.max(1) {
            if !ray.is_valid() {
                break;
            }
            let counts = if depth == 0 { &mut stats.camera } else { &mut stats.indirect };
            counts.rays += 1;
            let Some(hit) = self.accel.intersect(&ray, &mut stats.traversal) else {
                result.radiance += throughput * self.scene.background;
                break;
            };
            let counts = if depth == 0 { &mut stats.camera } else { &mut stats.indirect };
            counts.hits += 1;
            let si = interaction(self.scene, &ray, &hit);
            let material = &self.scene.materials[si.material as usize];
            if depth == 0 {
                result.depth = Some(hit.t);
                result.normal = Some(self.scene.camera.world_from_render * si.shading_normal);
                result.radiance += throughput * material.emission;
            }
            if self.max_depth == 0 || material.albedo == Vec3::ZERO {
                break;
            }
            result.radiance +=
                throughput * self.direct_light(&si, material.albedo, ray.time, stream, stats);
            if depth + 1 >= self.max_depth {
                break;
            }
            let local = cosine_hemisphere(stream.next_2d());
            let sampling_normal = (self.sampling_from_render * si.shading_normal).normalize();
            let dir = self.sampling_from_render.transpose()
                * (frame_from_normal(sampling_normal) * local);
            if dir.dot(si.surface.normal) <= 0.0 {
                break;
            }
            // Lambertian: f·cos/pdf = albedo.
            throughput *= material.albedo;
            if depth >= 3 {
                let survive = throughput.max_element().min(0.95);
                if stream.next_1d() >= survive {
                    break;
                }
                throughput /= survive;
            }
            ray = si.surface.spawn_ray(dir, ray.time);
        }
        result
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal_for_any_normal() {
        for n in [Vec3::Z, Vec3::NEG_Z, Vec3::new(0.3, -0.8, 0.1).normalize(), Vec3::X] {
            let f = frame_from_normal(n);
            assert!((f.determinant().abs() - 1.0).abs() < 1e-5);
            assert!((f.z_axis - n).length() < 1e-6);
            assert!(f.x_axis.dot(f.y_axis).abs() < 1e-5 && f.x_axis.dot(n).abs() < 1e-5);
        }
    }
}
