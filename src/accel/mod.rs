//! Acceleration-structure backends. The integrator sees only the [`Accel`] trait; all
//! `cfg(feature)` branching over backends lives in this file.

use crate::render_scene::RenderScene;
use crate::stats::TraversalCounters;
use glam::Vec3;

#[cfg(feature = "embree")]
pub mod embree;
#[cfg(feature = "obvhs")]
pub mod obvhs;

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
    pub fn new(origin: Vec3, dir: Vec3, tmax: f32) -> Self {
        Ray { origin, dir, tmin: 0.0, tmax, time: 0.0 }
    }

    /// Debian's Embree aborts the process on a NaN/Inf ray or a negative `tnear`, so every
    /// ray is checked before it reaches a backend.
    ///
    /// Embree also aborts on finite coordinates above about 1.8e18, so those are refused too
    /// (by both backends, so they agree).
    pub fn is_valid(&self) -> bool {
        const LIMIT: f32 = 1.0e18;
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

/// Which traversal counters a backend can observe.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Observes {
    pub node_visits: bool,
    pub prim_tests: bool,
}

/// A built acceleration structure over one `RenderScene`, safe to query from many threads.
pub trait Accel: Send + Sync {
    /// Short name for reports ("embree", "obvhs").
    fn name(&self) -> &'static str;
    /// Closest hit with `tmin <= t <= tmax`. The ray must satisfy [`Ray::is_valid`].
    fn intersect(&self, ray: &Ray, counters: &mut TraversalCounters) -> Option<Hit>;
    /// True if anything lies on the ray with `tmin <= t <= tmax`.
    fn occluded(&self, ray: &Ray, counters: &mut TraversalCounters) -> bool;
    /// Which counters this backend fills in (with `AccelOptions::count_traversal`).
    fn observes(&self) -> Observes {
        Observes::default()
    }
}

/// Which backend to build.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum BackendKind {
    Embree,
    Obvhs,
}

impl BackendKind {
    pub fn name(self) -> &'static str {
        match self {
            BackendKind::Embree => "embree",
            BackendKind::Obvhs => "obvhs",
        }
    }

    /// Every backend compiled into this build, Embree first.
    pub fn compiled() -> Vec<Self> {
        let mut all = Vec::new();
        if cfg!(feature = "embree") {
            all.push(BackendKind::Embree);
        }
        if cfg!(feature = "obvhs") {
            all.push(BackendKind::Obvhs);
        }
        all
    }

    /// The backend used when none is asked for: Embree when compiled in.
    pub fn default_compiled() -> Self {
        if cfg!(feature = "embree") { BackendKind::Embree } else { BackendKind::Obvhs }
    }
}

#[derive(Debug, thiserror::Error)]
pub enum AccelError {
    #[error("backend '{0}' was not compiled into this binary (rebuild with `--features {0}`)")]
    NotCompiled(&'static str),
    #[error("Embree: {0}")]
    Embree(String),
}

/// Options that change how a backend is built.
#[derive(Clone, Copy, Debug, Default)]
pub struct AccelOptions {
    /// Count node visits / primitive tests (may cost time; off by default).
    pub count_traversal: bool,
}

/// Builds the requested backend over `scene`.
pub fn build(
    kind: BackendKind,
    scene: &RenderScene,
    options: &AccelOptions,
) -> Result<Box<dyn Accel>, AccelError> {
    let _ = (scene, options);
    match kind {
        #[cfg(feature = "embree")]
        BackendKind::Embree => Ok(Box::new(embree::EmbreeAccel::build(scene, options)?)),
        #[cfg(not(feature = "embree"))]
        BackendKind::Embree => Err(AccelError::NotCompiled("embree")),
        #[cfg(feature = "obvhs")]
        BackendKind::Obvhs => Ok(Box::new(obvhs::ObvhsAccel::build(scene, options))),
        #[cfg(not(feature = "obvhs"))]
        BackendKind::Obvhs => Err(AccelError::NotCompiled("obvhs")),
    }
}
