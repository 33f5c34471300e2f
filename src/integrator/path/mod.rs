//! Path tracing with next-event estimation and multiple importance sampling (power
//! heuristic): at every non-specular hit, one shadow ray per point/directional light,
//! `light_samples` to points sampled on emitters and `light_samples` towards the
//! environment; then the BSDF picks the next direction, the last bounce included (one more
//! ray then collects only the emission it finds, MIS-weighted: `light_sampling`).
//! Only the random dimensions the scene's effects call for are drawn.

mod light_sampling;

use super::PathSample;
use super::trace::SceneTracer;
use crate::accel::Accel;
use crate::ray::{Hit, Ray};
use crate::render_scene::RenderScene;
use crate::sampling::{SampleStream, frame_from_normal};
use crate::shading::bsdf::{Bsdf, Energy};
use crate::shading::material::MaskOpacity;
use crate::shading::surface::{SurfaceInteraction, interaction};
use crate::stats::RenderStats;
use glam::{Mat3, Quat, Vec2, Vec3};

pub struct PathTracer<'a> {
    tracer: SceneTracer<'a>,
    /// Number of surface interactions that gather light (1 = direct lighting only).
    max_depth: u32,
    /// Shadow rays to emitters per shading point.
    light_samples: u32,
    /// Rotation into the space where directions are sampled (see `sampling_from_world`).
    sampling_from_render: Mat3,
    energy: Energy,
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

impl<'a> PathTracer<'a> {
    pub(crate) fn new(
        tracer: SceneTracer<'a>,
        max_depth: u32,
        light_samples: u32,
        energy: Energy,
    ) -> Self {
        let sampling_from_render =
            sampling_from_world() * tracer.scene.camera.world_from_render_rotation;
        let light_samples = light_samples.max(1);
        PathTracer { tracer, max_depth, light_samples, sampling_from_render, energy }
    }

    pub fn scene(&self) -> &RenderScene {
        self.tracer.scene
    }

    fn occluded(&self, ray: &Ray, stats: &mut RenderStats) -> bool {
        self.tracer.occluded(ray, stats)
    }

    /// Local shading frame (normal = +Z) → render space, built in the world-fixed sampling
    /// space.
    fn shading_frame(&self, normal: Vec3) -> Mat3 {
        let n = (self.sampling_from_render * normal).normalize();
        self.sampling_from_render.transpose() * frame_from_normal(n)
    }

    /// The shading frame whose tangent follows ∂p/∂u, as Mitsuba's does: anisotropic
    /// roughness is measured along it. Where there is no such direction, any frame.
    fn tangent_frame(&self, si: &SurfaceInteraction, time: f32) -> Mat3 {
        let n = si.shading_normal;
        let tangent = crate::shading::normal_map::uv_derivatives(self.tracer.scene, si, time)
            .map(|d| (d.dpdu - n * n.dot(d.dpdu)).normalize_or_zero())
            .filter(|s| *s != Vec3::ZERO);
        match tangent {
            Some(s) => Mat3::from_cols(s, n.cross(s), n),
            None => self.shading_frame(n),
        }
    }

    /// The first hit along a camera ray past the emitting surfaces it meets: with
    /// `hide_emitters` camera rays go through them (Mitsuba's rule), lighting what is behind.
    fn past_emitters(
        &self,
        ray: &mut Ray,
        mut found: Option<Hit>,
        stats: &mut RenderStats,
    ) -> Option<Hit> {
        // A bound on stacked emitters, for rays that would graze along coplanar ones.
        for _ in 0..64 {
            let hit = found?;
            let si = interaction(self.tracer.scene, ray, &hit);
            if !self.tracer.scene.materials[si.material as usize].is_emissive() {
                return Some(hit);
            }
            *ray = self.tracer.spawn.ray(&si.surface, ray.dir, ray.time);
            found = self.tracer.closest_hit(ray, false, None, stats);
        }
        None
    }

