//! The few calls that differ between Embree 3 and Embree 4 (`cfg(embree4)`, set by build.rs).
//!
//! Everything else (`RTCRay`, `RTCRayHit`, geometry and buffer calls, user-geometry argument
//! structs) has the same name and layout in both, so the rest of the backend is shared.
//!
//! Every ray query of the backend goes through [`intersect1`] / [`occluded1`], which always
//! pass a [`CountingContext`] as the query context. User-geometry callbacks rely on that:
//! [`count_prim_tests`] reads the counters pointer that follows Embree's own context.

use super::ffi;
use crate::stats::TraversalCounters;

/// Ray mask that hits every geometry: Embree 4's default geometry mask is 0x1 (Embree 3's is
/// all ones), so a mask of 0 would hit nothing there.
pub const RAY_MASK: u32 = u32::MAX;

/// The query context user-geometry callbacks receive in their `context` argument.
#[cfg(not(embree4))]
pub type QueryContext = ffi::RTCIntersectContext;
#[cfg(embree4)]
pub type QueryContext = ffi::RTCRayQueryContext;

/// Embree's query context extended with where counting-mode callbacks add their tests.
///
/// Both Embree 3 (`RTCIntersectContext`) and Embree 4 (`RTCRayQueryContext`) document this
/// way of passing data to callbacks: a struct whose first member is Embree's context. Embree
/// hands each user-geometry callback the very pointer given to the query, so with
/// `#[repr(C)]` (the context at offset 0) a callback can cast it back and reach `counters`.
#[repr(C)]
struct CountingContext {
    base: QueryContext,
    /// Null when the query does not count (normal mode); otherwise the caller's counters,
    /// exclusively ours for the duration of the query.
    counters: *mut TraversalCounters,
}

impl CountingContext {
    fn new(counters: Option<&mut TraversalCounters>) -> Self {
        CountingContext {
            base: query_context(),
            counters: counters.map_or(std::ptr::null_mut(), std::ptr::from_mut),
        }
    }

    /// The pointer to hand Embree: derived from the whole struct (not from `base` alone), so
    /// callbacks may read `counters` through it.
    fn as_query_context(&mut self) -> *mut QueryContext {
        std::ptr::from_mut(self).cast()
    }
}

/// Adds `tests` primitive tests to the counters of the running query, if it counts.
///
/// # Safety
/// `context` must be null or the context pointer Embree passed to the running callback, for
/// a query made through [`intersect1`] or [`occluded1`] (as every query of this backend is).
pub unsafe fn count_prim_tests(context: *const QueryContext, tests: u64) {
    if context.is_null() {
        return;
    }
    // SAFETY: per the caller, `context` is the pointer `intersect1`/`occluded1` passed to
    // Embree, which Embree hands unchanged to the callbacks: it points to a live
    // `CountingContext` (derived from the whole struct, see `as_query_context`), so reading
    // its `counters` field is in bounds. A non-null `counters` came from the `&mut` the query
    // was given and is used by nobody else until the query returns; Embree runs the
    // callbacks of a single-ray query on the calling thread, one at a time.
    unsafe {
        let counters = (*context.cast::<CountingContext>()).counters;
        if let Some(counters) = counters.as_mut() {
            counters.prim_tests += tests;
        }
    }
}

/// Closest hit for one ray; Embree updates `rayhit` in place. With `counters`, counting-mode
/// callbacks add their primitive tests to it.
///
/// # Safety
/// `scene` must be a live, committed scene.
#[cfg(not(embree4))]
pub unsafe fn intersect1(
    scene: ffi::RTCScene,
    rayhit: &mut ffi::RTCRayHit,
    counters: Option<&mut TraversalCounters>,
) {
    let mut context = CountingContext::new(counters);
    // SAFETY: the caller guarantees `scene`; `context` and `rayhit` are valid for the call.
    unsafe { ffi::rtcIntersect1(scene, context.as_query_context(), rayhit) }
}

/// Occlusion test for one ray; Embree sets `ray.tfar = -inf` if anything is hit. With
/// `counters`, counting-mode callbacks add their primitive tests to it.
///
/// # Safety
/// `scene` must be a live, committed scene.
#[cfg(not(embree4))]
pub unsafe fn occluded1(
    scene: ffi::RTCScene,
    ray: &mut ffi::RTCRay,
    counters: Option<&mut TraversalCounters>,
) {
    let mut context = CountingContext::new(counters);
    // SAFETY: the caller guarantees `scene`; `context` and `ray` are valid for the call.
    unsafe { ffi::rtcOccluded1(scene, context.as_query_context(), ray) }
}

