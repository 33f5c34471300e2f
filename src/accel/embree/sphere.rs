//! Spheres as Embree user geometry. The callbacks call `crate::intersect::intersect_sphere`,
//! the function the pure-Rust backend uses, so both backends agree bit for bit on spheres.
//!
//! The callbacks are `extern "C"`: unwinding out of them would abort, so nothing in them
//! can panic (plain float arithmetic and raw-pointer reads, no indexing or unwraps).
//!
//! Each call tests every valid lane once and counts those tests in the query's counters
//! when the query counts (`compat::count_prim_tests`; a no-op in normal mode).

use super::callback_data::CallbackData;
use super::device::Device;
use super::ffi;
use super::geometry_handle::{GeometryHandle, UserCallbacks};
use super::rayn::{LaneIntersection, intersect_lanes, occluded_lanes};
use crate::accel::AccelError;
use crate::intersect::intersect_sphere;
use crate::render_scene::Sphere;
use std::sync::Arc;

/// An Embree user geometry with one primitive, `sphere`.
pub fn sphere_geometry(device: &Arc<Device>, sphere: Sphere) -> Result<GeometryHandle, AccelError> {
    if !sphere.center.is_finite() || !sphere.radius.is_finite() || sphere.radius < 0.0 {
        return Err(AccelError::Embree(format!(
            "invalid sphere: center {}, radius {}",
            sphere.center, sphere.radius
        )));
    }
    let callbacks = UserCallbacks {
        bounds: Some(bounds),
        intersect: Some(intersect),
        occluded: Some(occluded),
    };
    // SAFETY: the data is a `Sphere`, and the three callbacks below read the user pointer as
    // `*const Sphere`.
    unsafe { GeometryHandle::user(device, CallbackData::new(sphere), 1, callbacks) }
}

unsafe extern "C" fn bounds(args: *const ffi::RTCBoundsFunctionArguments) {
    // SAFETY: Embree passes arguments valid for the call, whose user pointer is the `Sphere`
    // registered in `sphere_geometry` (alive while the scene is) and whose `bounds_o` is
    // ours to write.
    let (sphere, out) = unsafe {
        let args = &*args;
        (&*args.geometryUserPtr.cast::<Sphere>(), &mut *args.bounds_o)
    };
    // A few ulps of slack: `intersect_sphere` rounds, and a ray it would hit must never be
    // culled by the box. A larger box costs only a callback.
    let extent = sphere.radius + sphere.center.abs().max_element();
    let r = sphere.radius + extent * 4.0 * f32::EPSILON;
    [out.lower_x, out.lower_y, out.lower_z] = (sphere.center - r).to_array();
    [out.upper_x, out.upper_y, out.upper_z] = (sphere.center + r).to_array();
}

unsafe extern "C" fn intersect(args: *const ffi::RTCIntersectFunctionNArguments) {
    // SAFETY: Embree passes arguments valid for the call; the user pointer is the `Sphere`
    // registered in `sphere_geometry`.
    let (args, sphere) = unsafe { (&*args, &*(*args).geometryUserPtr.cast::<Sphere>()) };
    // SAFETY: these are the arguments of the running intersect callback.
    unsafe {
        intersect_lanes(args, |ray| {
            let (origin, dir, tfar) = (ray.origin(), ray.dir(), ray.tfar());
            let t = intersect_sphere(origin, dir, ray.tnear(), tfar, sphere.center, sphere.radius)
                .filter(|&t| t < tfar)?;
            // Outward if possible.
            let outward = origin + t * dir - sphere.center;
            let ng = if outward == glam::Vec3::ZERO { -dir } else { outward };
            Some(LaneIntersection { t, ng, u: 0.0, v: 0.0 })
        })
    };
}

unsafe extern "C" fn occluded(args: *const ffi::RTCOccludedFunctionNArguments) {
    // SAFETY: as in `intersect`.
    let (args, sphere) = unsafe { (&*args, &*(*args).geometryUserPtr.cast::<Sphere>()) };
    // SAFETY: these are the arguments of the running occluded callback.
    unsafe {
        occluded_lanes(args, |ray| {
            let (origin, dir) = (ray.origin(), ray.dir());
            intersect_sphere(origin, dir, ray.tnear(), ray.tfar(), sphere.center, sphere.radius)
                .is_some()
        })
    };
}
