//! `Scene` (being built) and `CommittedScene` (read-only, traced from many threads).

use super::device::Device;
use super::geometry_handle::GeometryHandle;
use super::{compat, ffi, ray};
use crate::accel::AccelError;
use crate::ray::{Hit, Ray};
use crate::stats::TraversalCounters;
use std::any::Any;
use std::sync::Arc;

/// An Embree scene that geometries can still be attached to.
pub struct Scene {
    handle: ffi::RTCScene,
    device: Arc<Device>,
    /// What the attached geometries need alive (their callback data, instanced child
    /// scenes; see `GeometryHandle::take_keep_alive`). Freed after the Embree scene is released
    /// (fields drop after `Drop::drop`), so no callback or traversal can outlive it.
    keep_alive: Vec<Box<dyn Any + Send + Sync>>,
    /// Attached geometries with more than one time step.
    motion_geometries: usize,
}

impl Scene {
    pub fn new(
        device: &Arc<Device>,
        quality: ffi::RTCBuildQuality,
        flags: ffi::RTCSceneFlags,
    ) -> Result<Scene, AccelError> {
        // SAFETY: the device handle is live (the `Arc` keeps it alive).
        let handle = unsafe { ffi::rtcNewScene(device.handle()) };
        if handle.is_null() {
            device.check()?;
            return Err(AccelError::Embree("cannot create a scene".into()));
        }
        // Wrapped before anything can fail, so an error still releases the handle.
        let scene = Scene {
            handle,
            device: Arc::clone(device),
            keep_alive: Vec::new(),
            motion_geometries: 0,
        };
        // SAFETY: `handle` is a live scene.
        unsafe {
            ffi::rtcSetSceneBuildQuality(handle, quality);
            ffi::rtcSetSceneFlags(handle, flags);
        }
        device.check()?;
        Ok(scene)
    }

    /// Attaches `geometry` with geometry id `id` (what hits report as `geomID`).
    pub fn attach(&mut self, mut geometry: GeometryHandle, id: u32) -> Result<(), AccelError> {
        if !Arc::ptr_eq(geometry.device(), &self.device) {
            return Err(AccelError::Embree(
                "geometry and scene belong to different devices".into(),
            ));
        }
        // SAFETY: both handles are live and belong to the same device. The scene takes its
        // own reference to the geometry; ours is released when `geometry` drops below.
        unsafe { ffi::rtcAttachGeometryByID(self.handle, geometry.handle(), id) };
        // Kept even if attaching failed: harmless, and never too short-lived.
        self.keep_alive.extend(geometry.take_keep_alive());
        if geometry.time_steps() > 1 {
            self.motion_geometries += 1;
        }
        drop(geometry);
        self.device.check()
    }

    /// Builds the acceleration structure. The result can no longer be modified.
    pub fn commit(self) -> Result<CommittedScene, AccelError> {
        // SAFETY: `self.handle` is a live scene; every attached geometry is committed (an
        // instance's child scene too) and what it needs alive is owned by `self`.
        unsafe { ffi::rtcCommitScene(self.handle) };
        self.device.check()?;
        Ok(CommittedScene { scene: self })
    }
}

impl Drop for Scene {
    fn drop(&mut self) {
        // SAFETY: we own the one reference to the live handle; releasing it releases the
        // attached geometries too. Callback data is freed afterwards (field drop order).
        unsafe { ffi::rtcReleaseScene(self.handle) };
    }
}

/// A committed scene: only queries, which Embree allows from any number of threads.
pub struct CommittedScene {
    scene: Scene,
}

// SAFETY: after `rtcCommitScene`, Embree scenes are safe to query concurrently from any
// thread (rtcIntersect/rtcOccluded are documented thread-safe on a committed scene), and
// `CommittedScene` offers no way to modify the scene (its handle is only given to
// `rtcSetGeometryInstancedScene`, which reads it). What it keeps alive is `Send + Sync`.
unsafe impl Send for CommittedScene {}
// SAFETY: as above.
unsafe impl Sync for CommittedScene {}

impl CommittedScene {
    pub fn handle(&self) -> ffi::RTCScene {
        self.scene.handle
    }

    pub fn device(&self) -> &Arc<Device> {
        &self.scene.device
    }

    /// The flags it was built with (`rtcGetSceneFlags`).
    #[cfg(test)]
    pub fn flags(&self) -> ffi::RTCSceneFlags {
        // SAFETY: the scene is live.
        unsafe { ffi::rtcGetSceneFlags(self.scene.handle) }
    }

    /// Geometries attached to this scene with more than one time step (child scenes of
    /// instances not included).
    pub fn motion_geometries(&self) -> usize {
        self.scene.motion_geometries
    }

    /// Closest hit with `tmin <= t <= tmax`. Rays Embree would reject are a miss.
    ///
    /// With `counters`, user-geometry callbacks of counting geometries add their primitive
    /// tests to it (see `compat::count_prim_tests`); `None` costs nothing.
    #[inline]
    pub fn intersect(&self, r: &Ray, counters: Option<&mut TraversalCounters>) -> Option<Hit> {
        if !embree_accepts(r) {
            return None;
        }
        let mut rayhit = ray::to_rtc_ray_hit(r);
        // SAFETY: the scene is live and committed; the ray passed `embree_accepts`, so
        // Debian's assertion-enabled Embree will not abort on it.
        unsafe { compat::intersect1(self.scene.handle, &mut rayhit, counters) };
        ray::from_rtc_ray_hit(&rayhit)
    }

    /// Whether anything lies on the ray within `[tmin, tmax]`. Invalid rays are unoccluded.
    /// `counters` as for [`CommittedScene::intersect`].
    #[inline]
    pub fn occluded(&self, r: &Ray, counters: Option<&mut TraversalCounters>) -> bool {
        if !embree_accepts(r) {
            return false;
        }
        let mut rtc_ray = ray::to_rtc_ray(r);
        // SAFETY: as in `intersect`.
        unsafe { compat::occluded1(self.scene.handle, &mut rtc_ray, counters) };
        rtc_ray.tfar == f32::NEG_INFINITY
    }
}

/// Embree's own validity test (`RayK::valid`, asserted in Debian's build) also rejects
/// finite coordinates above `FLT_LARGE` (measured: an origin at 1e30 or a direction of 1e20
/// aborts the process). `Ray::is_valid` refuses those already (checked at compile time).
#[inline]
pub(super) fn embree_accepts(r: &Ray) -> bool {
    const FLT_LARGE: f32 = 1.844e18;
    const _: () = assert!(Ray::COORDINATE_LIMIT <= FLT_LARGE);
    r.is_valid()
}
