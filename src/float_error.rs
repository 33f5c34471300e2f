//! Floating-point error bounds (pbrt-v4's `util/float.h` and its interval points): the
//! rounding bound γ(n), one-ulp steps, and hit points on triangles and spheres with a
//! conservative bound on their error. Below everything that spawns rays or samples lights.

use crate::lane_select::select3;
use glam::{Affine3A, Mat3, Vec3};

/// γ(n) = nε / (1 − nε), the relative error bound of n chained f32 operations.
pub const fn gamma(n: i32) -> f32 {
    let eps = f32::EPSILON * 0.5;
    (n as f32 * eps) / (1.0 - n as f32 * eps)
}

/// The next float above `v` (+inf stays; -0 and +0 step to the smallest positive).
/// Written as selects, without early returns, so that callers compile without branches.
#[inline]
pub fn next_float_up(v: f32) -> f32 {
    let v0 = if v == 0.0 { 0.0 } else { v };
    let bits = v0.to_bits();
    let stepped =
        f32::from_bits(if v0 >= 0.0 { bits.wrapping_add(1) } else { bits.wrapping_sub(1) });
    if v == f32::INFINITY { v } else { stepped }
}

/// The next float below `v` (-inf stays; +0 and -0 step to the smallest negative).
#[inline]
pub fn next_float_down(v: f32) -> f32 {
    let v0 = if v == 0.0 { -0.0 } else { v };
    let bits = v0.to_bits();
    let stepped =
        f32::from_bits(if v0 > 0.0 { bits.wrapping_sub(1) } else { bits.wrapping_add(1) });
    if v == f32::NEG_INFINITY { v } else { stepped }
}

/// A triangle's edges from vertex 0, its unit normal (zero if degenerate) and how far
/// (radians) rounding can tilt that normal, computed once per hit or light sample for both
/// hit-point bounds.
#[derive(Clone, Copy, Debug)]
pub struct TrianglePlane {
    pub e1: Vec3,
    pub e2: Vec3,
    pub normal: Vec3,
    /// Each component of e1 × e2 is off by γ(3)·|e1||e2|, which is large against |e1 × e2|
    /// for a sliver; normalising adds γ(3). 0 for a degenerate triangle (no plane).
    pub tilt: f32,
    /// The longer edge times `tilt`: how far the tilt can move the plane over the triangle.
    pub edge_tilt: f32,
}

impl TrianglePlane {
    pub fn new(tri: &[Vec3; 3]) -> Self {
        let (e1, e2) = (tri[1] - tri[0], tri[2] - tri[0]);
        let (e1_length, e2_length) = (e1.length(), e2.length());
        let cross = e1.cross(e2);
        let area2 = cross.length();
        let tilt =
            if area2 > 0.0 { gamma(3) * (e1_length * e2_length) / area2 + gamma(3) } else { 0.0 };
        // `normalize_or_zero` without computing the length again (one per hit).
        let recip = 1.0 / area2;
        let normal = if recip.is_finite() && recip > 0.0 { cross * recip } else { Vec3::ZERO };
        TrianglePlane { e1, e2, normal, tilt, edge_tilt: e1_length.max(e2_length) * tilt }
    }
}

/// Hit point on a triangle from barycentrics, with its error bound.
///
/// Two terms: pbrt-v4's bound on evaluating the barycentric sum (eq. 6.24), which grows with
/// the coordinates' magnitude; and the error of the ray-triangle test itself, which computes
/// relative to a vertex and so grows with the triangle's edge lengths. The second term matters
/// in camera-relative space, where a huge ground plane passes close to the origin: there the
/// first term is tiny, but an intersector re-testing the same plane can still report a small
/// positive t unless the origin is pushed past its own rounding error.
///
/// A third term covers slivers: the plane the intersector works with is tilted by up to
/// `plane.tilt`, which moves it by up to an edge length times that angle.
pub fn triangle_point(tri: &[Vec3; 3], plane: &TrianglePlane, b1: f32, b2: f32) -> (Vec3, Vec3) {
    let b0 = 1.0 - b1 - b2;
    let terms = [tri[0] * b0, tri[1] * b1, tri[2] * b2];
    let point = terms[0] + terms[1] + terms[2];
    let abs_sum = terms[0].abs() + terms[1].abs() + terms[2].abs();
    let edges = plane.e1.abs() + plane.e2.abs();
    (point, abs_sum * gamma(7) + edges * gamma(8) + Vec3::splat(plane.edge_tilt + MIN_OFFSET))
}

