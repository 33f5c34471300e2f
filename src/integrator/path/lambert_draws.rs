//! What a plain Lambertian bounce is computed from (`lambert`), gathered per path: the
//! hit, the path's throughput, and the light sample and random numbers the mixture BSDF's
//! code would draw, in the same order.

use super::PathTracer;
use super::bounce::PathState;
use super::lambert::{BY_AREA, DISTANT, LambertLane, POINT};
use crate::sampling::SampleStream;
use crate::shading::spawn::SurfacePoint;
use glam::{Vec2, Vec3};

impl PathTracer<'_> {
    /// The plain Lambertian bounce of reflectance `diffuse` (after the energy model) at
    /// `surface`, with the random numbers the mixture BSDF's would draw, in the same order:
    /// the light point's, then the direction's, written into `lane`. Sets what the bounce
    /// leaves as it is, whether the path goes on or not.
    pub(super) fn lambert_lane(
        &self,
        state: &mut PathState,
        diffuse: Vec3,
        (surface, shading_normal): (&SurfacePoint, Vec3),
        stream: &mut SampleStream,
        lane: &mut LambertLane,
    ) {
        let ray = &state.ray;
        if state.depth == 0 && self.tracer.first_hit_albedo {
            // As `albedo_bound` has it (a -0 channel reads +0).
            state.result.albedo = Some((diffuse + Vec3::ZERO).min(Vec3::ONE));
        }
        *lane = LambertLane {
            dir: ray.dir,
            point: surface.point,
            error: surface.error,
            normal: surface.normal,
            shading_normal,
            diffuse,
            throughput: state.throughput,
            eta_scale: state.eta_scale,
            roulette: if state.depth + 1 >= self.rr_depth { 1.0 } else { 0.0 },
            ..LambertLane::default()
        };
        // The scene's one light (`PathTracer::lambert_lanes`), sampled as `direct_light`
        // samples it.
        let lights = &self.tracer.scene.lights;
        if let Some(light) = lights.points.first() {
            let to_light = light.position - lane.point;
            let wi = to_light / to_light.length_squared().sqrt();
            lane.has_light = 1.0;
            lane.light_kind = POINT;
            lane.light_point = light.position;
            lane.emission = light.intensity_towards(-wi);
        } else if let Some(light) = lights.directional.first() {
            lane.has_light = 1.0;
            lane.light_kind = DISTANT;
            lane.light_point = -light.direction;
            lane.emission = light.irradiance;
            lane.light_pdf = 1.0;
        } else if lights.has_emitters() {
            // The point takes the draw's best stratified pair.
            let [u0, u1, u2, u3] = stream.next_4d();
            let (u_choice, u_point) = (Vec2::new(u2, u3), Vec2::new(u0, u1));
            if self.lone_emitter.as_ref().is_some_and(|e| e.by_area(lane.point)) {
                // Left for the lanes to sample (`with_light_point`).
                lane.light_kind = BY_AREA;
                lane.light_point = Vec3::new(u0, u1, 0.0);
            } else if let Some(light) = lights.sample_emitter(lane.point, u_choice, u_point) {
                lane.has_light = 1.0;
                lane.light_point = light.point;
                lane.light_error = light.error;
                lane.light_normal = light.normal;
                lane.emission = light.emission;
                lane.light_pdf = light.pdf;
                lane.light_visible = if light.visible { 1.0 } else { 0.0 };
                lane.light_two_sided = if light.two_sided { 1.0 } else { 0.0 };
            }
        } else if let Some(environment) = lights.environment.as_ref().filter(|e| e.is_lit()) {
            if let Some(sample) = environment.sample(stream.next_2d()) {
                lane.has_light = 1.0;
                lane.light_kind = DISTANT;
                lane.light_point = sample.wi;
                lane.emission = sample.radiance;
                lane.light_pdf = sample.pdf;
                lane.light_visible = 1.0;
            }
        }
        [lane.u0, lane.u1, _, lane.u_survive] = stream.next_4d();
        state.direct_weight = Some(state.throughput);
        state.from = surface.point;
    }
}
