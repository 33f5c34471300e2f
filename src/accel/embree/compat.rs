//! The few calls that differ between Embree 3 and Embree 4 (`cfg(embree4)`, set by build.rs).
//!
//! Everything else (`RTCRay`, `RTCRayHit`, geometry and buffer calls, user-geometry argument
//! structs) has the same name and layout in both, so the rest of the backend is shared.

use super::ffi;

/// Ray mask that hits every geometry: Embree 4's default geometry mask is 0x1 (Embree 3's is
/// all ones), so a mask of 0 would hit nothing there.
pub const RAY_MASK: u32 = u32::MAX;

/// The query context user-geometry callbacks receive in their `context` argument.
#[cfg(not(embree4))]
pub type QueryContext = ffi::RTCIntersectContext;
#[cfg(embree4)]
pub type QueryContext = ffi::RTCRayQueryContext;

/// Closest hit for one ray; Embree updates `rayhit` in place.
///
/// # Safety
/// `scene` must be a live, committed scene.
#[cfg(not(embree4))]
pub unsafe fn intersect1(scene: ffi::RTCScene, rayhit: &mut ffi::RTCRayHit) {
    let mut context = intersect_context();
    // SAFETY: the caller guarantees `scene`; `context` and `rayhit` are valid for the call.
    unsafe { ffi::rtcIntersect1(scene, &mut context, rayhit) }
}

/// Occlusion test for one ray; Embree sets `ray.tfar = -inf` if anything is hit.
///
/// # Safety
/// `scene` must be a live, committed scene.
#[cfg(not(embree4))]
pub unsafe fn occluded1(scene: ffi::RTCScene, ray: &mut ffi::RTCRay) {
    let mut context = intersect_context();
    // SAFETY: the caller guarantees `scene`; `context` and `ray` are valid for the call.
    unsafe { ffi::rtcOccluded1(scene, &mut context, ray) }
}

/// `rtcInitIntersectContext` from `rtcore_common.h`: an inline function, so not exported.
#[cfg(not(embree4))]
fn intersect_context() -> ffi::RTCIntersectContext {
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

/// Closest hit for one ray; Embree updates `rayhit` in place.
///
/// # Safety
/// `scene` must be a live, committed scene.
#[cfg(embree4)]
pub unsafe fn intersect1(scene: ffi::RTCScene, rayhit: &mut ffi::RTCRayHit) {
    // SAFETY: the caller guarantees `scene`; `rayhit` is valid for the call, and null
    // arguments mean Embree's defaults (incoherent rays, all features, no filter).
    unsafe { ffi::rtcIntersect1(scene, rayhit, std::ptr::null_mut()) }
}

/// Occlusion test for one ray; Embree sets `ray.tfar = -inf` if anything is hit.
///
/// # Safety
/// `scene` must be a live, committed scene.
#[cfg(embree4)]
pub unsafe fn occluded1(scene: ffi::RTCScene, ray: &mut ffi::RTCRay) {
    // SAFETY: as for `intersect1`; null arguments mean Embree's defaults.
    unsafe { ffi::rtcOccluded1(scene, ray, std::ptr::null_mut()) }
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
