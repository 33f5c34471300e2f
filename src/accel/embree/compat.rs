//! The few calls that differ between Embree 3 and Embree 4 (`cfg(embree4)`, set by build.rs).
//!
//! Everything else (`RTCRay`, `RTCRayHit`, geometry and buffer calls, user-geometry argument
//! structs) has the same name and layout in both, so the rest of the backend is shared.
//!
//! Every ray query of the backend goes through [`intersect1`] / [`occluded1`], which always
//! pass a [`CountingContext`] as the query context. User-geometry callbacks rely on that:
//! [`count_prim_tests`] reads the counters pointer that follows Embree's own context.

use super::ffi;
pub use crate::accel::Coherence;

mod packets;
use crate::stats::TraversalCounters;
pub use packets::*;

/// Instance levels in the bindings' hit and context structs (1 in every Embree we build with).
const LEVELS: usize = ffi::RTC_MAX_INSTANCE_LEVEL_COUNT as usize;

/// `T` followed by room for `instPrimID[LEVELS][LANES]`, the instance-primitive ids Embree
/// 4.3 and later append to every hit (`RTCHit`, `RTCHitN`) and query context when built with
/// instance arrays, which is their default (Debian 13's and the embreex wheel's are).
///
/// The Embree 4.2 headers `embree4-sys` vendors do not declare that field, so with those
/// bindings a 4.3+ library writes it past the end of our structs: that corrupted the stack
/// and returned wrong geometry ids on Embree 4.4 before this existed. Embree writes exactly
/// there, since each of these structs ends on a multiple of its alignment. We never read
/// the ids (we build no instance arrays). For Embree 3, and for bindings generated from a
/// header that declares the field, the room is simply unused.
#[repr(C)]
pub struct Padded<T, const LANES: usize> {
    pub inner: T,
    instance_prim_ids: [[u32; LANES]; LEVELS],
}

impl<T, const LANES: usize> Padded<T, LANES> {
    pub fn new(inner: T) -> Self {
        Padded { inner, instance_prim_ids: [[ffi::RTC_INVALID_GEOMETRY_ID; LANES]; LEVELS] }
    }

    /// The pointer to hand Embree: derived from the whole struct, so that Embree's writes to
    /// the padding stay within what the pointer may access.
    pub fn as_mut_ptr(&mut self) -> *mut T {
        std::ptr::from_mut(self).cast()
    }
}

impl<T, const LANES: usize> std::ops::Deref for Padded<T, LANES> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.inner
    }
}

impl<T, const LANES: usize> std::ops::DerefMut for Padded<T, LANES> {
    fn deref_mut(&mut self) -> &mut T {
        &mut self.inner
    }
}

/// A single-ray hit record with room for Embree 4.3+'s `instPrimID` (see [`Padded`]).
pub type RayHit = Padded<ffi::RTCRayHit, 1>;

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
    /// Embree's context, and room for the instance-primitive id stack that Embree 4.3+
    /// keeps in it (see [`Padded`]), before our field.
    base: Padded<QueryContext, 1>,
    /// Null when the query does not count (normal mode); otherwise the caller's counters,
    /// exclusively ours for the duration of the query.
    counters: *mut TraversalCounters,
}

