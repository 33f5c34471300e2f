//! Packet queries (`rtcIntersect4/8/16`, `rtcOccluded4/8/16`): the same names and layouts
//! in Embree 3 and 4, called with each version's query context or arguments.

use super::{Coherence, CountingContext, Padded, ValidMask, ffi};
#[cfg(embree4)]
use super::{intersect_arguments, occluded_arguments};

/// Packet queries (`rtcIntersect4/8/16`) of the same width in both versions; they never
/// count (counting mode traces one ray at a time). Generates, per width, a function
/// `$name(scene, valid, rayhit, coherence)`.
///
/// # Safety (of the generated functions)
/// `scene` must be a live, committed scene, and every lane `valid` marks -1 must hold a ray
/// `Ray::is_valid` and Embree accept (Debian's Embree aborts the process otherwise).
macro_rules! packet_intersect {
    ($($name:ident: $packet:ident, $width:literal, $ffi:ident;)*) => {$(
        /// Closest hits for the lanes of `rayhit` that `valid` marks -1, in place.
        ///
        /// # Safety
        /// See `packet_intersect!`.
        pub unsafe fn $name(
            scene: ffi::RTCScene,
            valid: &ValidMask,
            rayhit: &mut Padded<ffi::$packet, $width>,
            coherence: Coherence,
        ) {
            let mut context = CountingContext::new(None);
            #[cfg(not(embree4))]
            {
                if coherence == Coherence::Coherent {
                    context.base.inner.flags =
                        ffi::RTCIntersectContextFlags::RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
                }
                // SAFETY: per the caller; `valid` is 64-byte aligned and at least as wide
                // as the packet, `rayhit` is aligned by its type, and both and the context
                // are valid for the call.
                unsafe {
                    ffi::$ffi(valid.0.as_ptr(), scene, context.as_query_context(), rayhit.as_mut_ptr())
                }
            }
            #[cfg(embree4)]
            {
                let flags = match coherence {
                    Coherence::Coherent => ffi::RTCRayQueryFlags::COHERENT,
                    Coherence::Incoherent => ffi::RTCRayQueryFlags::INCOHERENT,
                };
                let mut args = intersect_arguments(&mut context, flags);
                // SAFETY: as for Embree 3; `args` points to `context`, both live.
                unsafe { ffi::$ffi(valid.0.as_ptr(), scene, rayhit.as_mut_ptr(), &mut args) }
            }
        }
    )*};
}

packet_intersect! {
    intersect4: RTCRayHit4, 4, rtcIntersect4;
    intersect8: RTCRayHit8, 8, rtcIntersect8;
    intersect16: RTCRayHit16, 16, rtcIntersect16;
}

/// Packet occlusion queries (`rtcOccluded4/8/16`), as `packet_intersect!` for closest hits:
/// Embree sets `tfar` to -inf in every valid lane that is blocked. Incoherent (shadow rays
/// of many paths' bounces).
///
/// # Safety (of the generated functions)
/// As for `packet_intersect!`.
macro_rules! packet_occluded {
    ($($name:ident: $packet:ident, $ffi:ident;)*) => {$(
        /// Occlusion of the lanes of `ray` that `valid` marks -1, in place.
        ///
        /// # Safety
        /// See `packet_occluded!`.
        pub unsafe fn $name(scene: ffi::RTCScene, valid: &ValidMask, ray: &mut ffi::$packet) {
            let mut context = CountingContext::new(None);
            // SAFETY: per the caller; `valid` is 64-byte aligned and at least as wide as
            // the packet, and it, `ray` and the context are valid for the call.
            #[cfg(not(embree4))]
            unsafe {
                ffi::$ffi(valid.0.as_ptr(), scene, context.as_query_context(), ray)
            }
            #[cfg(embree4)]
            {
                let mut args = occluded_arguments(&mut context);
                // SAFETY: as for Embree 3; `args` points to `context`, both live.
                unsafe { ffi::$ffi(valid.0.as_ptr(), scene, ray, &mut args) }
            }
        }
    )*};
}

packet_occluded! {
    occluded4: RTCRay4, rtcOccluded4;
    occluded8: RTCRay8, rtcOccluded8;
    occluded16: RTCRay16, rtcOccluded16;
}
