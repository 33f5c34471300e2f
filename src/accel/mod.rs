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
    fn intersect_batch(
        &self,
        rays: &[Ray],
        hits: &mut [Option<Hit>],
        counters: &mut TraversalCounters,
    ) {
        intersect_one_by_one(self, rays, hits, counters);
    }
    /// Which counters this backend fills in (with `AccelOptions::count_traversal`).
    fn observes(&self) -> Observes {
        Observes::default()
    }
    /// Whether [`Accel::intersect_batch`] traces coherent rays faster than one
    /// [`Accel::intersect`] each (the renderer batches camera rays only then: collecting
    /// them costs about 2 % of a render for nothing otherwise).
    fn prefers_batches(&self) -> bool {
        false
    }
    /// Bytes the structure holds, where the backend can count them (Embree's own allocator
    /// cannot be asked: the speed bench measures its resident memory instead).
    fn memory_bytes(&self) -> Option<usize> {
        None
    }
}

/// [`Accel::intersect_batch`] done one [`Accel::intersect`] at a time (invalid rays miss):
/// what every batched path must equal.
///
/// # Panics
/// If `rays` and `hits` differ in length.
pub fn intersect_one_by_one<A: Accel + ?Sized>(
    accel: &A,
    rays: &[Ray],
    hits: &mut [Option<Hit>],
    counters: &mut TraversalCounters,
) {
    assert_eq!(rays.len(), hits.len(), "one hit slot per ray");
    for (ray, hit) in rays.iter().zip(hits) {
        *hit = if ray.is_valid() { accel.intersect(ray, counters) } else { None };
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

/// How long a backend may spend building its BVH to make traversal faster.
///
/// Measured here (`benches/throughput.rs`, one thread, 256×256 camera rays): with Embree
/// 3.13.5 `Low` builds the 1M-triangle sphere about 10 % faster but traces 5-20 % fewer
/// rays per second; `High` is the same as `Medium`, because Embree has no spatial-split
/// builder for the robust triangle layout every scene of ours uses (`RTC_SCENE_FLAG_ROBUST`;
/// also none for user geometry and instances). obvhs: `Low` builds about 20 % faster and
/// `High` 2× slower, with whole renders within 2 % of `Medium`. Hence `Medium`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BuildQuality {
    /// Embree `RTC_BUILD_QUALITY_LOW` (its two-level Morton builder); obvhs `fastest_build`.
    Low,
    /// Embree `RTC_BUILD_QUALITY_MEDIUM` (binned SAH); obvhs `medium_build`.
    #[default]
    Medium,
    /// Embree `RTC_BUILD_QUALITY_HIGH` (SAH with spatial splits, where Embree has it: not for
    /// our robust scenes in 3.13.5); obvhs `slow_build`.
    High,
}

/// How the Embree backend traces [`Accel::intersect_batch`] (the renderer's batches of
/// camera rays); the obvhs backend traces them one at a time.
///
/// Measured here: packets of 8 trace camera rays at 1.2× (1M-triangle sphere) to 2.5×
/// (Cornell box) the rate of single rays and take 6-11 % off whole Embree renders (CPU time,
/// bundled scenes and the 1M sphere). They return the single-ray hits bit for bit, with one
/// exception: on an exact or 1-ulp tie between coincident surfaces (two faces in the same
/// plane that share no edge, e.g. a box standing on the floor seen from below, or duplicated
/// faces) Embree's packet kernel may report the other surface (see
/// `EmbreeAccel::intersect_batch`). Every bundled scene renders bit-identically either way.
/// `Single` is exact in every case, at the single-ray speed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BatchMode {
    /// One `rtcIntersect1` per ray: exactly the hits of `Accel::intersect`.
    Single,
    /// Packets of 8 rays (`rtcIntersect8`), the faster width on large meshes here.
    #[default]
    Packets8,
    /// Packets of 16 rays (`rtcIntersect16`).
    Packets16,
}

/// Options that change how a backend is built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AccelOptions {
    /// Count node visits / primitive tests (may cost time; off by default).
    pub count_traversal: bool,
    /// BVH build quality, both backends.
    pub build_quality: BuildQuality,
    /// Embree: `RTC_SCENE_FLAG_COMPACT`: a smaller BVH (triangles stored as indices), but
    /// 15-25 % fewer rays per second and renders 4-16 % slower here, so off by default.
    pub compact: bool,
    /// Embree: how batches of rays (`Accel::intersect_batch`) are traced.
    pub batch: BatchMode,
}

impl AccelOptions {
    /// The defaults (chosen by measurement, see `benches/throughput.rs`).
    pub const DEFAULT: AccelOptions = AccelOptions {
        count_traversal: false,
        build_quality: BuildQuality::Medium,
        compact: false,
        batch: BatchMode::Packets8,
    };
}

impl Default for AccelOptions {
    fn default() -> Self {
        AccelOptions::DEFAULT
    }
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
