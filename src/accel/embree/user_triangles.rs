//! Triangle meshes as Embree user geometry, for counting mode (see `EmbreeAccel`).
//!
//! One user primitive per triangle, bounded by the triangle's exact AABB. The callbacks run
//! `crate::intersect::intersect_triangle`, the watertight test the pure-Rust backend uses,
//! so hits agree bit for bit with that backend wherever both report the same triangle, and
//! they report hits exactly as Embree's native triangles do (`u`, `v` barycentrics of
//! vertices 1 and 2, `primID`, `geomID`, an unnormalised `Ng = (v0 - v1) × (v2 - v0)`).
//!
//! Every call counts one primitive test per valid lane in the query's counters
//! (`compat::count_prim_tests`).
//!
//! The callbacks are `extern "C"`: unwinding out of them would abort, so nothing in them
//! can panic (float arithmetic, raw-pointer reads, `slice::get`; no indexing or unwraps).

use super::callback_data::CallbackData;
use super::device::Device;
use super::ffi;
use super::geometry_handle::{GeometryHandle, UserCallbacks, validate_mesh};
use super::rayn::{LaneIntersection, intersect_lanes, occluded_lanes};
use crate::accel::AccelError;
use crate::intersect::intersect_triangle;
use glam::Vec3;
use std::sync::Arc;

/// What the callbacks read: the mesh's triangles, indexed by `primID`. Stored expanded (36
/// bytes per triangle) so a test touches one cache line instead of an index and 3 vertices.
struct Triangles(Vec<[Vec3; 3]>);

/// An Embree user geometry whose primitive `i` is triangle `indices[i]`.
pub fn user_triangle_geometry(
    device: &Arc<Device>,
    positions: &[Vec3],
    indices: &[[u32; 3]],
) -> Result<GeometryHandle, AccelError> {
    validate_mesh(positions, indices).map_err(AccelError::Embree)?;
    let count = u32::try_from(indices.len())
        .map_err(|_| AccelError::Embree("too many triangles".into()))?;
    // In range: `validate_mesh` checked every index.
    let triangles = indices.iter().map(|tri| tri.map(|i| positions[i as usize])).collect();
    let callbacks = UserCallbacks {
        bounds: Some(bounds),
        intersect: Some(intersect),
        occluded: Some(occluded),
    };
    // SAFETY: the data is a `Triangles`, and the three callbacks below read the user pointer
    // as `*const Triangles`.
    unsafe {
        GeometryHandle::user(device, CallbackData::new(Triangles(triangles)), count, callbacks)
    }
}

/// The triangle `prim_id` of the geometry whose user pointer is `user_ptr`.
///
/// # Safety
/// `user_ptr` must be the `Triangles` registered in `user_triangle_geometry` (alive while
/// the scene is, and only ever shared).
unsafe fn triangle<'a>(user_ptr: *mut std::ffi::c_void, prim_id: u32) -> Option<&'a [Vec3; 3]> {
    // SAFETY: per the caller.
    let triangles = unsafe { &*user_ptr.cast::<Triangles>() };
    triangles.0.get(prim_id as usize)
}

unsafe extern "C" fn bounds(args: *const ffi::RTCBoundsFunctionArguments) {
    // SAFETY: Embree passes arguments valid for the call, whose user pointer is the
    // `Triangles` registered in `user_triangle_geometry` and whose `bounds_o` is ours to
    // write.
    let (tri, out) = unsafe {
        let args = &*args;
        (triangle(args.geometryUserPtr, args.primID), &mut *args.bounds_o)
    };
    // The exact box, as obvhs gets: it contains the triangle exactly. (Embree 3.13.5 has no
    // robust traversal for user geometry, whatever the scene flags, so a ray within
    // rounding of a box face may skip the box; the counting-mode tests saw no such ray.)
    // An out-of-range `primID` (Embree never asks for one) gets an empty box (lower >
    // upper), which Embree skips.
    let (lower, upper) = match tri {
        Some(tri) => (tri[0].min(tri[1]).min(tri[2]), tri[0].max(tri[1]).max(tri[2])),
        None => (Vec3::INFINITY, Vec3::NEG_INFINITY),
    };
    [out.lower_x, out.lower_y, out.lower_z] = lower.to_array();
    [out.upper_x, out.upper_y, out.upper_z] = upper.to_array();
}

unsafe extern "C" fn intersect(args: *const ffi::RTCIntersectFunctionNArguments) {
    // SAFETY: Embree passes arguments valid for the call; the user pointer is the
    // `Triangles` registered in `user_triangle_geometry`.
    let (args, tri) = unsafe { (&*args, triangle((*args).geometryUserPtr, (*args).primID)) };
    // SAFETY: these are the arguments of the running intersect callback.
    unsafe {
        intersect_lanes(args, |ray| {
            let (origin, dir, tri) = (ray.origin(), ray.dir(), tri?);
            // `t <= tfar` (the current closest hit): on an exact tie the later triangle wins,
            // as with Embree's own triangle test and obvhs.
            let (t, u, v) = intersect_triangle(origin, dir, ray.tnear(), ray.tfar(), tri)?;
            let ng = (tri[0] - tri[1]).cross(tri[2] - tri[0]);
            let ng = if ng != Vec3::ZERO && ng.is_finite() { ng } else { -dir };
            Some(LaneIntersection { t, ng, u, v })
        })
    };
}

unsafe extern "C" fn occluded(args: *const ffi::RTCOccludedFunctionNArguments) {
    // SAFETY: as in `intersect`.
    let (args, tri) = unsafe { (&*args, triangle((*args).geometryUserPtr, (*args).primID)) };
    // SAFETY: these are the arguments of the running occluded callback.
    unsafe {
        occluded_lanes(args, |ray| {
            tri.is_some_and(|tri| {
                intersect_triangle(ray.origin(), ray.dir(), ray.tnear(), ray.tfar(), tri).is_some()
            })
        })
    };
}
