//! Conversions between our `Ray`/`Hit` and Embree's single-ray structs.

use super::{compat, ffi};
use crate::ray::{Hit, Ray};
use crate::ray_columns::{BLOCK, RayBlock};

/// Embree's ray for `ray`, its time clamped to the shutter interval [0, 1]. Only call with a
/// ray that satisfies `Ray::is_valid`: Debian's Embree aborts the process on NaN/Inf rays.
#[inline]
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
#[inline]
pub fn to_rtc_ray_hit(ray: &Ray) -> compat::RayHit {
    // SAFETY: `RTCRayHit` holds only f32/u32 fields and arrays of them, for which all-zero
    // bytes are valid. Zeroing (rather than a struct literal) also covers hit fields that
    // only some Embree versions have.
    let mut rh: ffi::RTCRayHit = unsafe { std::mem::zeroed() };
    rh.ray = to_rtc_ray(ray);
    rh.hit.geomID = ffi::RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID = [ffi::RTC_INVALID_GEOMETRY_ID; ffi::RTC_MAX_INSTANCE_LEVEL_COUNT as usize];
    compat::RayHit::new(rh)
}

/// The hit Embree recorded, if any.
///
/// Through an instance, Embree reports the instance's id in the top scene as `instID[0]`
/// and the child scene's geometry (always 0 here) as `geomID`; our geometry id is the
/// instance's. GeometryHandle attached directly to the top scene has `instID[0]` invalid. We never
/// nest instances, so one level (`RTC_MAX_INSTANCE_LEVEL_COUNT = 1`) is enough. `t`, `u`,
/// `v` and `primID` need no mapping: `t` is along the render-space ray (Embree transforms
/// the ray into the instance without renormalising its direction) and the barycentrics
/// are the object-space triangle's, as `surface.rs` expects.
#[inline]
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

/// An Embree ray-hit packet (`RTCRayHit4/8/16`, SOA: every field an array of `WIDTH` lanes).
pub trait RayHitPacket {
    const WIDTH: usize;
    /// A packet whose lanes hold a harmless ray (never traced: its lane is masked out) and
    /// no hit.
    fn empty() -> Self;
    /// Lane `lane` becomes `ray` (see [`to_rtc_ray`]). Its mask, id and flags stay those
    /// `empty` set (Embree never writes them), and its hit fields stay as they were:
    /// `clear_hits` clears them for a closest-hit query (an occlusion query never reads them).
    fn set_lane(&mut self, lane: usize, ray: &Ray);
    /// Lanes `at..at + BLOCK` become the rays of `block` (as `set_lane` sets each), a
    /// column at a time.
    ///
    /// # Panics
    /// If the packet has no such lanes.
    fn set_block(&mut self, at: usize, block: &RayBlock);
    /// No lane has a hit.
    fn clear_hits(&mut self);
    /// The hit Embree recorded in lane `lane`, if any (see [`from_rtc_ray_hit`]).
    fn hit(&self, lane: usize) -> Option<Hit>;
    /// Traces the lanes `valid` marks -1.
    ///
    /// # Safety
    /// `scene` must be a live, committed scene, and every lane marked -1 must have been set
    /// from a ray Embree accepts (`scene::embree_accepts`).
    unsafe fn intersect(
        &mut self,
        scene: ffi::RTCScene,
        valid: &compat::ValidMask,
        coherence: compat::Coherence,
    );
    /// Tests the lanes `valid` marks -1 for occlusion (the packet's rays only).
    ///
    /// # Safety
    /// As for [`RayHitPacket::intersect`].
    unsafe fn occluded(&mut self, scene: ffi::RTCScene, valid: &compat::ValidMask);
    /// Whether `occluded` found lane `lane` blocked.
    fn blocked(&self, lane: usize) -> bool;
}

