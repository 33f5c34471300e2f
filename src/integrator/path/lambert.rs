//! One bounce at a plain Lambertian surface (no other lobe, mask, blend or bump shadowing)
//! in a scene with one light to sample (emitters, a point or directional light, or the
//! environment), once its random numbers are drawn, its point known and its light sampled
//! (a triangle hit's point, and a lone emitter's light, are computed by the lanes first:
//! `lane_light`): the shadow ray and the light it brings, the next direction, the
//! throughput and Russian roulette. Written as straight-line arithmetic over one lane with
//! selects for its conditions, so that a loop over many lanes (`lanes`) vectorises; the scalar integrator
//! calls the same function, and both give the mixture BSDF's results bit for bit (the same
//! operations in the same order: `tests` compares them).

use super::light_sampling::power_heuristic;
use crate::lane_select::{select, select3};
use crate::ray::Ray;
use crate::shading::spawn::{SHADOW_TMAX, SurfacePoint};
use glam::{Mat3, Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// What a plain Lambertian bounce is computed from.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct LambertLane {
    /// Direction of the ray that hit.
    pub dir: Vec3,
    /// The hit point, its error bound and its geometric normal (facing the ray). Where
    /// `on_triangle` is not 0, the point and bound are still to be computed
    /// (`with_hit_point`) from the triangle hit in the `hit_` fields.
    pub point: Vec3,
    pub error: Vec3,
    pub normal: Vec3,
    /// The triangle's vertices, and the origin of the ray that hit it.
    pub hit_v0: Vec3,
    pub hit_v1: Vec3,
    pub hit_v2: Vec3,
    pub hit_origin: Vec3,
    pub shading_normal: Vec3,
    /// The Lambertian reflectance (after the energy model's clamp).
    pub diffuse: Vec3,
    pub throughput: Vec3,
    pub eta_scale: f32,
    /// 1 where a light was sampled, else 0.
    pub has_light: f32,
    /// What was sampled: `AREA` (a point on an emitter), `POINT` (a point light) or
    /// `DISTANT` (a direction: the environment, or a directional light); or what is still
    /// to be: `LONE` or `NEAR` (the lone emitter's light, whose draw `light_point` and
    /// `light_normal` then hold).
    pub light_kind: f32,
    /// The light point sampled, or the direction towards a distant light.
    pub light_point: Vec3,
    pub light_error: Vec3,
    pub light_normal: Vec3,
    pub emission: Vec3,
    pub light_pdf: f32,
    /// 1 where BSDF sampling can find the emitter too (MIS), else 0.
    pub light_visible: f32,
    /// 1 where the emitter sends light from both sides, else 0.
    pub light_two_sided: f32,
    /// The direction's stratified pair, and the roulette's number.
    pub u0: f32,
    pub u1: f32,
    pub u_survive: f32,
    /// 1 where Russian roulette may end the path at this bounce, else 0.
    pub roulette: f32,
    /// Where the point is to be computed from the triangle hit, 1 if `normal` is the
    /// triangle's own and -1 if it is its opposite (the back was hit), else 0: the lanes
    /// take the triangle's own normal back exactly, signed zeros included.
    pub on_triangle: f32,
    /// The hit's barycentrics and distance, and its triangle plane's `tilt` and `edge_tilt`.
    pub hit_b1: f32,
    pub hit_b2: f32,
    pub hit_t: f32,
    pub hit_tilt: f32,
    pub hit_edge_tilt: f32,
}

/// Where a path writes its plain Lambertian bounce: a lane of its own (one path at a time),
/// or straight into its column position among the lanes computed together
/// (`LambertLanes::next_lane`), with no lane in between to copy from.
pub(crate) trait LaneSink {
    /// Writes `lane`, but for the fields of `unwritten` (`LanePlace` bits), which need not
    /// be: the lanes set them before they are read (`lanes::POINT_UNWRITTEN`,
    /// `lanes::LONE_UNWRITTEN`).
    fn put(&mut self, lane: LambertLane, unwritten: u64);
}

impl LaneSink for LambertLane {
    /// The whole lane, whatever `unwritten` says: one path's lane is not a column, and a
    /// copy of all of it costs no more.
    #[inline(always)]
    fn put(&mut self, lane: LambertLane, _unwritten: u64) {
        *self = lane;
    }
}

/// `LambertLane::light_kind`s.
pub(crate) const AREA: f32 = 0.0;
pub(crate) const POINT: f32 = 1.0;
pub(crate) const DISTANT: f32 = 2.0;
/// The light of the scene's lone emitter, still to be sampled where the point is known
/// (`with_lone_light`), from the light's draw: its first two numbers in `light_point`, its
/// last two in `light_normal`.
pub(crate) const LONE: f32 = 3.0;
/// A `LONE` light near the emitter, where it is sampled by solid angle, one lane at a time
/// (`PathTracer::lambert_outcome`): until then the lane has no light.
pub(crate) const NEAR: f32 = 4.0;

