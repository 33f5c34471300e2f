//! How a backend is chosen and built: the backend, its build quality, the batch mode of the
//! Embree backend and the options passed to `accel::build`.

use crate::choice::named_choices;

/// Which backend to build.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BackendKind {
    Embree,
    Obvhs,
}

impl BackendKind {
    /// The memory one mesh triangle costs a render on this backend (`crate::limits`).
    pub fn bytes_per_triangle(self) -> u64 {
        match self {
            BackendKind::Embree => crate::limits::BYTES_PER_TRIANGLE_EMBREE,
            BackendKind::Obvhs => crate::limits::BYTES_PER_TRIANGLE_OBVHS,
        }
    }
}

/// How long a backend may spend building its BVH to make traversal faster.
///
/// Measured here (`benches/throughput.rs`, one thread, 256×256 camera rays): with Embree
/// 3.13.5 `Low` builds the 1M-triangle sphere about 10 % faster but traces 5-20 % fewer
/// rays per second; `High` is the same as `Medium`, because Embree has no spatial-split
/// builder for the robust triangle layout our scenes use by default
/// (`RTC_SCENE_FLAG_ROBUST`, `Intersection::Robust`; also none for user geometry and
/// instances). obvhs: `Low` builds about 20 % faster and `High` 2× slower, with whole
/// renders within 2 % of `Medium`. Hence `Medium`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BuildQuality {
    /// Embree `RTC_BUILD_QUALITY_LOW` (its two-level Morton builder); obvhs `fastest_build`.
    Low,
    /// Embree `RTC_BUILD_QUALITY_MEDIUM` (binned SAH); obvhs `medium_build`.
    #[default]
    Medium,
    /// Embree `RTC_BUILD_QUALITY_HIGH` (SAH with spatial splits, where Embree has it: not for
    /// robust scenes in 3.13.5, see `Intersection`); obvhs `slow_build`.
    High,
}

/// How the Embree backend traces batches of rays ([`Accel::intersect_batch`],
/// [`Accel::occluded_batch`]: the batched path tracer's camera, bounce and shadow rays); the
/// obvhs backend traces them one at a time.
///
/// Measured here (`embray bench queries`, one thread, AVX-512 EPYC, Embree 3.13.5, ns per
/// ray for camera / bounce / shadow rays): on the Cornell box single rays cost 74 / 101 /
/// 75, packets of 8 22 / 78 / 50, packets of 16 16 / 79 / 42; on the city block 80 / 88 /
/// 59, 34 / 72 / 38 and 31 / 72 / 35. Packets return the single-ray hits bit for bit, with
/// one exception: on an exact or 1-ulp tie between coincident surfaces (two faces in the
/// same plane that share no edge, e.g. a box standing on the floor seen from below, or
/// duplicated faces) Embree's packet kernel may report the other surface (see
/// `EmbreeAccel::intersect_batch`). Every bundled scene renders bit-identically either way.
/// `Single` is exact in every case, at the single-ray speed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BatchMode {
    /// Packets as wide as Embree's kernels on this CPU: 16 with AVX-512, else 8.
    #[default]
    Native,
    /// One `rtcIntersect1` / `rtcOccluded1` per ray: exactly the hits of `Accel::intersect`.
    Single,
    /// Packets of 8 rays (`rtcIntersect8`, `rtcOccluded8`).
    Packets8,
    /// Packets of 16 rays (`rtcIntersect16`, `rtcOccluded16`).
    Packets16,
}

/// How Embree tests rays against triangles (the obvhs backend has one test, and ignores this).
///
/// `Robust` (`RTC_SCENE_FLAG_ROBUST`) is watertight: a ray through an edge or a vertex that
/// triangles share hits one of them, never slips between them.
/// `Fast` (`RTC_SCENE_FLAG_NONE`, Mitsuba 3's setting) is Embree's default test, which may
/// let such a ray through, and lets `BuildQuality::High` build spatial splits. Measured
/// (AMD EPYC, AVX2, 256², alternated pairs, medians): `Fast` renders the Cornell box in
/// 0.87× the wall time (15 pairs, 16 spp) and the city block in 0.95× (7 pairs). At 64 spp
/// with the same seed, 12 % of the Cornell box's pixels differ (glass 2 %, city block
/// under 0.1 %), by at most 0.009, hit points rounded otherwise; each image's mean moves by
/// less than 4e-7 of itself.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Intersection {
    #[default]
    Robust,
    Fast,
}

/// Whether the rays of a batch start near each other and point the same way (a tile's
/// camera rays), or not (bounces). Embree's coherent packet traversal traces camera rays
/// about 3x faster and bounce rays about 15 % slower than its incoherent one (measured on
/// the Cornell box, AVX-512; `embray bench queries` measures each kind).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coherence {
    Coherent,
    Incoherent,
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
    /// Embree: watertight or fast triangle tests.
    pub intersection: Intersection,
}

impl AccelOptions {
    /// The defaults (chosen by measurement, see `benches/throughput.rs`).
    pub const DEFAULT: AccelOptions = AccelOptions {
        count_traversal: false,
        build_quality: BuildQuality::Medium,
        compact: false,
        batch: BatchMode::Native,
        intersection: Intersection::Robust,
    };
}

impl Default for AccelOptions {
    fn default() -> Self {
        AccelOptions::DEFAULT
    }
}

named_choices!(BackendKind, "backend", {
    Embree => "embree",
    Obvhs => "obvhs",
});

named_choices!(BuildQuality, "build quality", {
    Low => "low",
    Medium => "medium",
    High => "high",
});

named_choices!(BatchMode, "batch mode", {
    Native => "native",
    Single => "single",
    Packets8 => "packets8",
    Packets16 => "packets16",
});

named_choices!(Intersection, "intersection", {
    Robust => "robust",
    Fast => "fast",
});
