//! What a plain Lambertian bounce is computed from (`lambert`), gathered per path: the
//! hit, the path's throughput, and the light sample and random numbers the mixture BSDF's
//! code would draw, in the same order.

use super::PathTracer;
use super::bounce::PathState;
use super::lambert::lambert_bounce;
use super::lambert::{AREA, DISTANT, LONE, LambertLane, LambertOutcome, LaneSink, NEAR, POINT};
use super::lane_light::{
    BounceAt, TriangleHit, lone_draw, lone_draw_fields, with_hit_point, with_lone_light,
};
use super::lanes::{LONE_UNWRITTEN, POINT_UNWRITTEN};
use crate::sampling::SampleStream;
use crate::shading::spawn::SurfacePoint;
use crate::stats::RenderStats;
use glam::{Vec2, Vec3};

impl PathTracer<'_> {
    /// The plain Lambertian bounce of reflectance `diffuse` (after the energy model) at
    /// `at`, with the random numbers the mixture BSDF's would draw, in the same order:
    /// the light point's, then the direction's, written into `lane`. Sets what the bounce
    /// leaves as it is, whether the path goes on or not. A triangle hit's point is left to
    /// the lanes (`lane_light`), and with a lone emitter the light sample too; a light
    /// sample that needs the point (a spot's, one of several emitters') computes it here
    /// as well.
    pub(super) fn lambert_lane<At: BounceAt>(
        &self,
        state: &mut PathState,
        diffuse: Vec3,
        (at, shading_normal): (At, Vec3),
        stream: &mut SampleStream,
        lane: &mut impl LaneSink,
    ) {
        if state.depth == 0 && self.tracer.first_hit_albedo {
            // As `albedo_bound` has it (a -0 channel reads +0).
            state.result.albedo = Some((diffuse + Vec3::ZERO).min(Vec3::ONE));
        }
        let surface = (diffuse, shading_normal);
        // The columns the lanes set themselves are not written.
        let point_unwritten = if At::POINT_LEFT_TO_LANES { POINT_UNWRITTEN } else { 0 };
        let (light, direction_draw, light_unwritten) = match self.lone_emitter {
            // Both draws made first (the light's, then the direction's, as `light_sample`
            // and the mixture BSDF draw them), so that no light field is held across a
            // draw: a draw may call out of line, around which every live register was
            // spilled to the stack (a Cornell box render's bounces spent 40 instructions
            // each on that).
            Some(_) => {
                let light_draw = stream.next_4d();
                let direction_draw = stream.next_4d();
                (LaneLight::lone(light_draw), direction_draw, LONE_UNWRITTEN)
            }
            None => {
                let light = self.light_sample(&at, state.ray.dir, stream);
                (light, stream.next_4d(), 0)
            }
        };
        lane.put(
            self.lane_record(state, at.lane_fields(), surface, light, direction_draw),
            point_unwritten | light_unwritten,
        );
        state.direct_weight = Some(state.throughput);
    }

    /// The lane of `lambert_lane`, from where its bounce is (`BounceAt::lane_fields`), its
    /// surface's reflectance and shading normal, its light and its direction's draw: every
    /// field named, none set twice, and the lane written once, where it goes.
    #[inline(always)]
    fn lane_record(
        &self,
        state: &PathState,
        (surface, hit, on_triangle): (SurfacePoint, TriangleHit, f32),
        (diffuse, shading_normal): (Vec3, Vec3),
        light: LaneLight,
        [u0, u1, _, u_survive]: [f32; 4],
    ) -> LambertLane {
        let [hit_v0, hit_v1, hit_v2] = hit.triangle;
        LambertLane {
            dir: state.ray.dir,
            point: surface.point,
            error: surface.error,
            normal: surface.normal,
            hit_v0,
            hit_v1,
            hit_v2,
            hit_origin: hit.origin,
            shading_normal,
            diffuse,
            throughput: state.throughput,
            eta_scale: state.eta_scale,
            has_light: light.has_light,
            light_kind: light.kind,
            light_point: light.point,
            light_error: light.error,
            light_normal: light.normal,
            emission: light.emission,
            light_pdf: light.pdf,
            light_visible: light.visible,
            light_two_sided: light.two_sided,
            u0,
            u1,
            u_survive,
            roulette: if state.depth + 1 >= self.rr_depth { 1.0 } else { 0.0 },
            on_triangle,
            hit_b1: hit.barycentrics.0,
            hit_b2: hit.barycentrics.1,
            hit_t: hit.t,
            hit_tilt: hit.tilt,
            hit_edge_tilt: hit.edge_tilt,
        }
    }

    /// The outcome of the bounce `lambert_lane` wrote into `lane`, one lane at a time: its
    /// point and light sampled first where they were left to the lanes (`lane_light`),
    /// with the light of a `NEAR` lane, which the lanes leave to this.
    pub(crate) fn lambert_outcome(
        &self,
        lane: &LambertLane,
        stats: &mut RenderStats,
    ) -> LambertOutcome {
        let Some(emitter) = &self.lone_emitter else {
            return lambert_bounce(&with_hit_point(lane), &self.spaces);
        };
        let lane = with_lone_light(&with_hit_point(lane), &emitter.sampler);
        if lane.light_kind != NEAR {
            return lambert_bounce(&lane, &self.spaces);
        }
        stats.bounces.near_lights += 1;
        let light = self.emitter_sample(lane.point, lone_draw(&lane));
        lambert_bounce(&light.lighting(&lane), &self.spaces)
    }

    /// The light sample of a plain Lambertian bounce at `at`, hit by a ray of direction
    /// `dir`, from the scene's one light (`PathTracer::lambert_lanes`), as `direct_light`
    /// samples it, where it is not a lone emitter (whose light the lanes sample:
    /// `lane_light`). Only a spot or projector, or one of several emitters, needs the point.
    #[inline(always)]
    fn light_sample(&self, at: &impl BounceAt, dir: Vec3, stream: &mut SampleStream) -> LaneLight {
        let lights = &self.tracer.scene.lights;
        if let Some(light) = lights.points.first() {
            // An isotropic light's intensity is `intensity_towards`'s every way.
            let emission = if light.is_isotropic() {
                light.intensity
            } else {
                let to_light = light.position - at.resolve(dir).point;
                let wi = to_light / to_light.length_squared().sqrt();
                light.intensity_towards(-wi)
            };
            return LaneLight {
                has_light: 1.0,
                kind: POINT,
                point: light.position,
                emission,
                ..LaneLight::NONE
            };
        }
        if let Some(light) = lights.directional.first() {
            return LaneLight {
                has_light: 1.0,
                kind: DISTANT,
                point: -light.direction,
                emission: light.irradiance,
                pdf: 1.0,
                ..LaneLight::NONE
            };
        }
        if lights.has_emitters() {
            return self.emitter_sample(at.resolve(dir).point, stream.next_4d());
        }
        match lights.environment.as_ref().filter(|e| e.is_lit()) {
            Some(environment) => match environment.sample(stream.next_2d()) {
                Some(sample) => LaneLight {
                    has_light: 1.0,
                    kind: DISTANT,
                    point: sample.wi,
                    emission: sample.radiance,
                    pdf: sample.pdf,
                    visible: 1.0,
                    ..LaneLight::NONE
                },
                None => LaneLight::NONE,
            },
            None => LaneLight::NONE,
        }
    }
}