/// Hit point on a triangle from the ray (`origin + t·dir`) projected onto the triangle's
/// plane, with its error bound; meaningless for a degenerate triangle (a zero normal).
///
/// For a huge triangle seen from close by (a kilometre ground plane under a camera), the
/// barycentric sum of `triangle_point` carries the vertices' rounding (millimetres), while
/// the ray point is accurate in the plane and the projection removes its error across it.
/// `triangle_hit_point` keeps whichever of the two has the smaller bound across the surface.
#[inline(always)]
fn triangle_point_from_ray(
    tri: &[Vec3; 3],
    plane: &TrianglePlane,
    origin: Vec3,
    dir: Vec3,
    t: f32,
) -> (Vec3, Vec3) {
    let normal = plane.normal;
    let on_ray = origin + dir * t;
    let from_vertex = on_ray - tri[0];
    let distance = from_vertex.dot(normal);
    let point = on_ray - normal * distance;
    // The rounded normal tilts the plane through tri[0] (by |from_vertex| · tilt here), then
    // the plane distance's own rounding, and the projection's.
    let across = gamma(4) * from_vertex.abs().dot(normal.abs())
        + gamma(2) * distance.abs()
        + from_vertex.length() * plane.tilt;
    let error = Vec3::splat(across) + point.abs() * gamma(2) + Vec3::splat(MIN_OFFSET);
    (point, error)
}

/// A triangle hit's point and error bound: of `triangle_point` (from the barycentrics `b1`,
/// `b2`) and `triangle_point_from_ray` (from `origin + t·dir`), the one with the smaller
/// bound across the surface. Written as selects, so that a loop over many hits vectorises.
#[inline(always)]
pub fn triangle_hit_point(
    tri: &[Vec3; 3],
    plane: &TrianglePlane,
    (b1, b2): (f32, f32),
    (origin, dir, t): (Vec3, Vec3, f32),
) -> (Vec3, Vec3) {
    let (point, error) = triangle_point(tri, plane, b1, b2);
    let (ray_point, ray_error) = triangle_point_from_ray(tri, plane, origin, dir, t);
    let across = |e: Vec3| plane.normal.abs().dot(e);
    let from_ray =
        plane.normal != Vec3::ZERO && across(ray_error) < across(error) && ray_point.is_finite();
    (select3(from_ray, ray_point, point), select3(from_ray, ray_error, error))
}

/// Floor of every error bound: far below any geometric feature, but large enough that
/// t = -offset / |dir| cannot underflow to -0.0 (which compares equal to a zero `tmin`).
const MIN_OFFSET: f32 = 1e-20;

/// Hit point on a sphere: `origin + t·dir` reprojected onto the surface, with its bound.
pub fn sphere_point(center: Vec3, radius: f32, origin: Vec3, dir: Vec3, t: f32) -> (Vec3, Vec3) {
    let mut local = origin + dir * t - center;
    let len = local.length();
    if len > 0.0 {
        local *= radius / len;
    }
    sphere_point_from_local(center, radius, local)
}

/// The point `center + local` on a sphere (`local` of length `radius`, as reprojected or
/// as `radius` times a unit normal), with its bound.
pub fn sphere_point_from_local(center: Vec3, radius: f32, local: Vec3) -> (Vec3, Vec3) {
    let point = center + local;
    // Reprojection (pbrt: γ5·|p|) plus the final addition of the centre.
    let error = local.abs() * gamma(5)
        + (center.abs() + local.abs()) * gamma(1)
        + Vec3::splat(radius * gamma(8) + MIN_OFFSET);
    (point, error)
}

/// Applies `m` to a point with error bound `error`, returning the point and its new bound
/// (pbrt-v4's interval transform).
pub fn transform_point_with_error(m: &Affine3A, p: Vec3, error: Vec3) -> (Vec3, Vec3) {
    let linear = Mat3::from(m.matrix3);
    let abs = Mat3::from_cols(linear.x_axis.abs(), linear.y_axis.abs(), linear.z_axis.abs());
    let point = m.transform_point3(p);
    let rounding = (abs * p.abs() + Vec3::from(m.translation).abs()) * gamma(3);
    (point, abs * error * (1.0 + gamma(3)) + rounding)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn next_float_moves_by_one_ulp() {
        assert!(next_float_up(1.0) > 1.0 && next_float_down(1.0) < 1.0);
        assert_eq!(next_float_up(-0.0), f32::from_bits(1));
        assert_eq!(next_float_down(0.0), -f32::from_bits(1));
    }
}
