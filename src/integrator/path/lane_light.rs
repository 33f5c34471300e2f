//! What a plain Lambertian lane may still need before its bounce, left to the lanes so that
//! the loop over them computes it for many paths at once: the hit point of a triangle hit
//! (`with_hit_point`), and, where the scene's one light is a lone flat emitter, the light
//! sample its place calls for (`with_lone_light`): none behind a one-sided emitter, a point
//! sampled by area far from it, and near it a point sampled by solid angle, which is left
//! to one lane at a time (`NEAR`, `PathTracer::lambert_outcome`). Both in select form, and
//! the same operations as the scalar code's (`triangle_hit_point`, `sample_emitter`), so
//! the numbers are the same bit for bit.

use super::lambert::{AREA, LONE, LambertLane, NEAR};
use crate::float_error::{TrianglePlane, triangle_hit_point};
use crate::lane_select::{select, select3};
use crate::light::AreaSampler;
use crate::ray::Hit;
use crate::shading::spawn::SurfacePoint;
use glam::{Vec2, Vec3};

/// Where a plain Lambertian bounce is: at a point known (`SurfacePoint`), or on a triangle
/// hit whose point is still to be computed (`OnTriangle`). A trait rather than an enum, so
/// that `lambert_lane` is compiled for each on its own: the two merged spilled their fields
/// to the stack (60 instructions a bounce).
pub(crate) trait BounceAt: Copy {
    /// Whether the point is left to the lanes (`on_triangle` not 0).
    const POINT_LEFT_TO_LANES: bool;
    /// The point, its bound and its normal (facing the ray), computed if need be, for a ray
    /// of direction `dir`.
    fn resolve(&self, dir: Vec3) -> SurfacePoint;
    /// What a lane holds of it: the point, its bound (both zero where they are left to the
    /// lanes, whose columns then are not written: `POINT_UNWRITTEN`) and its normal, the
    /// triangle hit, and its `on_triangle` (0 where the point is known).
    fn lane_fields(&self) -> (SurfacePoint, TriangleHit, f32);
}

impl BounceAt for SurfacePoint {
    const POINT_LEFT_TO_LANES: bool = false;

    #[inline(always)]
    fn resolve(&self, _dir: Vec3) -> SurfacePoint {
        *self
    }

    #[inline(always)]
    fn lane_fields(&self) -> (SurfacePoint, TriangleHit, f32) {
        (*self, TriangleHit::default(), 0.0)
    }
}

/// A triangle hit, the triangle's normal facing the ray, and whether that is the triangle's
/// own (its front was hit) or its opposite.
#[derive(Clone, Copy, Debug)]
pub(crate) struct OnTriangle {
    pub hit: TriangleHit,
    pub normal: Vec3,
    pub front_face: bool,
}

impl BounceAt for OnTriangle {
    const POINT_LEFT_TO_LANES: bool = true;

    #[inline(always)]
    fn resolve(&self, dir: Vec3) -> SurfacePoint {
        // The triangle's own normal again: a negation is exact.
        let own = if self.front_face { self.normal } else { -self.normal };
        let (point, error) = self.hit.point(dir, own);
        SurfacePoint { point, error, normal: self.normal }
    }

    #[inline(always)]
    fn lane_fields(&self) -> (SurfacePoint, TriangleHit, f32) {
        let surface = SurfacePoint { point: Vec3::ZERO, error: Vec3::ZERO, normal: self.normal };
        (surface, self.hit, if self.front_face { 1.0 } else { -1.0 })
    }
}

/// What a triangle hit's point and error bound are computed from (`triangle_hit_point`).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct TriangleHit {
    pub triangle: [Vec3; 3],
    /// The origin of the ray that hit.
    pub origin: Vec3,
    pub barycentrics: (f32, f32),
    pub t: f32,
    /// The triangle plane's `tilt` and `edge_tilt`.
    pub tilt: f32,
    pub edge_tilt: f32,
}

