//! Conversions between our `Ray`/`Hit` and Embree's single-ray structs.

use super::{compat, ffi};
use crate::accel::{Hit, Ray};

/// Embree's ray for `ray`. Only call with a ray that satisfies `Ray::is_valid`: Debian's
/// Embree aborts the process on NaN/Inf rays.
pub fn to_rtc_ray(ray: &Ray) -> ffi::RTCRay {
    // SAFETY: `RTCRay` holds only f32/u32 fields, for which all-zero bytes are valid.
    let mut r: ffi::RTCRay = unsafe { std::mem::zeroed() };
    [r.org_x, r.org_y, r.org_z] = ray.origin.to_array();
    [r.dir_x, r.dir_y, r.dir_z] = ray.dir.to_array();
    r.tnear = ray.tmin;
    r.tfar = ray.tmax;
    r.time = ray.time;
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
pub fn from_rtc_ray_hit(rh: &ffi::RTCRayHit) -> Option<Hit> {
    (rh.hit.geomID != ffi::RTC_INVALID_GEOMETRY_ID).then_some(Hit {
        t: rh.ray.tfar,
        geom_id: rh.hit.geomID,
        prim_id: rh.hit.primID,
        u: rh.hit.u,
        v: rh.hit.v,
    })
}
