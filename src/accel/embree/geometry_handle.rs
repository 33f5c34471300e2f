//! `GeometryHandle`: one Embree geometry, not yet attached to a scene.

use super::callback_data::CallbackData;
use super::device::Device;
use super::ffi;
use crate::accel::AccelError;
use glam::Vec3;
use std::any::Any;
use std::sync::Arc;

/// A committed Embree geometry. Released on drop; attaching it to a scene hands the scene
/// its own reference and whatever must outlive it (see `Scene::attach`).
pub struct GeometryHandle {
    pub(super) handle: ffi::RTCGeometry,
    pub(super) device: Arc<Device>,
    /// What Embree reaches through this geometry and we own: a user geometry's callback
    /// data (read through its user pointer), or an instance's child scene (whose own
    /// geometries' callback data its traversal reads).
    pub(super) keep_alive: Option<Box<dyn Any + Send + Sync>>,
    /// Transform or vertex time steps: 1 for static geometry, 2 for a moving instance.
    pub(super) time_steps: u32,
}

/// The callbacks of a user geometry.
pub struct UserCallbacks {
    pub bounds: ffi::RTCBoundsFunction,
    pub intersect: ffi::RTCIntersectFunctionN,
    pub occluded: ffi::RTCOccludedFunctionN,
}

/// Element types of the buffers we create, with their Embree format.
trait BufferElement: Copy {
    const FORMAT: ffi::RTCFormat;
}

impl BufferElement for [f32; 3] {
    const FORMAT: ffi::RTCFormat = ffi::RTCFormat::FLOAT3;
}

impl BufferElement for [u32; 3] {
    const FORMAT: ffi::RTCFormat = ffi::RTCFormat::UINT3;
}

impl GeometryHandle {
    pub(super) fn new(
        device: &Arc<Device>,
        kind: ffi::RTCGeometryType,
    ) -> Result<GeometryHandle, AccelError> {
        // SAFETY: the device handle is live (the `Arc` keeps it alive).
        let handle = unsafe { ffi::rtcNewGeometry(device.handle(), kind) };
        if handle.is_null() {
            device.check()?;
            return Err(AccelError::Embree(format!("cannot create a {kind:?} geometry")));
        }
        // Wrapped before checking, so an error still releases the handle.
        let geometry =
            GeometryHandle { handle, device: Arc::clone(device), keep_alive: None, time_steps: 1 };
        device.check()?;
        Ok(geometry)
    }

    /// A triangle mesh. Embree checks neither the index range nor the triangle count, and
    /// reads out of bounds on a bad index, so both are checked here.
    pub fn triangles(
        device: &Arc<Device>,
        positions: &[Vec3],
        indices: &[[u32; 3]],
    ) -> Result<GeometryHandle, AccelError> {
        validate_mesh(positions, indices).map_err(AccelError::Embree)?;
        let geometry = GeometryHandle::new(device, ffi::RTCGeometryType::TRIANGLE)?;
        geometry
            .set_new_buffer(ffi::RTCBufferType::VERTEX, positions.iter().map(|p| p.to_array()))?;
        geometry.set_new_buffer(ffi::RTCBufferType::INDEX, indices.iter().copied())?;
        geometry.commit()?;
        Ok(geometry)
    }