    /// The fraction of the light that meets a masked surface at `si`.
    fn opacity(&self, opacity: &MaskOpacity, si: &SurfaceInteraction, time: f32) -> f32 {
        match opacity {
            MaskOpacity::Constant(value) => *value,
            MaskOpacity::Texture(texture) => {
                let c = self.tracer.texture_color(texture, si, time);
                (c.x + c.y + c.z) / 3.0
            }
        }
    }

    /// The acceleration structure paths are traced with.
    pub fn accel(&self) -> &'a dyn Accel {
        self.tracer.accel
    }

    /// Traces one camera path. `first_hit`, when given, is the camera ray's closest hit as
    /// `self.accel().intersect(&camera_ray, ..)` returns it (e.g. from
    /// `Accel::intersect_batch`); it is not looked up again, and is counted as `intersect`
    /// would count it. `backdrop` is what the camera ray sees if it leaves the scene (else
    /// the environment or background, as for every ray).
    pub fn trace(
        &self,
        camera_ray: Ray,
        mut first_hit: Option<Option<Hit>>,
        backdrop: Option<Vec3>,
        stream: &mut SampleStream,
        stats: &mut RenderStats,
    ) -> PathSample {
        let mut result = PathSample::default();
        let mut ray = camera_ray;
        let mut throughput = Vec3::ONE;
        // The product of the (η_t/η_i)² of the refractions so far: `throughput * eta_scale`
        // is the path's energy, without the radiance compression inside glass that it
        // undoes on the way out (roulette judged by throughput alone kills paths inside
        // glass too often and multiplies the survivors by up to 2.25 on leaving, which
        // compounded into pixels of 1e11 on the course's glass box).
        let mut eta_scale = 1.0f32;
        // Camera rays and specular bounces see emission in full (nothing else sampled it).
        let mut specular_bounce = true;
        let mut pdf_bsdf = 0.0;
        // The shading point the current ray left from (for the light-sampling density).
        let mut from = Vec3::ZERO;
        // Beer's-law absorption of the medium the ray travels through.
        let mut absorption = Vec3::ZERO;
        let bounces = self.max_depth.max(1);
        // After the last bounce's scattering one more ray is traced, for the emission it
        // finds only: light sampling and BSDF sampling share every bounce by MIS, the last
        // included (Mitsuba's and pbrt's `max_depth` count so), which keeps glossy lobes
        // lit by large lights as quiet as anywhere else, and lets delta lobes (mirrors,
        // glass, a mask's holes) see the lights at all.
        for depth in 0..=bounces {
            if !ray.is_valid() {
                break;
            }
            let mut found = self.tracer.closest_hit(&ray, depth == 0, first_hit.take(), stats);
            if depth == 0 && self.tracer.scene.hide_emitters {
                found = self.past_emitters(&mut ray, found, stats);
            }
            let Some(hit) = found else {
                if let (0, Some(backdrop)) = (depth, backdrop) {
                    result.radiance += backdrop;
                    break;
                }
                if depth == 0 && self.tracer.scene.hide_emitters {
                    break;
                }
                let weight =
                    if specular_bounce { 1.0 } else { self.environment_weight(ray.dir, pdf_bsdf) };
                result.radiance += throughput * self.tracer.escaped(ray.dir) * weight;
                break;
            };
            if absorption != Vec3::ZERO {
                let distance = hit.t * ray.dir.length();
                throughput *= (-absorption * distance).exp();
            }
            let si = interaction(self.tracer.scene, &ray, &hit);
            let material = &self.tracer.scene.materials[si.material as usize];
            let unmapped = si.shading_normal;
            let mut si = self.tracer.with_normal_map(si, material, ray.time);
            let bump_shadowing = material.bump_shadowing && si.shading_normal != unmapped;
            if bump_shadowing && ray.dir.dot(si.shading_normal) >= 0.0 {
                // Mitsuba keeps the view above the mapped normal by mirroring it about the
                // unmapped one.
                let n = si.shading_normal;
                si.shading_normal = (2.0 * n.dot(unmapped) * unmapped - n).normalize();
            }
            if depth == 0 {
                result.depth = Some(hit.t);
                result.normal =
                    Some(self.tracer.scene.camera.world_from_render_rotation * si.shading_normal);
            }
            if material.is_emissive() && (si.front_face || material.two_sided_emission) {
                let weight =
                    if specular_bounce { 1.0 } else { self.emission_weight(from, &si, pdf_bsdf) };
                result.radiance += throughput * material.emission * weight;
            }
            if self.max_depth == 0 || depth == bounces {
                break;
            }
            let albedo = self.tracer.surface_albedo(material, &si, ray.time);
            let course_specular = match (&material.specular_texture, &material.phong) {
                (Some(t), Some(_)) => self.tracer.texture_color(t, &si, ray.time),
                (_, phong) => phong.as_ref().map_or(Vec3::ZERO, |p| p.specular),
            };
            let frame = if material.is_anisotropic() {
                self.tangent_frame(&si, ray.time)
            } else {
                self.shading_frame(si.shading_normal)
            };
            let roughness = material.roughness_textures.as_deref().map(|[u, v]| {
                let alpha = |t| self.tracer.texture_color(t, &si, ray.time).element_sum() / 3.0;
                (alpha(u), alpha(v))
            });
            let bsdf = match &material.principled {
                Some(principled) => {
                    let at = principled.at(albedo, |t| self.tracer.texture_color(t, &si, ray.time));
                    Bsdf::principled(&at, frame, si.front_face, material.one_sided)
                }
                None => Bsdf::with_reflectances(
                    material,
                    albedo,
                    course_specular,
                    roughness,
                    frame,
                    si.front_face,
                    self.energy,
                ),
            };
            let bsdf = match &material.opacity {
                None => bsdf,
                Some(opacity) => bsdf.with_opacity(self.opacity(opacity, &si, ray.time)),
            };
            let bsdf = if bump_shadowing { bsdf.with_bump_shadowing(unmapped) } else { bsdf };
            let wo = -ray.dir.normalize();
            if depth == 0 && self.tracer.first_hit_albedo {
                result.albedo = Some(bsdf.albedo_bound(wo).min(Vec3::ONE));
            }
            if bsdf.has_smooth_lobe() {
                let direct = self.direct_light(&si, &bsdf, wo, ray.time, stream, stats);
                result.radiance += throughput * direct;
            }
            // Direction first (the best stratified pair), then lobe and roulette.
            let [u0, u1, u_lobe, u_survive] = stream.next_4d();
            let u = Vec2::new(u0, u1);
            let Some(sample) = bsdf.sample(wo, u_lobe, u) else { break };
            // The geometric surface must agree with the shading normal about the side.
            let below = sample.wi.dot(si.surface.normal) < 0.0;
            if below != sample.transmitted || sample.weight == Vec3::ZERO {
                break;
            }
            debug_assert!(
                self.energy == Energy::Additive
                    || bsdf.albedo_bound(wo).max_element() <= 1.0 + 1e-4,
                "a BSDF that reflects more than it receives: {:?}",
                bsdf.albedo_bound(wo)
            );
            throughput *= sample.weight;
            eta_scale *= sample.eta_scale;
            specular_bounce = sample.delta;
            pdf_bsdf = sample.pdf;
            if sample.transmitted && !sample.passes {
                absorption = match material.specular {
                    crate::scene::Specular::Dielectric { absorption: a, .. } if si.front_face => a,
                    _ => Vec3::ZERO,
                };
            }
            if depth >= 3 {
                let survive = (throughput * eta_scale).max_element().min(0.95);
                if u_survive >= survive {
                    break;
                }
                throughput /= survive;
            }
            from = si.surface.point;
            ray = self.tracer.spawn.ray(&si.surface, sample.wi, ray.time);
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
