//! Conversions between our `Ray`/`Hit` and Embree's single-ray structs.

use super::{compat, ffi};
use crate::accel::{Hit, Ray};

/// Embree's ray for `ray`, its time clamped to the shutter interval [0, 1]. Only call with a
/// ray that satisfies `Ray::is_valid`: Debian's Embree aborts the process on NaN/Inf rays.
pub fn to_rtc_ray(ray: &Ray) -> ffi::RTCRay {
    // SAFETY: `RTCRay` holds only f32/u32 fields, for which all-zero bytes are valid.
    let mut r: ffi::RTCRay = unsafe { std::mem::zeroed() };
    [r.org_x, r.org_y, r.org_z] = ray.origin.to_array();
    [r.dir_x, r.dir_y, r.dir_z] = ray.dir.to_array();
    r.tnear = ray.tmin;
    r.tfar = ray.tmax;
    // Debian's Embree asserts (aborts the process) on a time outside [0, 1] when it
    // traverses a motion BVH; the shutter interval is [0, 1] anyway. `Ray::is_valid`
    // guarantees a finite time.
    r.time = ray.time.clamp(0.0, 1.0);
    r.mask = compat::RAY_MASK;
    r
}

/// Embree's ray-and-hit record for `ray`, with no hit yet.
pub fn to_rtc_ray_hit(ray: &Ray) -> ffi::RTCRayHit {
    // SAFETY: `RTCRayHit` holds only f32/u32 fields and arrays of them, for which all-zero
    // bytes are valid. Zeroing (rather than a struct literal) also covers hit fields that
    // only some Embree versions have.
    let mut rh: ffi::RTCRayHit = unsafe { std::mem::zeroed() };
    rh.ray = to_rtc_ray(ray);
    rh.hit.geomID = ffi::RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID = [ffi::RTC_INVALID_GEOMETRY_ID; ffi::RTC_MAX_INSTANCE_LEVEL_COUNT as usize];
    rh
}

/// The hit Embree recorded, if any.
///
/// Through an instance, Embree reports the instance's id in the top scene as `instID[0]`
/// and the child scene's geometry (always 0 here) as `geomID`; our geometry id is the
/// instance's. Geometry attached directly to the top scene has `instID[0]` invalid. We never
/// nest instances, so one level (`RTC_MAX_INSTANCE_LEVEL_COUNT = 1`) is enough. `t`, `u`,
/// `v` and `primID` need no mapping: `t` is along the render-space ray (Embree transforms
/// the ray into the instance without renormalising its direction) and the barycentrics
/// are the object-space triangle's, as `surface.rs` expects.
pub fn from_rtc_ray_hit(rh: &ffi::RTCRayHit) -> Option<Hit> {
    let instance = rh.hit.instID[0];
    let geom_id = if instance == ffi::RTC_INVALID_GEOMETRY_ID { rh.hit.geomID } else { instance };
    (rh.hit.geomID != ffi::RTC_INVALID_GEOMETRY_ID).then_some(Hit {
        t: rh.ray.tfar,
        geom_id,
        prim_id: rh.hit.primID,
        u: rh.hit.u,
        v: rh.hit.v,
    })
}