macro_rules! ray_hit_packet {
    ($($packet:ident: $width:literal, $intersect:ident, $occluded:ident;)*) => {$(
        impl RayHitPacket for compat::Padded<ffi::$packet, $width> {
            const WIDTH: usize = $width;

            fn empty() -> Self {
                // SAFETY: f32/u32 arrays only, for which all-zero bytes are valid.
                let mut p: ffi::$packet = unsafe { std::mem::zeroed() };
                p.ray.dir_z = [1.0; $width];
                p.ray.tfar = [f32::INFINITY; $width];
                p.ray.mask = [compat::RAY_MASK; $width];
                p.hit.geomID = [ffi::RTC_INVALID_GEOMETRY_ID; $width];
                p.hit.instID = [[ffi::RTC_INVALID_GEOMETRY_ID; $width];
                    ffi::RTC_MAX_INSTANCE_LEVEL_COUNT as usize];
                compat::Padded::new(p)
            }

            #[inline]
            fn set_lane(&mut self, i: usize, ray: &Ray) {
                let r = to_rtc_ray(ray);
                let p = &mut self.ray;
                (p.org_x[i], p.org_y[i], p.org_z[i]) = (r.org_x, r.org_y, r.org_z);
                (p.dir_x[i], p.dir_y[i], p.dir_z[i]) = (r.dir_x, r.dir_y, r.dir_z);
                (p.tnear[i], p.tfar[i], p.time[i]) = (r.tnear, r.tfar, r.time);
            }

            #[inline]
            fn set_block(&mut self, at: usize, block: &RayBlock) {
                let p = &mut self.ray;
                let lanes = at..at + BLOCK;
                let [ox, oy, oz] = &block.origin;
                let [dx, dy, dz] = &block.dir;
                p.org_x[lanes.clone()].copy_from_slice(ox);
                p.org_y[lanes.clone()].copy_from_slice(oy);
                p.org_z[lanes.clone()].copy_from_slice(oz);
                p.dir_x[lanes.clone()].copy_from_slice(dx);
                p.dir_y[lanes.clone()].copy_from_slice(dy);
                p.dir_z[lanes.clone()].copy_from_slice(dz);
                p.tnear[lanes.clone()].copy_from_slice(&block.tmin);
                p.tfar[lanes.clone()].copy_from_slice(&block.tmax);
                // As `to_rtc_ray` clamps it.
                p.time[lanes].copy_from_slice(&block.time.map(|t| t.clamp(0.0, 1.0)));
            }

            #[inline]
            fn clear_hits(&mut self) {
                self.hit.geomID = [ffi::RTC_INVALID_GEOMETRY_ID; $width];
                for level in &mut self.hit.instID {
                    *level = [ffi::RTC_INVALID_GEOMETRY_ID; $width];
                }
            }

            #[inline]
            fn hit(&self, i: usize) -> Option<Hit> {
                let h = &self.hit;
                let instance = h.instID[0][i];
                let geom_id =
                    if instance == ffi::RTC_INVALID_GEOMETRY_ID { h.geomID[i] } else { instance };
                (h.geomID[i] != ffi::RTC_INVALID_GEOMETRY_ID).then_some(Hit {
                    t: self.ray.tfar[i],
                    geom_id,
                    prim_id: h.primID[i],
                    u: h.u[i],
                    v: h.v[i],
                })
            }

            #[inline]
            unsafe fn intersect(
                &mut self,
                scene: ffi::RTCScene,
                valid: &compat::ValidMask,
                coherence: compat::Coherence,
            ) {
                // SAFETY: per the caller.
                unsafe { compat::$intersect(scene, valid, self, coherence) }
            }

            #[inline]
            unsafe fn occluded(&mut self, scene: ffi::RTCScene, valid: &compat::ValidMask) {
                // SAFETY: per the caller; occlusion queries write only the rays' `tfar`.
                unsafe { compat::$occluded(scene, valid, &mut self.inner.ray) }
            }

            #[inline]
            fn blocked(&self, lane: usize) -> bool {
                self.ray.tfar[lane] == f32::NEG_INFINITY
            }
        }
    )*};
}

ray_hit_packet! {
    RTCRayHit4: 4, intersect4, occluded4;
    RTCRayHit8: 8, intersect8, occluded8;
    RTCRayHit16: 16, intersect16, occluded16;
}