/// What a plain Lambertian bounce gives.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct LambertOutcome {
    /// 1 where a shadow ray is to be traced (a valid ray: `Ray::is_valid`), else 0.
    pub shadow: f32,
    pub shadow_origin: Vec3,
    /// From the origin to the light point's far side of its error bound (`tmax` just
    /// short of 1: `spawn_ray_to`), or towards a distant light (`tmax` infinite).
    pub shadow_dir: Vec3,
    pub shadow_tmax: f32,
    /// The light the shadow ray brings unless blocked (before the path's throughput).
    pub contribution: Vec3,
    /// 1 where the path goes on (along a valid ray: `Ray::is_valid`), else 0.
    pub next: f32,
    pub next_origin: Vec3,
    pub next_dir: Vec3,
    pub throughput: Vec3,
    pub pdf: f32,
    /// The hit point (the path's next `from`).
    pub point: Vec3,
    /// 1 where the lane's light is to be sampled one lane at a time (`NEAR`): the rest of the
    /// outcome is to be computed again then, else 0.
    pub near: f32,
}

/// The rotations the shading frame is built through (`PathTracer::shading_frame`), and
/// whether its normal alone decides a direction's side (`Sides::Shading`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct FrameSpaces {
    pub sampling_from_render: Mat3,
    pub render_from_sampling: Mat3,
    pub shading_sides: bool,
}

/// The bounce of `lane` (see the module's comment).
#[inline(always)]
pub(crate) fn lambert_bounce(lane: &LambertLane, spaces: &FrameSpaces) -> LambertOutcome {
    let frame = super::shading_frame_in(spaces, lane.shading_normal);
    let to_local = frame.transpose();
    let wo = -lane.dir.normalize();
    let wo_local = to_local * wo;
    let surface = SurfacePoint { point: lane.point, error: lane.error, normal: lane.normal };

    // Next-event estimation (`direct_light`, its one light sample).
    let distant = lane.light_kind == DISTANT;
    let to_light = lane.light_point - lane.point;
    let dist2 = to_light.length_squared();
    let wi = select3(distant, lane.light_point, to_light / dist2.sqrt());
    let cos_emitted = lane.light_normal.dot(-wi);
    let cos_light = select(lane.light_two_sided != 0.0, cos_emitted.abs(), cos_emitted);
    let faces = spaces.shading_sides || lane.normal.dot(wi) > 0.0;
    let wi_local = to_local * wi;
    // Conditions are written as the scalar code has them, so that NaNs fall the same way.
    let lit = !(wo_local.z <= 0.0 || wi_local.z <= 0.0);
    let f_cos = select3(lit, lane.diffuse * Vec3::ONE * FRAC_1_PI * wi_local.z, Vec3::ZERO);
    let pdf_bsdf = select(lit, 1.0 * wi_local.z * FRAC_1_PI, 0.0);
    let target = SurfacePoint {
        point: lane.light_point,
        error: lane.light_error,
        normal: lane.light_normal,
    };
    let (to_point, point_end) = surface.spawn_ends_to(&target);
    let shadow_origin = select3(distant, surface.offset_origin(wi), to_point);
    let weight = select(lane.light_visible != 0.0, power_heuristic(lane.light_pdf, pdf_bsdf), 1.0);
    let contribution = select3(
        lane.light_kind == POINT,
        f_cos * lane.emission / dist2,
        f_cos * lane.emission * (weight / lane.light_pdf),
    );
    let shadow_dir = select3(distant, wi, point_end - shadow_origin);
    // A ray that is not valid is blocked and not counted (as `SceneTracer::occluded` has it):
    // tested here, in lanes, so that the queue need not test each ray again.
    let shadow = lane.has_light != 0.0
        && faces
        && (lane.light_kind != AREA || cos_light > 0.0)
        && (distant || dist2 > 0.0)
        && f_cos != Vec3::ZERO
        && Ray::coordinates_valid(shadow_origin, shadow_dir);

    // BSDF sampling (`Mixture::sample`'s lone Lambertian lobe) and roulette (`scatter`).
    let wi_sampled = crate::sampling::cosine_hemisphere(Vec2::new(lane.u0, lane.u1));
    let pdf = wi_sampled.z * FRAC_1_PI;
    let next_dir = frame * wi_sampled;
    let below = !spaces.shading_sides && next_dir.dot(lane.normal) < 0.0;
    let throughput = lane.throughput * lane.diffuse;
    let survive = (throughput * lane.eta_scale).max_element().min(0.95);
    let rouletted = lane.roulette != 0.0;
    let survives = !rouletted || !(lane.u_survive >= survive);
    let throughput = select3(rouletted, throughput / survive, throughput);
    let next_origin = surface.offset_origin(next_dir);
    // As for the shadow ray: an invalid next ray ends the path (as `PathState::advance`
    // has it), tested here so that the path need not test it again.
    let next = !(wo_local.z <= 0.0)
        && !(wi_sampled.z <= 0.0)
        && pdf > 0.0
        && !below
        && lane.diffuse != Vec3::ZERO
        && survives
        && Ray::coordinates_valid(next_origin, next_dir);
    LambertOutcome {
        shadow: select(shadow, 1.0, 0.0),
        shadow_origin,
        shadow_dir,
        shadow_tmax: select(distant, f32::INFINITY, SHADOW_TMAX),
        contribution,
        next: select(next, 1.0, 0.0),
        next_origin,
        next_dir,
        throughput,
        pdf,
        point: lane.point,
        near: select(lane.light_kind == NEAR, 1.0, 0.0),
    }
}