/// `rtcInitIntersectContext` from `rtcore_common.h`: an inline function, so not exported.
#[cfg(not(embree4))]
fn query_context() -> ffi::RTCIntersectContext {
    // SAFETY: the struct holds only integers, integer arrays and an `Option<fn>`, for which
    // all-zero bytes are valid (`None`). Zeroing first also covers the fields that exist
    // only in some Embree configurations (`instStackSize`, `minWidthDistanceFactor`),
    // whose initial value is 0.
    let mut context: ffi::RTCIntersectContext = unsafe { std::mem::zeroed() };
    context.flags = ffi::RTCIntersectContextFlags::RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    context.filter = None;
    context.instID = [ffi::RTC_INVALID_GEOMETRY_ID; ffi::RTC_MAX_INSTANCE_LEVEL_COUNT as usize];
    context
}

/// `rtcInitRayQueryContext` from `rtcore_common.h`: an inline function, so not exported.
#[cfg(embree4)]
fn query_context() -> ffi::RTCRayQueryContext {
    // SAFETY: the struct holds only integers and integer arrays; zeroing also covers
    // `instStackSize`, which exists only in some configurations and starts at 0.
    let mut context: ffi::RTCRayQueryContext = unsafe { std::mem::zeroed() };
    context.instID = [ffi::RTC_INVALID_GEOMETRY_ID; ffi::RTC_MAX_INSTANCE_LEVEL_COUNT as usize];
    context
}

/// Closest hit for one ray; Embree updates `rayhit` in place. With `counters`, counting-mode
/// callbacks add their primitive tests to it.
///
/// # Safety
/// `scene` must be a live, committed scene.
#[cfg(embree4)]
pub unsafe fn intersect1(
    scene: ffi::RTCScene,
    rayhit: &mut ffi::RTCRayHit,
    counters: Option<&mut TraversalCounters>,
) {
    let mut context = CountingContext::new(counters);
    // `rtcInitIntersectArguments`, plus our context. SAFETY: flags, pointers and
    // `Option<fn>`s, for which all-zero bytes are valid (null, `None`); zero also covers the
    // optional `minWidthDistanceFactor`.
    let mut args: ffi::RTCIntersectArguments = unsafe { std::mem::zeroed() };
    args.flags = ffi::RTCRayQueryFlags::INCOHERENT;
    args.feature_mask = ffi::RTCFeatureFlags::RTC_FEATURE_FLAG_ALL;
    args.context = context.as_query_context();
    // SAFETY: the caller guarantees `scene`; `rayhit`, `args` and the context it points to
    // are valid for the call.
    unsafe { ffi::rtcIntersect1(scene, rayhit, &mut args) }
}

/// Occlusion test for one ray; Embree sets `ray.tfar = -inf` if anything is hit. With
/// `counters`, counting-mode callbacks add their primitive tests to it.
///
/// # Safety
/// `scene` must be a live, committed scene.
#[cfg(embree4)]
pub unsafe fn occluded1(
    scene: ffi::RTCScene,
    ray: &mut ffi::RTCRay,
    counters: Option<&mut TraversalCounters>,
) {
    let mut context = CountingContext::new(counters);
    // `rtcInitOccludedArguments`, plus our context. SAFETY: as in `intersect1`.
    let mut args: ffi::RTCOccludedArguments = unsafe { std::mem::zeroed() };
    args.flags = ffi::RTCRayQueryFlags::INCOHERENT;
    args.feature_mask = ffi::RTCFeatureFlags::RTC_FEATURE_FLAG_ALL;
    args.context = context.as_query_context();
    // SAFETY: as in `intersect1`.
    unsafe { ffi::rtcOccluded1(scene, ray, &mut args) }
}

/// Innermost instance id of a query (what a user geometry writes to `hit.instID[0]`);
/// `RTC_INVALID_GEOMETRY_ID` outside instances. Same field in both versions' context types.
///
/// # Safety
/// `context` must be null or the context pointer Embree passed to the running callback.
pub unsafe fn instance_id(context: *const QueryContext) -> u32 {
    if context.is_null() {
        return ffi::RTC_INVALID_GEOMETRY_ID;
    }
    // SAFETY: non-null and, per the caller, valid for the duration of the callback.
    unsafe { (*context).instID[0] }
}