impl TriangleHit {
    /// The hit of a ray from `origin` on `triangle`, of plane `plane`, at `hit`.
    #[inline(always)]
    pub fn new(triangle: [Vec3; 3], plane: &TrianglePlane, origin: Vec3, hit: &Hit) -> Self {
        let (barycentrics, t) = ((hit.u, hit.v), hit.t);
        TriangleHit {
            triangle,
            origin,
            barycentrics,
            t,
            tilt: plane.tilt,
            edge_tilt: plane.edge_tilt,
        }
    }

    /// The point and its bound, for a ray of direction `dir`, where the triangle's own unit
    /// normal (its plane's) is `normal`.
    #[inline(always)]
    fn point(&self, dir: Vec3, normal: Vec3) -> (Vec3, Vec3) {
        let [v0, v1, v2] = self.triangle;
        // The plane `TrianglePlane::new` gives the triangle: its edges are these differences.
        let plane = TrianglePlane {
            e1: v1 - v0,
            e2: v2 - v0,
            normal,
            tilt: self.tilt,
            edge_tilt: self.edge_tilt,
        };
        triangle_hit_point(&self.triangle, &plane, self.barycentrics, (self.origin, dir, self.t))
    }
}

/// `lane` with its point and error bound computed where they are left to be (`on_triangle`).
#[inline(always)]
pub(crate) fn with_hit_point(lane: &LambertLane) -> LambertLane {
    let hit = TriangleHit {
        triangle: [lane.hit_v0, lane.hit_v1, lane.hit_v2],
        origin: lane.hit_origin,
        barycentrics: (lane.hit_b1, lane.hit_b2),
        t: lane.hit_t,
        tilt: lane.hit_tilt,
        edge_tilt: lane.hit_edge_tilt,
    };
    // The triangle's own normal again (`on_triangle` is 1 or -1 here): exact.
    let (point, error) = hit.point(lane.dir, lane.normal * lane.on_triangle);
    let computed = lane.on_triangle != 0.0;
    LambertLane {
        point: select3(computed, point, lane.point),
        error: select3(computed, error, lane.error),
        ..*lane
    }
}

/// `lane` (its point known) with its light sampled on `emitter` where it was left to be
/// (`LONE`), as `sample_emitter` would sample it; near the emitter, marked `NEAR` instead,
/// its draw kept and no light yet.
#[inline(always)]
pub(crate) fn with_lone_light(lane: &LambertLane, emitter: &AreaSampler) -> LambertLane {
    let lone = lane.light_kind == LONE;
    let (behind, near) = (emitter.behind(lane.point), emitter.is_near(lane.point));
    // As `AreaSampler::by_area` has it.
    let by_area = lone && !behind && !near;
    let near = !behind && near;
    let u = Vec2::new(lane.light_point.x, lane.light_point.y);
    let sample = emitter.sample_by_area(lane.point, u);
    let flag = |set: bool| if set { 1.0 } else { 0.0 };
    let kind = select(near, NEAR, AREA);
    LambertLane {
        has_light: select(lone, flag(by_area && sample.pdf > 0.0), lane.has_light),
        light_kind: select(lone, kind, lane.light_kind),
        light_point: select3(by_area, sample.point, lane.light_point),
        light_error: select3(by_area, sample.error, lane.light_error),
        light_normal: select3(by_area, sample.normal, lane.light_normal),
        emission: select3(by_area, emitter.emission, lane.emission),
        light_pdf: select(by_area, sample.pdf, lane.light_pdf),
        light_visible: select(by_area, flag(emitter.visible), lane.light_visible),
        light_two_sided: select(by_area, flag(emitter.two_sided), lane.light_two_sided),
        ..*lane
    }
}

/// The light's draw of a `LONE` or `NEAR` lane, as `light_point` and `light_normal` keep it.
pub(crate) fn lone_draw(lane: &LambertLane) -> [f32; 4] {
    let (first, second) = (lane.light_point, lane.light_normal);
    [first.x, first.y, second.x, second.y]
}

/// The light fields of a `LONE` lane that keep the light's draw (see `LONE`).
pub(crate) fn lone_draw_fields([u0, u1, u2, u3]: [f32; 4]) -> (Vec3, Vec3) {
    (Vec3::new(u0, u1, 0.0), Vec3::new(u2, u3, 0.0))
}
