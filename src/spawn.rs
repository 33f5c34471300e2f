//! Spawning rays from surfaces without self-intersection, using floating-point error bounds
//! on the hit point (pbrt-v4's `OffsetRayOrigin`) instead of a fixed epsilon: the origin is
//! pushed along the geometric normal just past the bound, then rounded away from the
//! surface, so a spawned ray can never re-hit the surface it left, at any scale.

use crate::accel::Ray;
use glam::Vec3;

/// γ(n) = nε / (1 − nε), the relative error bound of n chained f32 operations.
pub fn gamma(n: i32) -> f32 {
    let eps = f32::EPSILON * 0.5;
    (n as f32 * eps) / (1.0 - n as f32 * eps)
}

pub fn next_float_up(v: f32) -> f32 {
    if v.is_infinite() && v > 0.0 {
        return v;
    }
    let v = if v == -0.0 { 0.0 } else { v };
    let bits = v.to_bits();
    f32::from_bits(if v >= 0.0 { bits + 1 } else { bits - 1 })
}

pub fn next_float_down(v: f32) -> f32 {
    if v.is_infinite() && v < 0.0 {
        return v;
    }
    let v = if v == 0.0 { -0.0 } else { v };
    let bits = v.to_bits();
    f32::from_bits(if v > 0.0 { bits - 1 } else { bits + 1 })
}

/// A point on a surface with a conservative bound on its rounding error per axis.
#[derive(Clone, Copy, Debug)]
pub struct SurfacePoint {
    pub point: Vec3,
    pub error: Vec3,
    /// Unit geometric normal (either orientation).
    pub normal: Vec3,
}

impl SurfacePoint {
    /// Ray origin for leaving the surface in direction `w`.
    ///
    /// Unlike pbrt, every axis along which the normal has a component is rounded at least one
    /// ulp outwards even when the error bound is zero (a hit exactly on an axis-aligned plane
    /// at integer coordinates): otherwise the origin stays on the plane and the surface is hit
    /// again at t = -0, which compares equal to a zero `tmin`.
    pub fn offset_origin(&self, w: Vec3) -> Vec3 {
        let d = self.normal.abs().dot(self.error);
        let outward = if w.dot(self.normal) < 0.0 { -self.normal } else { self.normal };
        let mut origin = self.point + outward * d;
        for axis in 0..3 {
            if outward[axis] > 0.0 {
                origin[axis] = next_float_up(origin[axis]);
            } else if outward[axis] < 0.0 {
                origin[axis] = next_float_down(origin[axis]);
            }
        }
        origin
    }

    /// A ray leaving the surface in direction `dir`.
    pub fn spawn_ray(&self, dir: Vec3, time: f32) -> Ray {
        Ray { origin: self.offset_origin(dir), dir, tmin: 0.0, tmax: f32::INFINITY, time }
    }

    /// A shadow ray from this surface towards `target`, stopping just short of it.
    /// `target` may itself be a surface point (its own offset is applied) or a point light.
    pub fn spawn_ray_to(&self, target: &SurfacePoint, time: f32) -> Ray {
        const SHADOW_EPSILON: f32 = 1e-4;
        let origin = self.offset_origin(target.point - self.point);
        let end = target.offset_origin(origin - target.point);
        Ray { origin, dir: end - origin, tmin: 0.0, tmax: 1.0 - SHADOW_EPSILON, time }
    }

    /// A point with no error and no surface (a point light).
    pub fn exact(point: Vec3) -> Self {
        SurfacePoint { point, error: Vec3::ZERO, normal: Vec3::ZERO }
    }
}

/// How rays leave surfaces: the robust error-bound offset, or the classic fixed epsilon
/// (kept to show what it costs: acne on grazing light, leaks through thin walls).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum SpawnMode {
    #[default]
    Robust,
    /// Push the origin this far (render-space units) along the normal.
    Epsilon(f32),
}

impl SpawnMode {
    /// Parses `robust` or `epsilon=VALUE`.
    pub fn parse(text: &str) -> Result<Self, String> {
        if text == "robust" {
            return Ok(SpawnMode::Robust);
        }
        let value = text
            .strip_prefix("epsilon=")
            .ok_or_else(|| format!("expected 'robust' or 'epsilon=VALUE', got '{text}'"))?;
        match value.parse::<f32>() {
            Ok(eps) if eps.is_finite() && eps >= 0.0 => Ok(SpawnMode::Epsilon(eps)),
            _ => Err(format!("'{value}' is not a non-negative number")),
        }
    }

    pub fn name(&self) -> String {
        match self {
            SpawnMode::Robust => "robust".into(),
            SpawnMode::Epsilon(eps) => format!("epsilon={eps}"),
        }
    }