impl PathTracer<'_> {
    /// `light_sample` from the scene's emitters, from the light's draw.
    #[inline(always)]
    fn emitter_sample(&self, point: Vec3, [u0, u1, u2, u3]: [f32; 4]) -> LaneLight {
        // The point takes the draw's best stratified pair.
        let (u_choice, u_point) = (Vec2::new(u2, u3), Vec2::new(u0, u1));
        let Some(light) = self.tracer.scene.lights.sample_emitter(point, u_choice, u_point) else {
            return LaneLight::NONE;
        };
        LaneLight {
            has_light: 1.0,
            kind: AREA,
            point: light.point,
            error: light.error,
            normal: light.normal,
            emission: light.emission,
            pdf: light.pdf,
            visible: if light.visible { 1.0 } else { 0.0 },
            two_sided: if light.two_sided { 1.0 } else { 0.0 },
        }
    }
}

/// The light fields of a `LambertLane` (see there).
struct LaneLight {
    has_light: f32,
    kind: f32,
    point: Vec3,
    error: Vec3,
    normal: Vec3,
    emission: Vec3,
    pdf: f32,
    visible: f32,
    two_sided: f32,
}

impl LaneLight {
    /// The lone emitter's light, left to the lanes (`LONE`), from the light's draw.
    fn lone(draw: [f32; 4]) -> LaneLight {
        let (point, normal) = lone_draw_fields(draw);
        LaneLight { kind: LONE, point, normal, ..LaneLight::NONE }
    }

    /// `lane` lit by this light instead.
    fn lighting(&self, lane: &LambertLane) -> LambertLane {
        LambertLane {
            has_light: self.has_light,
            light_kind: self.kind,
            light_point: self.point,
            light_error: self.error,
            light_normal: self.normal,
            emission: self.emission,
            light_pdf: self.pdf,
            light_visible: self.visible,
            light_two_sided: self.two_sided,
            ..*lane
        }
    }

    /// No light sampled.
    const NONE: LaneLight = LaneLight {
        has_light: 0.0,
        kind: AREA,
        point: Vec3::ZERO,
        error: Vec3::ZERO,
        normal: Vec3::ZERO,
        emission: Vec3::ZERO,
        pdf: 0.0,
        visible: 0.0,
        two_sided: 0.0,
    };
}
