//! `Geometry`: one Embree geometry, not yet attached to a scene.

use super::callback_data::CallbackData;
use super::device::Device;
use super::ffi;
use super::scene::CommittedScene;
use crate::accel::AccelError;
use crate::render_scene::Trs;
use glam::{Affine3A, Vec3};
use std::any::Any;
use std::sync::Arc;

/// A committed Embree geometry. Released on drop; attaching it to a scene hands the scene
/// its own reference and whatever must outlive it (see `Scene::attach`).
pub struct Geometry {
    handle: ffi::RTCGeometry,
    device: Arc<Device>,
    /// What Embree reaches through this geometry and we own: a user geometry's callback
    /// data (read through its user pointer), or an instance's child scene (whose own
    /// geometries' callback data its traversal reads).
    keep_alive: Option<Box<dyn Any + Send + Sync>>,
    /// Transform or vertex time steps: 1 for static geometry, 2 for a moving instance.
    time_steps: u32,
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

impl Geometry {
    fn new(device: &Arc<Device>, kind: ffi::RTCGeometryType) -> Result<Geometry, AccelError> {
        // SAFETY: the device handle is live (the `Arc` keeps it alive).
        let handle = unsafe { ffi::rtcNewGeometry(device.handle(), kind) };
        if handle.is_null() {
            device.check()?;
            return Err(AccelError::Embree(format!("cannot create a {kind:?} geometry")));
        }
        // Wrapped before checking, so an error still releases the handle.
        let geometry =
            Geometry { handle, device: Arc::clone(device), keep_alive: None, time_steps: 1 };
        device.check()?;
        Ok(geometry)
    }