    fn epsilon_origin(eps: f32, from: &SurfacePoint, towards: Vec3) -> Vec3 {
        let side = if towards.dot(from.normal) < 0.0 { -from.normal } else { from.normal };
        from.point + side * eps
    }

    /// A ray leaving `from` in direction `dir`.
    pub fn ray(self, from: &SurfacePoint, dir: Vec3, time: f32) -> Ray {
        match self {
            SpawnMode::Robust => from.spawn_ray(dir, time),
            SpawnMode::Epsilon(eps) => Ray {
                origin: Self::epsilon_origin(eps, from, dir),
                dir,
                tmin: 0.0,
                tmax: f32::INFINITY,
                time,
            },
        }
    }

    /// A shadow ray from `from` to `target`.
    pub fn ray_to(self, from: &SurfacePoint, target: &SurfacePoint, time: f32) -> Ray {
        match self {
            SpawnMode::Robust => from.spawn_ray_to(target, time),
            SpawnMode::Epsilon(eps) => {
                let origin = Self::epsilon_origin(eps, from, target.point - from.point);
                Ray { origin, dir: target.point - origin, tmin: 0.0, tmax: 1.0 - 1e-4, time }
            }
        }
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
pub fn triangle_point(tri: &[Vec3; 3], b1: f32, b2: f32) -> (Vec3, Vec3) {
    let b0 = 1.0 - b1 - b2;
    let terms = [tri[0] * b0, tri[1] * b1, tri[2] * b2];
    let point = terms[0] + terms[1] + terms[2];
    let abs_sum = terms[0].abs() + terms[1].abs() + terms[2].abs();
    let edges = (tri[1] - tri[0]).abs() + (tri[2] - tri[0]).abs();
    (point, abs_sum * gamma(7) + edges * gamma(8) + Vec3::splat(MIN_OFFSET))
}

/// Hit point on a triangle from the ray (`origin + t·dir`) projected onto the triangle's
/// plane, with its error bound; `None` if the triangle is degenerate.
///
/// For a huge triangle seen from close by (a kilometre ground plane under a camera), the
/// barycentric sum of `triangle_point` carries the vertices' rounding (millimetres), while
/// the ray point is accurate in the plane and the projection removes its error across it.
/// `surface.rs` keeps whichever of the two has the smaller bound across the surface.
pub fn triangle_point_from_ray(
    tri: &[Vec3; 3],
    origin: Vec3,
    dir: Vec3,
    t: f32,
) -> Option<(Vec3, Vec3)> {
    let normal = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize_or_zero();
    if normal == Vec3::ZERO {
        return None;
    }
    let on_ray = origin + dir * t;
    let from_vertex = on_ray - tri[0];
    let distance = from_vertex.dot(normal);
    let point = on_ray - normal * distance;
    // The plane distance's own rounding, then the projection's.
    let across = gamma(4) * from_vertex.abs().dot(normal.abs()) + gamma(2) * distance.abs();
    let error = Vec3::splat(across) + point.abs() * gamma(2) + Vec3::splat(MIN_OFFSET);
    Some((point, error))
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
    let point = center + local;
    // Reprojection (pbrt: γ5·|p|) plus the final addition of the centre.
    let error = local.abs() * gamma(5)
        + (center.abs() + local.abs()) * gamma(1)
        + Vec3::splat(radius * gamma(8) + MIN_OFFSET);
    (point, error)
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

    #[test]
    fn exact_points_on_axis_aligned_planes_still_leave_the_plane() {
        let sp = SurfacePoint {
            point: Vec3::new(9.0, 14.0, 0.0),
            error: Vec3::ZERO,
            normal: Vec3::NEG_Z,
        };
        assert!(sp.offset_origin(Vec3::new(1.0, 1.0, -1.0)).z < 0.0);
        assert!(sp.offset_origin(Vec3::new(1.0, 1.0, 1.0)).z > 0.0);
    }

    #[test]
    fn offset_origin_lands_on_the_requested_side_far_from_the_origin() {
        let base = Vec3::splat(1.0e6);
        let tri = [base, base + Vec3::new(1000.0, 0.0, 0.0), base + Vec3::new(0.0, 0.0, 1000.0)];
        let normal = Vec3::Y;
        for i in 0..100 {
            let b1 = (i as f32 * 0.37).fract() * 0.5;
            let b2 = (i as f32 * 0.61).fract() * 0.5;
            let (point, error) = triangle_point(&tri, b1, b2);
            let sp = SurfacePoint { point, error, normal };
            assert!(sp.offset_origin(Vec3::Y).y > base.y);
            assert!(sp.offset_origin(-Vec3::Y).y < base.y);
        }
    }
}
