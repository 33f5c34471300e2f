//! Rays and hits in render space: shared by the camera, the backends and ray spawning, so it
//! sits below all of them.

use glam::Vec3;

/// A ray in render space. `dir` need not be normalised; `t` is measured in units of `dir`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: Vec3,
    pub dir: Vec3,
    pub tmin: f32,
    pub tmax: f32,
    /// Time within the shutter interval, in [0, 1].
    pub time: f32,
}

impl Ray {
    /// Largest coordinate magnitude [`Ray::is_valid`] accepts (exclusive).
    pub const COORDINATE_LIMIT: f32 = 1.0e18;

    pub fn new(origin: Vec3, dir: Vec3, tmax: f32) -> Self {
        Ray { origin, dir, tmin: 0.0, tmax, time: 0.0 }
    }

    /// Debian's Embree aborts the process on a NaN/Inf ray or a negative `tnear`, so every
    /// ray is checked before it reaches a backend.
    ///
    /// Embree also aborts on finite coordinates above about 1.8e18, so those are refused too
    /// (by both backends, so they agree).
    #[inline]
    pub fn is_valid(&self) -> bool {
        // Every ray is checked (by the path or the lanes that make it, and by the backend),
        // with comparisons that are false for NaN, so that they also test finiteness, joined
        // without a branch; coordinate by coordinate, not as SIMD vectors of a ray's origin
        // and direction, which would reload a ray just stored field by field (a stall).
        Ray::coordinates_valid(self.origin, self.dir)
            & (self.tmin >= 0.0)
            & (self.tmin < f32::INFINITY)
            & (self.tmax >= self.tmin)
            & self.time.is_finite()
    }

    /// Whether a ray from `origin` along `dir` passes the coordinate tests of
    /// [`Ray::is_valid`]: written coordinate by coordinate, so that loops over many lanes
    /// vectorise it (the lanes of Lambertian bounces test their shadow and next rays so, and
    /// the path and the queue of shadow rays need not test them again).
    #[inline(always)]
    pub fn coordinates_valid(origin: Vec3, dir: Vec3) -> bool {
        let below = |x: f32| x.abs() < Ray::COORDINATE_LIMIT;
        (below(origin.x) & below(origin.y) & below(origin.z))
            & (below(dir.x) & below(dir.y) & below(dir.z))
            & ((dir.x != 0.0) | (dir.y != 0.0) | (dir.z != 0.0))
    }
}

/// The closest hit along a ray.
///
/// For triangles `(u, v)` are the barycentric weights of vertices 1 and 2 (vertex 0 gets
/// `1 - u - v`), Embree's convention; for spheres they are unused (0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f32,
    /// Index into `RenderScene::shapes`.
    pub geom_id: u32,
    /// Triangle index within the mesh (0 for a sphere).
    pub prim_id: u32,
    pub u: f32,
    pub v: f32,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rays_embree_would_abort_on_are_invalid() {
        let good = Ray::new(Vec3::new(1.0, -2.0, 3.0), Vec3::new(0.0, 0.0, -1.0), f32::INFINITY);
        assert!(good.is_valid());
        let big = Ray::COORDINATE_LIMIT;
        let bad_vectors = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, big, -big, f32::MAX];
        for bad in bad_vectors {
            for axis in 0..3 {
                let mut r = good;
                r.origin[axis] = bad;
                assert!(!r.is_valid(), "origin {:?}", r.origin);
                let mut r = good;
                r.dir[axis] = bad;
                assert!(!r.is_valid(), "dir {:?}", r.dir);
            }
        }
        let mut r = good;
        r.origin.x = big * (1.0 - f32::EPSILON);
        assert!(r.is_valid(), "just inside the limit");
        let invalid = [
            Ray { dir: Vec3::ZERO, ..good },
            Ray { tmin: -1e-30, ..good },
            Ray { tmin: f32::NAN, ..good },
            Ray { tmin: f32::INFINITY, tmax: f32::INFINITY, ..good },
            Ray { tmax: f32::NAN, ..good },
            Ray { tmin: 2.0, tmax: 1.0, ..good },
            Ray { time: f32::NAN, ..good },
            Ray { time: f32::INFINITY, ..good },
        ];
        for r in invalid {
            assert!(!r.is_valid(), "{r:?}");
        }
        assert!(Ray { tmin: 0.0, tmax: 0.0, ..good }.is_valid(), "an empty interval is valid");
        assert!(Ray { dir: Vec3::new(0.0, -0.0, 1e-40), ..good }.is_valid(), "subnormal direction");
    }

    /// `coordinates_valid` (which `is_valid` tests with) against the rule said another way:
    /// finite coordinates, all below the limit, and a direction that is not zero; on every
    /// mix of ordinary, edge and non-finite coordinates.
    #[test]
    fn coordinates_valid_is_finite_below_the_limit_and_moving() {
        let big = Ray::COORDINATE_LIMIT;
        let values = [
            0.0,
            -0.0,
            1e-40,
            -1.0,
            2.5,
            big * (1.0 - f32::EPSILON),
            big,
            -big,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        let mut checked = 0;
        for &a in &values {
            for &b in &values {
                for axis in 0..3 {
                    let mut origin = Vec3::new(1.0, -2.0, 3.0);
                    origin[axis] = a;
                    let mut dir = Vec3::new(0.0, 0.0, -0.0);
                    dir[(axis + 1) % 3] = b;
                    for (origin, dir) in [(origin, dir), (dir, origin)] {
                        let below = |v: Vec3| v.is_finite() && v.abs().max_element() < big;
                        let rule = below(origin) && below(dir) && dir != Vec3::ZERO;
                        let ray = Ray::new(origin, dir, f32::INFINITY);
                        assert_eq!(Ray::coordinates_valid(origin, dir), rule, "{ray:?}");
                        assert_eq!(ray.is_valid(), rule, "{ray:?}");
                        checked += usize::from(rule);
                    }
                }
            }
        }
        assert!(checked > 100, "valid rays among the cases: {checked}");
    }
}
