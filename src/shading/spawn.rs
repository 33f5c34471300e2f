//! Spawning rays from surfaces without self-intersection, using floating-point error bounds
//! on the hit point (pbrt-v4's `OffsetRayOrigin`) instead of a fixed epsilon: the origin is
//! pushed along the geometric normal just past the bound, then rounded away from the
//! surface, so a spawned ray can never re-hit the surface it left, at any scale.

use crate::float_error::{gamma, next_float_down, next_float_up};
use crate::ray::Ray;
use glam::Vec3;

/// Relative shortening of shadow rays: the triangle tests (ours and Embree's) and instance
/// transforms round a hit distance by a few γ; γ(16) covers them with room to spare.
const SHADOW_GAP: f32 = gamma(16);

/// Where shadow rays to surface points stop (`spawn_ray_to`).
pub const SHADOW_TMAX: f32 = 1.0 - SHADOW_GAP;

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
    #[inline(always)]
    pub fn offset_origin(&self, w: Vec3) -> Vec3 {
        let d = self.normal.abs().dot(self.error);
        let outward = if w.dot(self.normal) < 0.0 { -self.normal } else { self.normal };
        let origin = self.point + outward * d;
        Vec3::new(
            step_towards(origin.x, outward.x),
            step_towards(origin.y, outward.y),
            step_towards(origin.z, outward.z),
        )
    }

    /// A ray leaving the surface in direction `dir`.
    pub fn spawn_ray(&self, dir: Vec3, time: f32) -> Ray {
        Ray { origin: self.offset_origin(dir), dir, tmin: 0.0, tmax: f32::INFINITY, time }
    }

    /// A shadow ray from this surface to `target`. Both ends are pushed off their surfaces
    /// past their points' error bounds; the ray then stops `SHADOW_GAP` (relative) short of
    /// its end, because the backend computes the target surface's hit distance with a
    /// relative error of a few γ of its own. That keeps the target out of reach at any
    /// distance while leaving a gap of only ~1e-6 of the length (1 cm at 10⁴ units) where
    /// an occluder could be missed; pbrt's `1 − 1e-4` leaves 1 m. `target` may itself be a
    /// surface point (its own offset is applied) or a point light (no error, no offset).
    pub fn spawn_ray_to(&self, target: &SurfacePoint, time: f32) -> Ray {
        let (origin, end) = self.spawn_ends_to(target);
        Ray { origin, dir: end - origin, tmin: 0.0, tmax: SHADOW_TMAX, time }
    }

    /// The two ends of `spawn_ray_to`'s ray: its origin and the point at t = 1.
    #[inline(always)]
    pub fn spawn_ends_to(&self, target: &SurfacePoint) -> (Vec3, Vec3) {
        let origin = self.offset_origin(target.point - self.point);
        (origin, target.offset_origin(origin - target.point))
    }

    /// A point with no error and no surface (a point light).
    pub fn exact(point: Vec3) -> Self {
        SurfacePoint { point, error: Vec3::ZERO, normal: Vec3::ZERO }
    }
}

/// `v` one ulp up where `direction` is positive, one down where it is negative, unchanged
/// where it is zero: `next_float_up` / `next_float_down` computed both and selected, without
/// branches (the sign of a spawned ray's offset on each axis is as good as random, and the
/// mispredicted branches made this a tenth of a Cornell render).
#[inline]
fn step_towards(v: f32, direction: f32) -> f32 {
    let up = next_float_up(v);
    let down = next_float_down(v);
    let stepped = if direction > 0.0 { up } else { down };
    if direction == 0.0 || direction.is_nan() { v } else { stepped }
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
            // An offset past the coordinate range puts every ray outside the scene.
            Ok(eps) if (0.0..=crate::limits::MAX_COORDINATE as f32).contains(&eps) => {
                Ok(SpawnMode::Epsilon(eps))
            }
            Ok(eps) if eps > 0.0 => Err(format!(
                "'{value}' is beyond the coordinate range: an offset must be at most {:e}",
                crate::limits::MAX_COORDINATE
            )),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::float_error::{TrianglePlane, triangle_point};

    #[test]
    fn stepping_without_branches_is_stepping_with_them() {
        let reference = |v: f32, direction: f32| {
            if direction > 0.0 {
                next_float_up(v)
            } else if direction < 0.0 {
                next_float_down(v)
            } else {
                v
            }
        };
        let mut values = vec![
            0.0,
            -0.0,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            f32::from_bits(1),
            -f32::from_bits(1),
            f32::MAX,
            f32::MIN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            1.0,
            -1.0,
        ];
        let mut rng = crate::splitmix::SplitMix64(7);
        values.extend(
            (0..2000).map(|_| f32::from_bits(rng.next_u64() as u32)).filter(|v| !v.is_nan()),
        );
        for &v in &values {
            for direction in [1.0, -1.0, 0.0, -0.0, 1e-30, -1e-30, f32::NAN] {
                let (got, want) = (step_towards(v, direction), reference(v, direction));
                assert_eq!(got.to_bits(), want.to_bits(), "{v:e} towards {direction}");
            }
        }
        assert_eq!(next_float_up(-0.0), f32::from_bits(1));
        assert_eq!(next_float_down(0.0), -f32::from_bits(1));
        assert_eq!(next_float_up(f32::INFINITY), f32::INFINITY);
        assert_eq!(next_float_down(f32::NEG_INFINITY), f32::NEG_INFINITY);
        assert_eq!(next_float_up(f32::NEG_INFINITY), f32::MIN);
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
            let (point, error) = triangle_point(&tri, &TrianglePlane::new(&tri), b1, b2);
            let sp = SurfacePoint { point, error, normal };
            assert!(sp.offset_origin(Vec3::Y).y > base.y);
            assert!(sp.offset_origin(-Vec3::Y).y < base.y);
        }
    }
}