    /// A user geometry of `prim_count` primitives whose callbacks read `data`.
    ///
    /// # Safety
    /// The callbacks must read the geometry user pointer (and the bounds callback's user
    /// pointer) as `*const T`, and be sound for every call Embree makes.
    pub unsafe fn user<T: Send + Sync + 'static>(
        device: &Arc<Device>,
        data: CallbackData<T>,
        prim_count: u32,
        callbacks: UserCallbacks,
    ) -> Result<GeometryHandle, AccelError> {
        let mut geometry = GeometryHandle::new(device, ffi::RTCGeometryType::USER)?;
        let h = geometry.handle;
        let ptr = data.user_ptr();
        // SAFETY: `h` is a live user geometry. `ptr` stays valid as long as the geometry
        // can call back: `data` moves into the geometry and, on attach, into the scene,
        // which frees it only after releasing the Embree scene. The callbacks match `T`
        // per this function's contract. Both user pointers are set because Embree passes
        // the geometry's user data to the bounds callback in `geometryUserPtr`.
        unsafe {
            ffi::rtcSetGeometryUserPrimitiveCount(h, prim_count);
            ffi::rtcSetGeometryUserData(h, ptr);
            ffi::rtcSetGeometryBoundsFunction(h, callbacks.bounds, ptr);
            ffi::rtcSetGeometryIntersectFunction(h, callbacks.intersect);
            ffi::rtcSetGeometryOccludedFunction(h, callbacks.occluded);
        }
        geometry.keep_alive = Some(Box::new(data));
        device.check()?;
        geometry.commit()?;
        Ok(geometry)
    }

    pub fn handle(&self) -> ffi::RTCGeometry {
        self.handle
    }

    pub fn device(&self) -> &Arc<Device> {
        &self.device
    }

    /// What the geometry's owner must keep alive while Embree may use the geometry.
    pub fn take_keep_alive(&mut self) -> Option<Box<dyn Any + Send + Sync>> {
        self.keep_alive.take()
    }

    /// How many time steps the geometry was committed with (more than 1: motion blur).
    pub fn time_steps(&self) -> u32 {
        self.time_steps
    }

    /// Fills a new Embree-allocated buffer (Embree pads it, so its SIMD loads past the last
    /// element stay in bounds, unlike a shared buffer of ours).
    fn set_new_buffer<E: BufferElement>(
        &self,
        kind: ffi::RTCBufferType,
        elements: impl ExactSizeIterator<Item = E>,
    ) -> Result<(), AccelError> {
        let count = elements.len();
        let stride = std::mem::size_of::<E>();
        // SAFETY: `self.handle` is live; Embree allocates `count * stride` bytes (plus padding).
        let ptr =
            unsafe { ffi::rtcSetNewGeometryBuffer(self.handle, kind, 0, E::FORMAT, stride, count) };
        self.device.check()?;
        let ptr = ptr.cast::<E>();
        if ptr.is_null() || !ptr.is_aligned() {
            return Err(AccelError::Embree(format!(
                "cannot allocate a {kind:?} buffer of {count} elements"
            )));
        }
        for (i, e) in elements.take(count).enumerate() {
            // SAFETY: `ptr` is non-null, aligned and has room for `count` elements, and
            // `i < count`. Writing (not referencing) is fine for uninitialised memory.
            // Embree reads the buffer only at commit, after this returns.
            unsafe { ptr.add(i).write(e) };
        }
        Ok(())
    }

    pub(super) fn commit(&self) -> Result<(), AccelError> {
        // SAFETY: `self.handle` is live.
        unsafe { ffi::rtcCommitGeometry(self.handle) };
        self.device.check()
    }
}

impl Drop for GeometryHandle {
    fn drop(&mut self) {
        // SAFETY: we own one reference to the live handle. If the geometry was never
        // attached this frees it, so Embree stops using the callback data, which is freed
        // afterwards (fields drop after `drop`).
        unsafe { ffi::rtcReleaseGeometry(self.handle) };
    }
}

/// Problems Embree would not report (it would read out of bounds or build nothing).
pub(super) fn validate_mesh(positions: &[Vec3], indices: &[[u32; 3]]) -> Result<(), String> {
    if indices.is_empty() {
        return Err("the mesh has no triangles".into());
    }
    if u32::try_from(indices.len()).is_err() {
        return Err(format!("the mesh has {} triangles; at most 2^32 - 1 fit", indices.len()));
    }
    if let Some((i, p)) = positions.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        return Err(format!("vertex {i} is not finite: {p}"));
    }
    let n = positions.len();
    for (t, tri) in indices.iter().enumerate() {
        if let Some(&bad) = tri.iter().find(|&&i| i as usize >= n) {
            return Err(format!(
                "triangle {t} refers to vertex {bad}, but the mesh has {n} vertices"
            ));
        }
    }
    Ok(())
}