impl CountingContext {
    #[inline]
    fn new(counters: Option<&mut TraversalCounters>) -> Self {
        CountingContext {
            base: Padded::new(query_context()),
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
#[inline]
pub unsafe fn intersect1(
    scene: ffi::RTCScene,
    rayhit: &mut RayHit,
    counters: Option<&mut TraversalCounters>,
) {
    let mut context = CountingContext::new(counters);
    // SAFETY: the caller guarantees `scene`; `context` and `rayhit` are valid for the call.
    unsafe { ffi::rtcIntersect1(scene, context.as_query_context(), rayhit.as_mut_ptr()) }
}

/// Occlusion test for one ray; Embree sets `ray.tfar = -inf` if anything is hit. With
/// `counters`, counting-mode callbacks add their primitive tests to it.
///
/// # Safety
/// `scene` must be a live, committed scene.
#[cfg(not(embree4))]
#[inline]
pub unsafe fn occluded1(
    scene: ffi::RTCScene,
    ray: &mut ffi::RTCRay,
    counters: Option<&mut TraversalCounters>,
) {
    let mut context = CountingContext::new(counters);
    // SAFETY: the caller guarantees `scene`; `context` and `ray` are valid for the call.
    unsafe { ffi::rtcOccluded1(scene, context.as_query_context(), ray) }
}

/// The `valid` argument of a packet query: -1 for a lane to trace, 0 for one Embree must
/// ignore. Aligned to 64 bytes, the strictest requirement (`rtcIntersect16`); packets of 4
/// and 8 read only their first 4 or 8 entries.
#[repr(C, align(64))]
#[derive(Clone, Copy)]
pub struct ValidMask(pub [i32; 16]);

impl ValidMask {
    /// Whether any lane is marked to trace.
    pub fn any(&self) -> bool {
        self.0.iter().any(|&v| v != 0)
    }
}

/// Closest hits for a stream of rays (`rtcIntersect1M`, Embree 3 only), in place; never
/// counts. `coherent` selects Embree's stream traversal for coherent rays (else it traces
/// packets of the native SIMD width).
///
/// # Safety
/// `scene` must be a live, committed scene and every ray one `Ray::is_valid` and Embree
/// accept.
#[cfg(not(embree4))]
pub unsafe fn intersect_stream(
    scene: ffi::RTCScene,
    rayhits: &mut [ffi::RTCRayHit],
    coherent: bool,
) {
    let mut context = CountingContext::new(None);
    if coherent {
        context.base.inner.flags =
            ffi::RTCIntersectContextFlags::RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    }
    let Ok(count) = u32::try_from(rayhits.len()) else {
        for chunk in rayhits.chunks_mut(u32::MAX as usize) {
            // SAFETY: per the caller (a sub-slice of the caller's rays).
            unsafe { intersect_stream(scene, chunk, coherent) };
        }
        return;
    };
    // SAFETY: per the caller; `rayhits` holds `count` records `size_of::<RTCRayHit>()`
    // bytes apart (Embree's AOS layout), and they and the context are valid for the call.
    unsafe {
        ffi::rtcIntersect1M(
            scene,
            context.as_query_context(),
            rayhits.as_mut_ptr(),
            count,
            std::mem::size_of::<ffi::RTCRayHit>(),
        )
    }
}

/// A query context made once for a loop of single-ray queries (what a bare `rtcIntersect1`
/// loop in C does): never counts.
pub struct SingleRayLoop {
    context: CountingContext,
    #[cfg(embree4)]
    args: ffi::RTCIntersectArguments,
}

impl SingleRayLoop {
    pub fn new() -> Box<Self> {
        // Boxed: under Embree 4, `args` points into `context`, so the two must not move.
        #[cfg(not(embree4))]
        let this = Box::new(SingleRayLoop { context: CountingContext::new(None) });
        #[cfg(embree4)]
        let this = {
            let mut this = Box::new(SingleRayLoop {
                context: CountingContext::new(None),
                // SAFETY: as in `intersect_arguments`.
                args: unsafe { std::mem::zeroed() },
            });
            let this_ref = &mut *this;
            this_ref.args =
                intersect_arguments(&mut this_ref.context, ffi::RTCRayQueryFlags::INCOHERENT);
            this
        };
        this
    }

    /// `rtcIntersect1` with the loop's context.
    ///
    /// # Safety
    /// As for [`intersect1`].
    #[inline]
    pub unsafe fn intersect1(&mut self, scene: ffi::RTCScene, rayhit: &mut RayHit) {
        // SAFETY: per the caller; the context (and Embree 4's arguments pointing to it) live
        // in `self`, which does not move during the call.
        #[cfg(not(embree4))]
        unsafe {
            ffi::rtcIntersect1(scene, self.context.as_query_context(), rayhit.as_mut_ptr())
        }
        // SAFETY: as above.
        #[cfg(embree4)]
        unsafe {
            ffi::rtcIntersect1(scene, rayhit.as_mut_ptr(), &mut self.args)
        }
    }
}

/// `rtcInitOccludedArguments` with `context`, incoherent (what every occlusion query of
/// ours is: single shadow rays, or many paths' shadow rays in a packet).
#[cfg(embree4)]
fn occluded_arguments(context: &mut CountingContext) -> ffi::RTCOccludedArguments {
    // SAFETY: flags, pointers and `Option<fn>`s, for which all-zero bytes are valid (null,
    // `None`).
    let mut args: ffi::RTCOccludedArguments = unsafe { std::mem::zeroed() };
    args.flags = ffi::RTCRayQueryFlags::INCOHERENT;
    args.feature_mask = ffi::RTCFeatureFlags::RTC_FEATURE_FLAG_ALL;
    args.context = context.as_query_context();
    args
}

/// `rtcInitIntersectArguments` with `context` and `flags`.
#[cfg(embree4)]
fn intersect_arguments(
    context: &mut CountingContext,
    flags: ffi::RTCRayQueryFlags,
) -> ffi::RTCIntersectArguments {
    // SAFETY: flags, pointers and `Option<fn>`s, for which all-zero bytes are valid (null,
    // `None`); zero also covers the optional `minWidthDistanceFactor`.
    let mut args: ffi::RTCIntersectArguments = unsafe { std::mem::zeroed() };
    args.flags = flags;
    args.feature_mask = ffi::RTCFeatureFlags::RTC_FEATURE_FLAG_ALL;
    args.context = context.as_query_context();
    args
}

/// `rtcInitIntersectContext` from `rtcore_common.h`: an inline function, so not exported.
#[cfg(not(embree4))]
#[inline]
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
    rayhit: &mut RayHit,
    counters: Option<&mut TraversalCounters>,
) {
    let mut context = CountingContext::new(counters);
    let mut args = intersect_arguments(&mut context, ffi::RTCRayQueryFlags::INCOHERENT);
    // SAFETY: the caller guarantees `scene`; `rayhit`, `args` and the context it points to
    // are valid for the call.
    unsafe { ffi::rtcIntersect1(scene, rayhit.as_mut_ptr(), &mut args) }
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
    let mut args = occluded_arguments(&mut context);
    // SAFETY: as in `intersect1`; `args` points to `context`, both live.
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
