//! Instance geometries: a committed child scene placed by a fixed transform or moving
//! between two transforms over the shutter interval.

use super::device::Device;
use super::ffi;
use super::geometry_handle::GeometryHandle;
use super::scene::CommittedScene;
use crate::accel::AccelError;
use crate::render_scene::Trs;
use glam::{Affine3A, Vec3};
use std::sync::Arc;

impl GeometryHandle {
    /// An instance of `child` fixed at `render_from_object` (one time step).
    pub fn static_instance(
        device: &Arc<Device>,
        child: &Arc<CommittedScene>,
        render_from_object: &Affine3A,
    ) -> Result<GeometryHandle, AccelError> {
        validate_affine(render_from_object).map_err(AccelError::Embree)?;
        let geometry = GeometryHandle::instance(device, child)?;
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
    ) -> Result<GeometryHandle, AccelError> {
        validate_motion(start, end).map_err(AccelError::Embree)?;
        let mut geometry = GeometryHandle::instance(device, child)?;
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
    fn instance(
        device: &Arc<Device>,
        child: &Arc<CommittedScene>,
    ) -> Result<GeometryHandle, AccelError> {
        if !Arc::ptr_eq(child.device(), device) {
            return Err(AccelError::Embree(
                "instance and instanced scene belong to different devices".into(),
            ));
        }
        let mut geometry = GeometryHandle::new(device, ffi::RTCGeometryType::INSTANCE)?;
        // SAFETY: a live instance geometry and a live, committed scene of the same device.
        unsafe { ffi::rtcSetGeometryInstancedScene(geometry.handle, child.handle()) };
        geometry.keep_alive = Some(Box::new(Arc::clone(child)));
        device.check()?;
        Ok(geometry)
    }
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
