//! The CENG795 course's shading model: ambient + Blinn-Phong direct light with shadow rays,
//! recursive perfect (or roughness-perturbed) mirror, conductor and dielectric rays up to
//! the maximum recursion depth, no indirect diffuse light. Scenes in the course's units keep
//! radiance in 0–255 display units; the PNG writer then clamps without a tone curve.

use crate::accel::{Accel, Ray};
use crate::bsdf::{fresnel_conductor, fresnel_dielectric};
use crate::integrator::PathSample;
use crate::material::Specular;
use crate::render_scene::RenderScene;
use crate::sampling::SampleStream;
use crate::spawn::{SpawnMode, SurfacePoint};
use crate::stats::RenderStats;
use crate::surface::{SurfaceInteraction, interaction};
use glam::{Vec2, Vec3};

pub struct WhittedTracer<'a> {
    scene: &'a RenderScene,
    accel: &'a dyn Accel,
    /// Reflection/refraction bounces after the camera ray.
    max_depth: u32,
    spawn: SpawnMode,
}

fn reflect(d: Vec3, n: Vec3) -> Vec3 {
    d - 2.0 * d.dot(n) * n
}

/// Perturbs a unit direction within a square of side `roughness` on its tangent plane (the
/// course's glossy reflection).
fn perturb(r: Vec3, roughness: f32, u: Vec2) -> Vec3 {
    let a = if r.x.abs() < 0.9 { Vec3::X } else { Vec3::Y };
    let t = r.cross(a).normalize();
    let b = r.cross(t);
    (r + roughness * ((u.x - 0.5) * t + (u.y - 0.5) * b)).normalize()
}