    /// A triangle mesh. Embree checks neither the index range nor the triangle count, and
    /// reads out of bounds on a bad index, so both are checked here.
    pub fn triangles(
        device: &Arc<Device>,
        positions: &[Vec3],
        indices: &[[u32; 3]],
    ) -> Result<Geometry, AccelError> {
        validate_mesh(positions, indices).map_err(AccelError::Embree)?;
        let geometry = Geometry::new(device, ffi::RTCGeometryType::TRIANGLE)?;
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
    ) -> Result<Geometry, AccelError> {
        let mut geometry = Geometry::new(device, ffi::RTCGeometryType::USER)?;
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

    /// An instance of `child` fixed at `render_from_object` (one time step).
    pub fn static_instance(
        device: &Arc<Device>,
        child: &Arc<CommittedScene>,
        render_from_object: &Affine3A,
    ) -> Result<Geometry, AccelError> {
        validate_affine(render_from_object).map_err(AccelError::Embree)?;
        let geometry = Geometry::instance(device, child)?;
        let m = render_from_object;
        // Column major 3x4: the three linear columns, then the translation.
        let columns: [[f32; 3]; 4] = [
            m.matrix3.x_axis.to_array(),
            m.matrix3.y_axis.to_array(),
            m.matrix3.z_axis.to_array(),
            m.translation.to_array(),
        ];
        // SAFETY: a live instance geometry with one time step (the default); Embree copies
        // the 12 floats `columns` holds in the FLOAT3X4_COLUMN_MAJOR layout during the call.
        unsafe {
            ffi::rtcSetGeometryTransform(
                geometry.handle,
                0,
                ffi::RTCFormat::FLOAT3X4_COLUMN_MAJOR,
                columns.as_ptr().cast(),
            );
        }
        geometry.device.check()?;
        geometry.commit()?;
        Ok(geometry)
    }

    /// An instance of `child` moving from `start` (time 0) to `end` (time 1): two time steps
    /// given as quaternion decompositions, which Embree interpolates as [`Trs::lerp`] does
    /// (see [`quaternion_decomposition`]).
    pub fn moving_instance(
        device: &Arc<Device>,
        child: &Arc<CommittedScene>,
        start: &Trs,
        end: &Trs,
    ) -> Result<Geometry, AccelError> {
        validate_motion(start, end).map_err(AccelError::Embree)?;
        let mut geometry = Geometry::instance(device, child)?;
        // SAFETY: a live instance geometry; the time step count is set before any
        // per-step transform, as Embree requires.
        unsafe { ffi::rtcSetGeometryTimeStepCount(geometry.handle, 2) };
        geometry.time_steps = 2;
        for (step, trs) in [(0, start), (1, end)] {
            let decomposition = quaternion_decomposition(trs);
            // SAFETY: a live instance geometry with 2 time steps and `step < 2`; Embree
            // copies the decomposition during the call.
            unsafe {
                ffi::rtcSetGeometryTransformQuaternion(geometry.handle, step, &decomposition);
            }
        }
        geometry.device.check()?;
        geometry.commit()?;
        Ok(geometry)
    }

    /// An instance geometry of `child`, transform not yet set. The geometry keeps `child`
    /// alive: Embree keeps its own reference to the Embree scene, but the callback data of
    /// the child's user geometries is ours.
    fn instance(device: &Arc<Device>, child: &Arc<CommittedScene>) -> Result<Geometry, AccelError> {
        if !Arc::ptr_eq(child.device(), device) {
            return Err(AccelError::Embree(
                "instance and instanced scene belong to different devices".into(),
            ));
        }
        let mut geometry = Geometry::new(device, ffi::RTCGeometryType::INSTANCE)?;
        // SAFETY: a live instance geometry and a live, committed scene of the same device.
        unsafe { ffi::rtcSetGeometryInstancedScene(geometry.handle, child.handle()) };
        geometry.keep_alive = Some(Box::new(Arc::clone(child)));
        device.check()?;
        Ok(geometry)
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

    fn commit(&self) -> Result<(), AccelError> {
        // SAFETY: `self.handle` is live.
        unsafe { ffi::rtcCommitGeometry(self.handle) };
        self.device.check()
    }
}

impl Drop for Geometry {
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

/// `trs` as Embree's quaternion decomposition. Embree's transform is `T · R · S` with `S`
/// upper triangular (scale on the diagonal, skew above it, a "shift" column), `R` the
/// rotation of the normalised quaternion `r + i·i + j·j + k·k` (`r` the real part), and `T`
/// the translation: with no skew and no shift that is `Trs::to_affine`. Between time steps
/// Embree lerps the scale, skew, shift and translation and slerps the quaternion along the
/// shorter arc (flipping one end when their dot product is negative), as `Trs::lerp` does
/// with glam's `Quat::slerp`; only its `acos`/`sincos` are fast approximations.
pub(super) fn quaternion_decomposition(trs: &Trs) -> ffi::RTCQuaternionDecomposition {
    let (s, q, t) = (trs.scale, trs.rotation, trs.translation);
    ffi::RTCQuaternionDecomposition {
        scale_x: s.x,
        scale_y: s.y,
        scale_z: s.z,
        skew_xy: 0.0,
        skew_xz: 0.0,
        skew_yz: 0.0,
        shift_x: 0.0,
        shift_y: 0.0,
        shift_z: 0.0,
        quaternion_r: q.w,
        quaternion_i: q.x,
        quaternion_j: q.y,
        quaternion_k: q.z,
        translation_x: t.x,
        translation_y: t.y,
        translation_z: t.z,
    }
}

/// Embree inverts instance transforms without checking: a singular or non-finite one would
/// send NaN rays into the child scene.
fn validate_affine(m: &Affine3A) -> Result<(), String> {
    let inverse = m.inverse();
    if !m.is_finite() || m.matrix3.determinant() == 0.0 || !inverse.is_finite() {
        return Err(format!("the instance transform is singular or not finite: {m:?}"));
    }
    Ok(())
}

/// Also refuses a scale component that is zero or changes sign over the shutter interval:
/// the interpolated transform would be singular at some time.
fn validate_motion(start: &Trs, end: &Trs) -> Result<(), String> {
    for (when, trs) in [("start", start), ("end", end)] {
        let finite = trs.translation.is_finite() && trs.scale.is_finite();
        if !finite || !trs.rotation.is_finite() || trs.rotation.length_squared() == 0.0 {
            return Err(format!("the motion's {when} transform is not finite: {trs:?}"));
        }
    }
    if (start.scale * end.scale).cmple(Vec3::ZERO).any() {
        return Err(format!(
            "the motion's scale is zero or changes sign (from {} to {}): the transform \
             would be singular",
            start.scale, end.scale
        ));
    }
    Ok(())
}
