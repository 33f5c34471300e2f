//! Signed distance grids as Embree user geometry: one primitive per voxel the surface may
//! pass through, bounded by its box around the surface. The callbacks call
//! `crate::intersect_sdf::intersect_voxel`, the function the pure-Rust backend uses, so
//! both backends find the same hits.
//!
//! The callbacks are `extern "C"`: unwinding out of them would abort, so nothing in them
//! can panic (float arithmetic, raw-pointer reads, `slice::get`; no indexing, unwraps or
//! `clamp`, which panics on a NaN or crossed bound: `max` then `min` instead), whatever
//! the ray holds (infinite or NaN parts are a miss, tested in `crate::intersect_sdf`).

use super::callback_data::CallbackData;
use super::device::Device;
use super::ffi;
use super::geometry_handle::{GeometryHandle, UserCallbacks};
use super::rayn::{LaneIntersection, intersect_lanes, occluded_lanes};
use crate::accel::AccelError;
use crate::intersect_sdf::intersect_voxel;
use crate::sdf_grid::SdfGrid;
use glam::Vec3;
use std::sync::Arc;

/// An Embree user geometry whose primitive `i` is voxel `grid.voxels[i]`.
pub fn sdf_grid_geometry(
    device: &Arc<Device>,
    grid: Arc<SdfGrid>,
) -> Result<GeometryHandle, AccelError> {
    let count = u32::try_from(grid.voxels.len())
        .map_err(|_| AccelError::Embree("too many voxels in a signed distance grid".into()))?;
    let callbacks = UserCallbacks {
        bounds: Some(bounds),
        intersect: Some(intersect),
        occluded: Some(occluded),
    };
    // SAFETY: the data is an `Arc<SdfGrid>`, and the three callbacks below read the user
    // pointer as `*const Arc<SdfGrid>`.
    unsafe { GeometryHandle::user(device, CallbackData::new(grid), count, callbacks) }
}

/// The grid of the geometry whose user pointer is `user_ptr`.
///
/// # Safety
/// `user_ptr` must be the `Arc<SdfGrid>` registered in `sdf_grid_geometry` (alive while
/// the scene is, and only ever shared).
unsafe fn grid<'a>(user_ptr: *mut std::ffi::c_void) -> &'a SdfGrid {
    // SAFETY: per the caller.
    unsafe { &*user_ptr.cast::<Arc<SdfGrid>>() }
}

unsafe extern "C" fn bounds(args: *const ffi::RTCBoundsFunctionArguments) {
    // SAFETY: Embree passes arguments valid for the call, whose user pointer is the grid
    // registered in `sdf_grid_geometry` and whose `bounds_o` is ours to write.
    let (grid, prim, out) = unsafe {
        let args = &*args;
        (grid(args.geometryUserPtr), args.primID, &mut *args.bounds_o)
    };
    // An out-of-range `primID` (Embree never asks for one) gets an empty box, which
    // Embree skips.
    let (lower, upper) =
        grid.boxes.get(prim as usize).copied().unwrap_or((Vec3::INFINITY, Vec3::NEG_INFINITY));
    [out.lower_x, out.lower_y, out.lower_z] = lower.to_array();
    [out.upper_x, out.upper_y, out.upper_z] = upper.to_array();
}

unsafe extern "C" fn intersect(args: *const ffi::RTCIntersectFunctionNArguments) {
    // SAFETY: Embree passes arguments valid for the call; the user pointer is the grid
    // registered in `sdf_grid_geometry`.
    let (args, voxel) =
        unsafe { (&*args, grid((*args).geometryUserPtr).prim_corners((*args).primID)) };
    // SAFETY: these are the arguments of the running intersect callback.
    unsafe {
        intersect_lanes(args, |ray| {
            let (voxel, corners) = voxel?;
            let (origin, dir) = (ray.origin(), ray.dir());
            let t = intersect_voxel(origin, dir, ray.tnear(), ray.tfar(), voxel, &corners)?;
            // Any nonzero normal will do: shading recomputes it from the grid.
            Some(LaneIntersection { t, ng: -dir, u: 0.0, v: 0.0 })
        })
    };
}

unsafe extern "C" fn occluded(args: *const ffi::RTCOccludedFunctionNArguments) {
    // SAFETY: as in `intersect`.
    let (args, voxel) =
        unsafe { (&*args, grid((*args).geometryUserPtr).prim_corners((*args).primID)) };
    // SAFETY: these are the arguments of the running occluded callback.
    unsafe {
        occluded_lanes(args, |ray| {
            voxel.is_some_and(|(voxel, corners)| {
                let (origin, dir) = (ray.origin(), ray.dir());
                intersect_voxel(origin, dir, ray.tnear(), ray.tfar(), voxel, &corners).is_some()
            })
        })
    };
}
