//! Path tracing with next-event estimation and multiple importance sampling (power
//! heuristic): at every non-specular hit, one shadow ray per point/directional light,
//! `light_samples` to points sampled on emitters and `light_samples` towards the
//! environment; then the BSDF picks the next direction, the last bounce included (one more
//! ray then collects only the emission it finds, MIS-weighted: `light_sampling`).
//! Only the random dimensions the scene's effects call for are drawn.

mod bounce;
mod lambert;
mod lambert_draws;
mod lane_light;
mod lanes;
mod light_sampling;
mod plain_hit;
mod scattering;
mod wavefront;

pub(crate) use bounce::{PathState, ShadowSink};
pub(crate) use wavefront::Wavefront;

use super::trace::SceneTracer;
use crate::accel::Accel;
use crate::light::LoneEmitter;
use crate::ray::{Hit, Ray};
use crate::render_scene::RenderScene;
use crate::sampling::frame_from_normal;
use crate::shading::bsdf::Energy;
use crate::shading::material::MaskOpacity;
use crate::shading::spawn::SpawnMode;
use crate::shading::surface::{SurfaceInteraction, interaction};
use crate::stats::RenderStats;
use glam::{Mat3, Quat, Vec3};
use lambert::FrameSpaces;
use plain_hit::PlainSurfaces;

pub struct PathTracer<'a> {
    tracer: SceneTracer<'a>,
    /// Number of surface interactions that gather light (1 = direct lighting only).
    max_depth: u32,
    /// The interaction (from 1) from which Russian roulette may end a path.
    rr_depth: u32,
    /// Shadow rays to emitters per shading point.
    light_samples: u32,
    /// Rotation into the space where directions are sampled (see `sampling_from_world`)
    /// and back: every hit's frame goes through both.
    spaces: FrameSpaces,
    energy: Energy,
    /// Whether plain Lambertian bounces may take the lane path (`lambert`): a bounce
    /// samples one light at most (emitters or the environment with one sample, or a single
    /// point or directional light), and rays leave surfaces robustly.
    lambert_lanes: bool,
    /// The scene's one flat emitter, whose area samples the lanes make (`LoneEmitter`).
    /// Boxed: it is larger than the rest of the tracer.
    lone_emitter: Option<Box<LoneEmitter>>,
    /// The instances whose hits go straight to their Lambertian lane (`plain_hit`); none
    /// without the lanes.
    plain_surfaces: PlainSurfaces<'a>,
    /// Whether a ray can find light where it hits or leaves the scene (an emissive surface,
    /// an environment, a background): if not, the ray after the last bounce, which looks
    /// for nothing else, is not traced.
    rays_find_light: bool,
}

/// How far from 1 a squared normal length may be for the normal to count as unit: 16 ulps,
/// above a normalised and rotated vector's rounding; the frame built from it is then
/// orthonormal to about a millionth.
const UNIT_TOLERANCE: f32 = 2e-6;

/// `v` normalised, where it is not unit already. Shading normals arrive unit to a few ulps
/// and a rotation keeps them so: only one off by more is normalised again (a square root and
/// a division on every hit's critical path, for a change in the seventh digit).
fn near_unit(v: Vec3) -> Vec3 {
    if (v.length_squared() - 1.0).abs() <= UNIT_TOLERANCE { v } else { v.normalize() }
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

/// Local shading frame (normal = +Z) → render space, built in the world-fixed sampling
/// space.
#[inline(always)]
pub(super) fn shading_frame_in(spaces: &FrameSpaces, normal: Vec3) -> Mat3 {
    let n = near_unit(spaces.sampling_from_render * normal);
    spaces.render_from_sampling * frame_from_normal(n)
}

impl<'a> PathTracer<'a> {
    pub(crate) fn new(
        tracer: SceneTracer<'a>,
        max_depth: u32,
        rr_depth: u32,
        light_samples: u32,
        energy: Energy,
        lambertian_lanes: bool,
    ) -> Self {
        let sampling_from_render =
            sampling_from_world() * tracer.scene.camera.world_from_render_rotation;
        let light_samples = light_samples.max(1);
        let lights = &tracer.scene.lights;
        let lit_environment = lights.environment.as_ref().is_some_and(|e| e.is_lit());
        let shadow_rays = lights.points.len()
            + lights.directional.len()
            + lights.has_emitters() as usize
            + lit_environment as usize;
        let lambert_lanes = lambertian_lanes
            && light_samples == 1
            && shadow_rays <= 1
            && tracer.spawn == SpawnMode::Robust;
        let spaces = FrameSpaces {
            sampling_from_render,
            render_from_sampling: sampling_from_render.transpose(),
            shading_sides: tracer.scene.sides == crate::scene::Sides::Shading,
        };
        let lone_emitter = lights.lone_emitter().filter(|_| lambert_lanes).map(Box::new);
        let plain_surfaces = match lambert_lanes {
            true => PlainSurfaces::new(tracer.scene, energy),
            false => PlainSurfaces::default(),
        };
        let scene = tracer.scene;
        let rays_find_light = lights.environment.is_some()
            || scene.background != Vec3::ZERO
            || lights.has_emitters()
            || scene.materials.iter().any(|m| m.is_emissive());
        PathTracer {
            tracer,
            max_depth,
            rr_depth,
            light_samples,
            spaces,
            energy,
            lambert_lanes,
            lone_emitter,
            plain_surfaces,
            rays_find_light,
        }
    }

    pub fn scene(&self) -> &RenderScene {
        self.tracer.scene
    }

    fn occluded(&self, ray: &Ray, stats: &mut RenderStats) -> bool {
        self.tracer.occluded(ray, stats)
    }

    /// The shading frame at `normal` (`shading_frame_in`).
    fn shading_frame(&self, normal: Vec3) -> Mat3 {
        shading_frame_in(&self.spaces, normal)
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
            found = self.tracer.closest_hit(ray, false, stats);
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
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normals_off_unit_length_are_normalised_and_unit_ones_kept() {
        let unit = Vec3::new(0.3, -0.8, 0.1).normalize();
        assert_eq!(near_unit(unit), unit);
        for scale in [0.5, 0.999, 1.001, 3.0] {
            let n = near_unit(unit * scale);
            assert!((n.length() - 1.0).abs() < 1e-6 && (n - unit).length() < 1e-6, "{scale}");
        }
        // At the tolerance the frame is still orthonormal to about a millionth.
        let f = frame_from_normal(near_unit(unit * (1.0 + 0.49 * UNIT_TOLERANCE)));
        let lengths = [f.x_axis, f.y_axis, f.z_axis].map(|a| (a.length() - 1.0).abs());
        let dots = [f.x_axis.dot(f.y_axis), f.y_axis.dot(f.z_axis), f.z_axis.dot(f.x_axis)];
        assert!(lengths.iter().chain(&dots.map(f32::abs)).all(|e| *e < 2e-6));
    }

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
