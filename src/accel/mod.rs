//! Acceleration-structure backends. The integrator sees only the [`Accel`] trait; all
//! `cfg(feature)` branching over backends lives in this file.

use crate::ray::{Hit, Ray};
use crate::ray_columns::{RayBatch, RayColumns};
use crate::render_scene::RenderScene;
use crate::stats::TraversalCounters;

#[cfg(feature = "embree")]
pub mod embree;
#[cfg(feature = "obvhs")]
pub mod obvhs;
mod options;

mod library;
pub use library::{EmbreeLibrary, backends_description, embree_library};
pub use options::{AccelOptions, BackendKind, BatchMode, BuildQuality, Coherence, Intersection};

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
    /// Closest hits of a batch of rays: `hits[i]` becomes what `intersect(&rays[i], counters)`
    /// returns (bit for bit, counters included; Embree packets may break a tie between
    /// coincident surfaces differently, see [`BatchMode`]), so a caller may batch coherent
    /// rays (a tile's camera rays) without changing its results. Unlike [`Accel::intersect`], rays need not
    /// be valid: an invalid ray is a miss.
    ///
    /// # Panics
    /// If `rays` and `hits` differ in length.
    ///
    /// `coherence` says whether the rays start near each other and point the same way (a
    /// tile's camera rays) or not (bounces), for backends whose batched traversal differs.
    fn intersect_batch(
        &self,
        rays: &[Ray],
        hits: &mut [Option<Hit>],
        coherence: Coherence,
        counters: &mut TraversalCounters,
    ) {
        let _ = coherence;
        intersect_one_by_one(self, rays, hits, counters);
    }
    /// Occlusion of a batch of rays: `blocked[i]` becomes what `occluded(&rays[i], counters)`
    /// returns (counters included). An invalid ray counts as blocked (it is never traced).
    ///
    /// # Panics
    /// If `rays` and `blocked` differ in length.
    fn occluded_batch(&self, rays: &[Ray], blocked: &mut [bool], counters: &mut TraversalCounters) {
        occluded_one_by_one(self, rays, blocked, counters);
    }
    /// [`Accel::intersect_batch`] of rays queued in columns: `hits[i]` for `rays.ray(i)`.
    ///
    /// # Panics
    /// If `rays` and `hits` differ in length.
    fn intersect_columns(
        &self,
        rays: &RayColumns,
        hits: &mut [Option<Hit>],
        coherence: Coherence,
        counters: &mut TraversalCounters,
    ) {
        let _ = coherence;
        intersect_one_by_one(self, rays, hits, counters);
    }
    /// [`Accel::occluded_batch`] of rays queued in columns: `blocked[i]` for `rays.ray(i)`.
    ///
    /// # Panics
    /// If `rays` and `blocked` differ in length.
    fn occluded_columns(
        &self,
        rays: &RayColumns,
        blocked: &mut [bool],
        counters: &mut TraversalCounters,
    ) {
        occluded_one_by_one(self, rays, blocked, counters);
    }
    /// Which counters this backend fills in (with `AccelOptions::count_traversal`).
    fn observes(&self) -> Observes {
        Observes::default()
    }
    /// Bytes the structure holds: obvhs counts its nodes, leaves and ids; Embree reports
    /// what its memory monitor counted for the backend's device.
    fn memory_bytes(&self) -> Option<usize> {
        None
    }
}

/// [`Accel::intersect_batch`] (or `intersect_columns`) done one [`Accel::intersect`] at a
/// time (invalid rays miss): what every batched path must equal.
///
/// # Panics
/// If `rays` and `hits` differ in length.
pub fn intersect_one_by_one<A: Accel + ?Sized, R: RayBatch + ?Sized>(
    accel: &A,
    rays: &R,
    hits: &mut [Option<Hit>],
    counters: &mut TraversalCounters,
) {
    assert_eq!(rays.count(), hits.len(), "one hit slot per ray");
    for (i, hit) in hits.iter_mut().enumerate() {
        let ray = rays.ray_at(i);
        *hit = if ray.is_valid() { accel.intersect(&ray, counters) } else { None };
    }
}

/// [`Accel::occluded_batch`] (or `occluded_columns`) done one [`Accel::occluded`] at a time
/// (invalid rays are blocked): what every batched path must equal.
///
/// # Panics
/// If `rays` and `blocked` differ in length.
pub fn occluded_one_by_one<A: Accel + ?Sized, R: RayBatch + ?Sized>(
    accel: &A,
    rays: &R,
    blocked: &mut [bool],
    counters: &mut TraversalCounters,
) {
    assert_eq!(rays.count(), blocked.len(), "one answer per ray");
    for (i, blocked) in blocked.iter_mut().enumerate() {
        let ray = rays.ray_at(i);
        *blocked = !ray.is_valid() || accel.occluded(&ray, counters);
    }
}

impl BackendKind {
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

/// Traces a slice of rays, returning how many hit.
pub type RawLoop = Box<dyn Fn(&[Ray]) -> usize + Send + Sync>;

/// A bare `rtcIntersect1` loop over `scene` (closest hits, counted), the yardstick our
/// Embree wrapper is measured against; `None` without Embree (or if its build fails).
pub fn raw_embree_loop(scene: &RenderScene) -> Option<RawLoop> {
    #[cfg(feature = "embree")]
    {
        let raw = embree::EmbreeAccel::build(scene, &AccelOptions::default()).ok()?;
        Some(Box::new(move |rays: &[Ray]| raw.raw_intersect_loop(rays)))
    }
    #[cfg(not(feature = "embree"))]
    {
        let _ = scene;
        None
    }
}
