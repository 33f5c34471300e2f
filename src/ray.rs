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
        const LIMIT: f32 = Ray::COORDINATE_LIMIT;
        self.origin.is_finite()
            && self.dir.is_finite()
            && self.origin.abs().max_element() < LIMIT
            && self.dir.abs().max_element() < LIMIT
            && self.dir != Vec3::ZERO
            && self.tmin.is_finite()
            && self.tmin >= 0.0
            && !self.tmax.is_nan()
            && self.tmax >= self.tmin
            && self.time.is_finite()
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
