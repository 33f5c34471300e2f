//! One path as a state that advances a bounce at a time: the closest hit of its ray is
//! found by the caller (one ray, or a packet of many paths' rays), `on_hit` shades it,
//! hands its shadow rays to a [`ShadowSink`] and picks the next ray. The scalar integrator
//! (`PathTracer::trace`) and the batched one (`Wavefront`) run this same code per path, so
//! they give the same image bit for bit.

use super::PathTracer;
use super::lambert::{LambertLane, LaneSink};
use super::lanes::OutcomeFields;
use crate::integrator::PathSample;
use crate::ray::{Hit, Ray};
use crate::sampling::SampleStream;
use crate::shading::bsdf::Energy;
use crate::shading::surface::interaction;
use crate::stats::RenderStats;
use glam::{Vec2, Vec3};

/// Where a bounce's shadow rays go: traced at once (scalar) or queued for one batched
/// occlusion query over many paths.
pub(crate) trait ShadowSink {
    /// A shadow ray along which `contribution` (light times BSDF, over its density) reaches
    /// the shading point unless something blocks it.
    fn shadow(&mut self, ray: Ray, contribution: Vec3, stats: &mut RenderStats);

    /// `shadow` for a ray known to be valid (`Ray::is_valid`), which need not be tested
    /// again.
    #[inline]
    fn valid_shadow(&mut self, ray: Ray, contribution: Vec3, stats: &mut RenderStats) {
        self.shadow(ray, contribution, stats);
    }
}

/// A path between bounces.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PathState {
    /// The ray to trace next.
    pub(super) ray: Ray,
    pub(super) throughput: Vec3,
    /// The product of the (η_t/η_i)² of the refractions so far: `throughput * eta_scale`
    /// is the path's energy, without the radiance compression inside glass that it
    /// undoes on the way out (roulette judged by throughput alone kills paths inside
    /// glass too often and multiplies the survivors by up to 2.25 on leaving, which
    /// compounded into pixels of 1e11 on the course's glass box).
    pub(super) eta_scale: f32,
    /// Camera rays and specular bounces see emission in full (nothing else sampled it).
    specular_bounce: bool,
    pdf_bsdf: f32,
    /// The shading point the current ray left from (for the light-sampling density).
    pub(super) from: Vec3,
    /// Beer's-law absorption of the medium the ray travels through.
    absorption: Vec3,
    /// The surface interaction the next hit is (0: the camera ray's).
    pub(super) depth: u32,
    /// Whether the path goes on: `ray` is valid (`Ray::is_valid`, tested as the ray is
    /// set) and within the depth.
    live: bool,
    /// What the camera ray sees if it leaves the scene, if the scene has a backdrop.
    backdrop: Option<Vec3>,
    /// The throughput the light of this bounce's shadow rays is scaled by, while they are
    /// pending.
    pub(super) direct_weight: Option<Vec3>,
    pub result: PathSample,
}

impl PathState {
    /// The ray whose closest hit the path waits for, if it goes on.
    #[inline]
    pub fn pending_ray(&self) -> Option<&Ray> {
        self.live.then_some(&self.ray)
    }

    /// Whether the ray `pending_ray` gives is a camera ray.
    pub fn at_camera(&self) -> bool {
        self.depth == 0
    }

    /// Adds the light of this bounce's unblocked shadow rays, `direct` (their contributions
    /// summed in the order they were handed to the sink).
    #[inline]
    pub fn finish_direct(&mut self, direct: Vec3) {
        if let Some(weight) = self.direct_weight.take() {
            self.result.radiance += weight * direct;
        }
    }
}

/// Traces shadow rays as they come and sums the light of those that are not blocked.
struct ImmediateShadows<'p, 'a> {
    path: &'p PathTracer<'a>,
    direct: Vec3,
}

impl ShadowSink for ImmediateShadows<'_, '_> {
    fn shadow(&mut self, ray: Ray, contribution: Vec3, stats: &mut RenderStats) {
        if !self.path.occluded(&ray, stats) {
            self.direct += contribution;
        }
    }
}