impl<'a> WhittedTracer<'a> {
    pub fn new(
        scene: &'a RenderScene,
        accel: &'a dyn Accel,
        max_depth: u32,
        spawn: SpawnMode,
    ) -> Self {
        WhittedTracer { scene, accel, max_depth, spawn }
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

    /// Ambient + diffuse + Blinn-Phong specular from every light at `si`.
    fn local_shading(
        &self,
        si: &SurfaceInteraction,
        wo: Vec3,
        time: f32,
        stream: &mut SampleStream,
        stats: &mut RenderStats,
    ) -> Vec3 {
        let material = &self.scene.materials[si.material as usize];
        let lights = &self.scene.lights;
        let (ambient, specular, exponent) = match &material.phong {
            Some(p) => (p.ambient, p.specular, p.exponent),
            None => (Vec3::ZERO, Vec3::ZERO, 1.0),
        };
        let n = si.shading_normal;
        let shade = |wi: Vec3, irradiance: Vec3| {
            let cos = n.dot(wi).max(0.0);
            let h = (wi + wo).normalize_or_zero();
            let highlight = n.dot(h).max(0.0).powf(exponent);
            (material.albedo * cos + specular * highlight) * irradiance
        };
        let mut color = ambient * lights.ambient;
        let faces = |wi: Vec3| si.surface.normal.dot(wi) > 0.0;
        for light in &lights.points {
            let to_light = light.position - si.surface.point;
            let dist2 = to_light.length_squared();
            let wi = to_light / dist2.sqrt();
            if !faces(wi) {
                continue;
            }
            let shadow = self.spawn.ray_to(&si.surface, &SurfacePoint::exact(light.position), time);
            if !self.occluded(&shadow, stats) {
                color += shade(wi, light.intensity / dist2);
            }
        }
        for light in &lights.directional {
            let wi = -light.direction;
            if faces(wi) && !self.occluded(&self.spawn.ray(&si.surface, wi, time), stats) {
                color += shade(wi, light.irradiance);
            }
        }
        if lights.has_emitters() {
            if let Some(sample) = lights.sample_emitter(stream.next_1d(), stream.next_2d()) {
                let to_light = sample.point - si.surface.point;
                let dist2 = to_light.length_squared();
                let wi = to_light / dist2.sqrt();
                let cos_light = (-sample.normal.dot(wi)).max(0.0);
                let target = SurfacePoint {
                    point: sample.point,
                    error: sample.error,
                    normal: sample.normal,
                };
                if faces(wi)
                    && sample.geom_id != si.geom_id
                    && !self.occluded(&self.spawn.ray_to(&si.surface, &target, time), stats)
                {
                    color += shade(wi, sample.emission * cos_light / (dist2 * sample.pdf_area));
                }
            }
        }
        color
    }

    /// Radiance along `ray`, recursing `depth_left` more times through specular surfaces.
    fn radiance(
        &self,
        ray: &Ray,
        depth_left: u32,
        camera_ray: bool,
        stream: &mut SampleStream,
        stats: &mut RenderStats,
        first: &mut PathSample,
    ) -> Vec3 {
        if !ray.is_valid() {
            return Vec3::ZERO;
        }
        let counts = if camera_ray { &mut stats.camera } else { &mut stats.indirect };
        counts.rays += 1;
        let Some(hit) = self.accel.intersect(ray, &mut stats.traversal) else {
            return self.scene.background;
        };
        let counts = if camera_ray { &mut stats.camera } else { &mut stats.indirect };
        counts.hits += 1;
        let si = interaction(self.scene, ray, &hit);
        if camera_ray {
            first.depth = Some(hit.t);
            first.normal = Some(self.scene.camera.world_from_render * si.shading_normal);
        }
        let material = &self.scene.materials[si.material as usize];
        let wo = -ray.dir.normalize();
        let mut color = if si.front_face { material.emission } else { Vec3::ZERO };
        if !material.is_dielectric() {
            color += self.local_shading(&si, wo, ray.time, stream, stats);
        }
        if depth_left == 0 {
            return color;
        }
        let n = si.shading_normal;
        let cos_o = n.dot(wo).clamp(0.0, 1.0);
        let reflected = |tint: Vec3,
                         stream: &mut SampleStream,
                         stats: &mut RenderStats,
                         first: &mut PathSample| {
            if tint == Vec3::ZERO {
                return Vec3::ZERO;
            }
            let mut dir = reflect(-wo, n);
            if material.roughness > 0.0 {
                dir = perturb(dir, material.roughness, stream.next_2d());
            }
            if dir.dot(si.surface.normal) <= 0.0 {
                return Vec3::ZERO;
            }
            let next = self.spawn.ray(&si.surface, dir, ray.time);
            tint * self.radiance(&next, depth_left - 1, false, stream, stats, first)
        };
        match material.specular {
            Specular::None => {}
            Specular::Mirror { reflectance } => {
                color += reflected(reflectance, stream, stats, first);
            }
            Specular::Conductor { eta, k, reflectance } => {
                let tint = fresnel_conductor(cos_o, eta, k) * reflectance;
                color += reflected(tint, stream, stats, first);
            }
            Specular::Dielectric { ior, absorption } => {
                let eta = if si.front_face { ior } else { 1.0 / ior };
                let fr = fresnel_dielectric(cos_o, eta);
                color += reflected(Vec3::splat(fr), stream, stats, first);
                if fr < 1.0 {
                    let sin2_t = (1.0 - cos_o * cos_o) / (eta * eta);
                    let cos_t = (1.0 - sin2_t).max(0.0).sqrt();
                    let dir = (-wo / eta + (cos_o / eta - cos_t) * n).normalize();
                    let next = self.spawn.ray(&si.surface, dir, ray.time);
                    let mut inside =
                        self.radiance(&next, depth_left - 1, false, stream, stats, first);
                    if si.front_face && absorption != Vec3::ZERO {
                        // Beer's law over the distance to where the refracted ray leaves.
                        let mut scratch = TraversalScratch::default();
                        if let Some(exit) = self.accel.intersect(&next, &mut scratch.0) {
                            inside *= (-absorption * exit.t * next.dir.length()).exp();
                        }
                    }
                    color += (1.0 - fr) * inside;
                }
            }
        }
        color
    }

    pub fn trace(
        &self,
        camera_ray: Ray,
        stream: &mut SampleStream,
        stats: &mut RenderStats,
    ) -> PathSample {
        let mut result = PathSample::default();
        result.radiance =
            self.radiance(&camera_ray, self.max_depth, true, stream, stats, &mut result);
        result
    }
}

/// Counters for bookkeeping queries that should not show up in the statistics.
#[derive(Default)]
struct TraversalScratch(crate::stats::TraversalCounters);
