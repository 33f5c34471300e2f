//! Spheres as Embree user geometry. The callbacks call `crate::geometry::intersect_sphere`,
//! the function the pure-Rust backend uses, so both backends agree bit for bit on spheres.
//!
//! The callbacks are `extern "C"`: unwinding out of them would abort, so nothing in them
//! can panic (plain float arithmetic and raw-pointer reads, no indexing or unwraps).
//!
//! Each call tests every valid lane once and counts those tests in the query's counters
//! when the query counts (`compat::count_prim_tests`; a no-op in normal mode).

use super::callback_data::CallbackData;
use super::compat;
use super::device::Device;
use super::ffi;
use super::geometry::{Geometry, UserCallbacks};
use super::rayn::{LaneHit, RayHitLane, RayLane};
use crate::accel::AccelError;
use crate::geometry::intersect_sphere;
use crate::render_scene::Sphere;
use std::sync::Arc;

/// An Embree user geometry with one primitive, `sphere`.
pub fn sphere_geometry(device: &Arc<Device>, sphere: Sphere) -> Result<Geometry, AccelError> {
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
    unsafe { Geometry::user(device, CallbackData::new(sphere), 1, callbacks) }
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
    // SAFETY: `context` is the pointer Embree passed to this callback.
    let inst_id = unsafe { compat::instance_id(args.context) };
    let n = args.N as usize;
    let mut tests = 0;
    for i in 0..n {
        // SAFETY: `valid` has `N` entries and `i < N`.
        if unsafe { *args.valid.add(i) } == 0 {
            continue;
        }
        tests += 1;
        // SAFETY: `rayhit` is an `RTCRayHitN` of width `N`, ours for the call, and `i < N`.
        let lane = unsafe { RayHitLane::new(args.rayhit.cast(), n, i) };
        let ray = lane.ray();
        let (origin, dir, tfar) = (ray.origin(), ray.dir(), ray.tfar());
        let hit = intersect_sphere(origin, dir, ray.tnear(), tfar, sphere.center, sphere.radius)
            .filter(|&t| t < tfar);
        if let Some(t) = hit {
            // Any nonzero normal will do (the integrator recomputes it); outward if possible.
            let outward = origin + t * dir - sphere.center;
            let ng = if outward == glam::Vec3::ZERO { -dir } else { outward };
            lane.set_hit(&LaneHit {
                t,
                ng,
                u: 0.0,
                v: 0.0,
                prim_id: args.primID,
                geom_id: args.geomID,
                inst_id,
            });
        }
    }
    // SAFETY: `context` is the pointer Embree passed to this callback.
    unsafe { compat::count_prim_tests(args.context, tests) };
}

unsafe extern "C" fn occluded(args: *const ffi::RTCOccludedFunctionNArguments) {
    // SAFETY: as in `intersect`.
    let (args, sphere) = unsafe { (&*args, &*(*args).geometryUserPtr.cast::<Sphere>()) };
    let n = args.N as usize;
    let mut tests = 0;
    for i in 0..n {
        // SAFETY: `valid` has `N` entries and `i < N`.
        if unsafe { *args.valid.add(i) } == 0 {
            continue;
        }
        tests += 1;
        // SAFETY: `ray` is an `RTCRayN` of width `N`, ours for the call, and `i < N`.
        let ray = unsafe { RayLane::new(args.ray.cast(), n, i) };
        let (origin, dir) = (ray.origin(), ray.dir());
        if intersect_sphere(origin, dir, ray.tnear(), ray.tfar(), sphere.center, sphere.radius)
            .is_some()
        {
            // Embree's convention for "occluded".
            ray.set_tfar(f32::NEG_INFINITY);
        }
    }
    // SAFETY: `context` is the pointer Embree passed to this callback.
    unsafe { compat::count_prim_tests(args.context, tests) };
}