impl PathTracer<'_> {
    /// A path that starts with `camera_ray`; `backdrop` is what it sees if it leaves the
    /// scene (else the environment or background, as for every ray).
    pub(crate) fn start(&self, camera_ray: Ray, backdrop: Option<Vec3>) -> PathState {
        PathState {
            ray: camera_ray,
            throughput: Vec3::ONE,
            eta_scale: 1.0,
            specular_bounce: true,
            pdf_bsdf: 0.0,
            from: Vec3::ZERO,
            absorption: Vec3::ZERO,
            depth: 0,
            live: camera_ray.is_valid(),
            backdrop,
            direct_weight: None,
            result: PathSample::default(),
        }
    }

    /// Traces one camera path, one ray at a time: the reference the batched integrator
    /// (`Wavefront`) is compared with, and what single samples use.
    pub fn trace(
        &self,
        camera_ray: Ray,
        backdrop: Option<Vec3>,
        stream: &mut SampleStream,
        stats: &mut RenderStats,
    ) -> PathSample {
        let mut state = self.start(camera_ray, backdrop);
        let mut lane = LambertLane::default();
        while let Some(&ray) = state.pending_ray() {
            let found = self.tracer.closest_hit(&ray, state.at_camera(), stats);
            let mut shadows = ImmediateShadows { path: self, direct: Vec3::ZERO };
            if self.on_hit(&mut state, found, stream, stats, &mut shadows, &mut lane) {
                let outcome = self.lambert_outcome(&lane, stats);
                self.finish_lambert(&mut state, &outcome, &mut shadows, stats);
            }
            state.finish_direct(shadows.direct);
        }
        state.result
    }

    /// Advances `state` past the closest hit of its pending ray, `found` (counted by the
    /// caller): adds the emission it sees, hands the shadow rays of next-event estimation to
    /// `shadows`, and samples the next ray or ends the path.
    ///
    /// After the last bounce's scattering one more ray is traced, for the emission it finds
    /// only: light sampling and BSDF sampling share every bounce by MIS, the last included
    /// (Mitsuba's and pbrt's `max_depth` count so), which keeps glossy lobes lit by large
    /// lights as quiet as anywhere else, and lets delta lobes (mirrors, glass, a mask's
    /// holes) see the lights at all. Where no ray can find light (point and directional
    /// lights only, no environment or background), that ray is not traced.
    ///
    /// A plain Lambertian bounce is left to the caller (`true`), written into `lane` with
    /// its random numbers drawn: `lambert_outcome` computes it (or `LambertLanes`, with many
    /// paths'), `finish_lambert` applies it. Handed
    /// to `lane`, not returned: the lane is large, and a `LaneSink` writes it once where it
    /// goes (copies of it cost a Cornell box render 2 % of its instructions).
    pub(crate) fn on_hit(
        &self,
        state: &mut PathState,
        found: Option<Hit>,
        stream: &mut SampleStream,
        stats: &mut RenderStats,
        shadows: &mut impl ShadowSink,
        lane: &mut impl LaneSink,
    ) -> bool {
        state.live = false;
        match self.scatter(state, found, stream, stats, shadows, lane) {
            Scattered::End => false,
            Scattered::Ray(next) => {
                self.advance(state, next);
                false
            }
            Scattered::Lambert => true,
        }
    }

    /// Records the camera ray's hit in the sample's AOVs: its distance and its shading
    /// normal in world space.
    #[inline]
    pub(super) fn record_first_hit(&self, result: &mut PathSample, t: f32, shading_normal: Vec3) {
        result.depth = Some(t);
        let world_from_render = self.tracer.scene.camera.world_from_render_rotation;
        result.normal = Some(world_from_render * shading_normal);
    }

    /// Whether a path ends at surface interaction `depth` without scattering: its emission
    /// counts, nothing after it.
    #[inline]
    pub(super) fn ends_at(&self, depth: u32) -> bool {
        self.max_depth == 0 || depth == self.max_depth.max(1)
    }

    /// Whether the ray to surface interaction `depth` (the camera's: 0) is traced: up to the
    /// last, which looks only for light, and which is not traced where no ray finds any.
    #[inline]
    fn traces_ray(&self, depth: u32) -> bool {
        let last = self.max_depth.max(1);
        depth < last || (depth == last && self.rays_find_light)
    }

    /// The path goes on along `next`, if it is valid (an invalid ray ends it, uncounted).
    #[inline]
    fn advance(&self, state: &mut PathState, next: Ray) {
        self.advance_valid(state, next, next.is_valid());
    }

    /// `advance` along `next`, whose validity (`Ray::is_valid`) is `valid`: the lanes test
    /// theirs together.
    #[inline]
    fn advance_valid(&self, state: &mut PathState, next: Ray, valid: bool) {
        debug_assert_eq!(valid, next.is_valid(), "{next:?}");
        state.depth += 1;
        state.live = valid & self.traces_ray(state.depth);
        state.ray = next;
    }

    /// Applies the outcome of the plain Lambertian bounce `on_hit` left to the caller: its
    /// shadow ray to `shadows`, and the next ray if the path goes on. (What it reads, and
    /// when, is what `lanes_unwritten_tests.rs` compares.)
    pub(crate) fn finish_lambert(
        &self,
        state: &mut PathState,
        outcome: &impl OutcomeFields,
        shadows: &mut impl ShadowSink,
        stats: &mut RenderStats,
    ) {
        let time = state.ray.time;
        state.from = outcome.point();
        if outcome.shadow() != 0.0 {
            let (origin, dir, tmax) =
                (outcome.shadow_origin(), outcome.shadow_dir(), outcome.shadow_tmax());
            let ray = Ray { origin, dir, tmin: 0.0, tmax, time };
            shadows.valid_shadow(ray, outcome.contribution(), stats);
        }
        if outcome.next() != 0.0 {
            state.throughput = outcome.throughput();
            state.specular_bounce = false;
            state.pdf_bsdf = outcome.pdf();
            let (origin, dir) = (outcome.next_origin(), outcome.next_dir());
            let next = Ray { origin, dir, tmin: 0.0, tmax: f32::INFINITY, time };
            self.advance_valid(state, next, true);
        }
    }

    /// The work of `on_hit`.
    fn scatter(
        &self,
        state: &mut PathState,
        mut found: Option<Hit>,
        stream: &mut SampleStream,
        stats: &mut RenderStats,
        shadows: &mut impl ShadowSink,
        lane: &mut impl LaneSink,
    ) -> Scattered {
        let depth = state.depth;
        let scene = self.tracer.scene;
        if depth == 0 && scene.hide_emitters {
            found = self.past_emitters(&mut state.ray, found, stats);
        }
        let Some(hit) = found else {
            let (ray, result) = (&state.ray, &mut state.result);
            if let (0, Some(backdrop)) = (depth, state.backdrop) {
                result.radiance += backdrop;
                return Scattered::End;
            }
            if depth == 0 && scene.hide_emitters {
                return Scattered::End;
            }
            let weight = if state.specular_bounce {
                1.0
            } else {
                self.environment_weight(ray.dir, state.pdf_bsdf)
            };
            result.radiance += state.throughput * self.tracer.escaped(ray.dir) * weight;
            return Scattered::End;
        };
        if state.absorption != Vec3::ZERO {
            let distance = hit.t * state.ray.dir.length();
            state.throughput *= (-state.absorption * distance).exp();
        }
        if let Some(plain) = self.plain_surfaces.get(hit.geom_id)
            && let Some(scattered) = self.plain_hit(state, (&hit, plain), stream, stats, lane)
        {
            return scattered;
        }
        // Copied only here: the plain hits, most of a render's, read it in place.
        let ray = state.ray;
        let result = &mut state.result;
        let mut si = interaction(scene, &ray, &hit);
        let material = &scene.materials[si.material as usize];
        let unmapped = si.shading_normal;
        self.tracer.map_normal(&mut si, material, ray.time);
        let bump_shadowing = material.bump_shadowing && si.shading_normal != unmapped;
        if bump_shadowing && ray.dir.dot(si.shading_normal) >= 0.0 {
            // Mitsuba keeps the view above the mapped normal by mirroring it about the
            // unmapped one.
            let n = si.shading_normal;
            si.shading_normal = (2.0 * n.dot(unmapped) * unmapped - n).normalize();
        }
        if depth == 0 {
            self.record_first_hit(result, hit.t, si.shading_normal);
        }
        if material.is_emissive() && (si.front_face || material.two_sided_emission) {
            let weight = if state.specular_bounce {
                1.0
            } else {
                self.emission_weight(state.from, &si, state.pdf_bsdf)
            };
            result.radiance += state.throughput * material.emission_at(si.uv) * weight;
        }
        if self.ends_at(depth) {
            return Scattered::End;
        }
        if self.lambert_lanes
            && material.is_plain_lambertian()
            && !bump_shadowing
            && (si.front_face || !material.one_sided)
        {
            stats.bounces.lanes += 1;
            let albedo = self.tracer.surface_albedo(material, &si, ray.time);
            let diffuse = self.energy.lambertian(albedo);
            self.lambert_lane(state, diffuse, (si.surface, si.shading_normal), stream, lane);
            return Scattered::Lambert;
        }
        stats.bounces.scalar += 1;
        let mut bsdf = self.scattering(material, &si, ray.time);
        if bump_shadowing {
            bsdf.set_bump_shadowing(unmapped);
        }
        let wo = -ray.dir.normalize();
        if depth == 0 && self.tracer.first_hit_albedo {
            result.albedo = Some(bsdf.albedo_bound(wo).min(Vec3::ONE));
        }
        if bsdf.has_smooth_lobe() {
            state.direct_weight = Some(state.throughput);
            self.direct_light(&si, &bsdf, wo, ray.time, stream, stats, shadows);
        }
        if !self.traces_ray(depth + 1) {
            return Scattered::End;
        }
        // Direction first (the best stratified pair), then lobe and roulette.
        let [u0, u1, u_lobe, u_survive] = stream.next_4d();
        let Some(sample) = bsdf.sample(wo, u_lobe, Vec2::new(u0, u1)) else {
            return Scattered::End;
        };
        // The geometric surface must agree with the shading normal about the side, unless
        // the shading normal alone decides (`Sides::Shading`).
        let below = sample.wi.dot(si.surface.normal) < 0.0;
        let disagree = below != sample.transmitted && !self.spaces.shading_sides;
        if disagree || sample.weight == Vec3::ZERO {
            return Scattered::End;
        }
        debug_assert!(
            self.energy == Energy::Additive || bsdf.albedo_bound(wo).max_element() <= 1.0 + 1e-4,
            "a BSDF that reflects more than it receives: {:?}",
            bsdf.albedo_bound(wo)
        );
        state.throughput *= sample.weight;
        state.eta_scale *= sample.eta_scale;
        state.specular_bounce = sample.delta;
        state.pdf_bsdf = sample.pdf;
        if sample.transmitted && !sample.passes {
            state.absorption = match material.specular {
                crate::scene::Specular::Dielectric { absorption: a, .. } if si.front_face => a,
                _ => Vec3::ZERO,
            };
        }
        if depth + 1 >= self.rr_depth {
            let survive = (state.throughput * state.eta_scale).max_element().min(0.95);
            if u_survive >= survive {
                return Scattered::End;
            }
            state.throughput /= survive;
        }
        state.from = si.surface.point;
        Scattered::Ray(self.tracer.spawn.ray(&si.surface, sample.wi, ray.time))
    }
}

/// What `scatter` leaves: the path's end, its next ray, or a plain Lambertian bounce (in
/// the lane it was given) for the caller to compute.
pub(super) enum Scattered {
    End,
    Ray(Ray),
    Lambert,
}
