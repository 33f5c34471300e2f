//! One lane of the SOA ray packets Embree hands to user-geometry callbacks (`RTCRayN`,
//! `RTCRayHitN`): each field is `n` consecutive 32-bit words, and in `RTCRayHitN` the hit
//! fields follow the 12 ray fields. Rust versions of the header's `RTCRayN_*` inline
//! accessors, which bindgen cannot generate.

use super::{compat, ffi};
use glam::Vec3;
use std::ffi::c_void;
use std::marker::PhantomData;

// Word offsets of the fields, in units of `n` (rtcore_ray.h).
const ORG: usize = 0;
const TNEAR: usize = 3;
const DIR: usize = 4;
const TFAR: usize = 8;
const HIT: usize = 12;
const NG: usize = 0;
const U: usize = 3;
const V: usize = 4;
const PRIM_ID: usize = 5;
const GEOM_ID: usize = 6;
const INST_ID: usize = 7;

/// Lane `i` of an `RTCRayN` packet, borrowed for the duration of a callback.
#[derive(Clone, Copy)]
pub struct RayLane<'a> {
    base: *mut u32,
    n: usize,
    i: usize,
    _packet: PhantomData<&'a mut u32>,
}

impl<'a> RayLane<'a> {
    /// # Safety
    /// `packet` must point to an `RTCRayN` (or `RTCRayHitN`) of width `n`, valid for reads
    /// and writes for `'a`, and `i < n`.
    pub unsafe fn new(packet: *mut c_void, n: usize, i: usize) -> Self {
        RayLane { base: packet.cast(), n, i, _packet: PhantomData }
    }

    fn word(&self, field: usize) -> *mut u32 {
        // Pointer arithmetic only; in bounds because `field < 12` (ray) or `HIT + field < 20`
        // (hit) and `i < n`, as promised to `new`.
        self.base.wrapping_add(field * self.n + self.i)
    }

    fn get(&self, field: usize) -> u32 {
        // SAFETY: `word` is inside the packet (see `new`), which is valid for reads for 'a.
        unsafe { self.word(field).read() }
    }

    fn set(&self, field: usize, value: u32) {
        // SAFETY: `word` is inside the packet (see `new`), which is valid for writes for 'a.
        unsafe { self.word(field).write(value) }
    }

    fn get_vec3(&self, field: usize) -> Vec3 {
        Vec3::new(
            f32::from_bits(self.get(field)),
            f32::from_bits(self.get(field + 1)),
            f32::from_bits(self.get(field + 2)),
        )
    }

    pub fn origin(&self) -> Vec3 {
        self.get_vec3(ORG)
    }

    pub fn dir(&self) -> Vec3 {
        self.get_vec3(DIR)
    }

    pub fn tnear(&self) -> f32 {
        f32::from_bits(self.get(TNEAR))
    }

    pub fn tfar(&self) -> f32 {
        f32::from_bits(self.get(TFAR))
    }

    pub fn set_tfar(&self, t: f32) {
        self.set(TFAR, t.to_bits());
    }
}

/// Lane `i` of an `RTCRayHitN` packet: a ray lane whose hit can also be written.
#[derive(Clone, Copy)]
pub struct RayHitLane<'a> {
    ray: RayLane<'a>,
}

/// What a user geometry reports for a hit.
pub struct LaneHit {
    pub t: f32,
    pub ng: Vec3,
    pub u: f32,
    pub v: f32,
    pub prim_id: u32,
    pub geom_id: u32,
    pub inst_id: u32,
}

impl<'a> RayHitLane<'a> {
    /// # Safety
    /// `packet` must point to an `RTCRayHitN` of width `n`, valid for reads and writes for
    /// `'a`, and `i < n`.
    pub unsafe fn new(packet: *mut c_void, n: usize, i: usize) -> Self {
        // SAFETY: an `RTCRayHitN` starts with an `RTCRayN` of the same width.
        RayHitLane { ray: unsafe { RayLane::new(packet, n, i) } }
    }

    pub fn ray(&self) -> RayLane<'a> {
        self.ray
    }

    pub fn set_hit(&self, hit: &LaneHit) {
        let h = |field| HIT + field;
        self.ray.set_tfar(hit.t);
        self.ray.set(h(NG), hit.ng.x.to_bits());
        self.ray.set(h(NG + 1), hit.ng.y.to_bits());
        self.ray.set(h(NG + 2), hit.ng.z.to_bits());
        self.ray.set(h(U), hit.u.to_bits());
        self.ray.set(h(V), hit.v.to_bits());
        self.ray.set(h(PRIM_ID), hit.prim_id);
        self.ray.set(h(GEOM_ID), hit.geom_id);
        self.ray.set(h(INST_ID), hit.inst_id);
    }
}

/// What a user-geometry test reports for one ray: distance, geometric normal (any nonzero
/// vector will do: the integrator recomputes it) and barycentrics.
pub struct LaneIntersection {
    pub t: f32,
    pub ng: Vec3,
    pub u: f32,
    pub v: f32,
}

/// Calls `lane(i)` for every `i < n` that `valid` marks (nonzero), and returns how many.
///
/// # Safety
/// `valid` must point to `n` readable `i32`s.
unsafe fn for_valid_lanes(valid: *const i32, n: usize, mut lane: impl FnMut(usize)) -> u64 {
    let mut count = 0;
    for i in 0..n {
        // SAFETY: `valid` has `n` entries (per the caller) and `i < n`.
        if unsafe { *valid.add(i) } != 0 {
            lane(i);
            count += 1;
        }
    }
    count
}

/// The body of a user-geometry intersect callback: `test` on every valid lane, each hit
/// written to its lane, and the tests counted (counting mode).
///
/// # Safety
/// `args` must be the arguments Embree passed to the running intersect callback.
pub unsafe fn intersect_lanes(
    args: &ffi::RTCIntersectFunctionNArguments,
    mut test: impl FnMut(&RayLane) -> Option<LaneIntersection>,
) {
    // SAFETY: `context` is the pointer Embree passed to this callback.
    let inst_id = unsafe { compat::instance_id(args.context) };
    let n = args.N as usize;
    let each = |i| {
        // SAFETY: `rayhit` is an `RTCRayHitN` of width `N`, ours for the call; `i < N`.
        let lane = unsafe { RayHitLane::new(args.rayhit.cast(), n, i) };
        if let Some(LaneIntersection { t, ng, u, v }) = test(&lane.ray()) {
            let (prim_id, geom_id) = (args.primID, args.geomID);
            lane.set_hit(&LaneHit { t, ng, u, v, prim_id, geom_id, inst_id });
        }
    };
    // SAFETY: `valid` has `N` entries.
    let tests = unsafe { for_valid_lanes(args.valid, n, each) };
    // SAFETY: `context` is the pointer Embree passed to this callback.
    unsafe { compat::count_prim_tests(args.context, tests) };
}

/// The body of a user-geometry occluded callback: every valid lane `blocks` is marked
/// occluded (Embree's convention: `tfar = -∞`), and the tests are counted.
///
/// # Safety
/// `args` must be the arguments Embree passed to the running occluded callback.
pub unsafe fn occluded_lanes(
    args: &ffi::RTCOccludedFunctionNArguments,
    mut blocks: impl FnMut(&RayLane) -> bool,
) {
    let n = args.N as usize;
    let each = |i| {
        // SAFETY: `ray` is an `RTCRayN` of width `N`, ours for the call; `i < N`.
        let ray = unsafe { RayLane::new(args.ray.cast(), n, i) };
        if blocks(&ray) {
            ray.set_tfar(f32::NEG_INFINITY);
        }
    };
    // SAFETY: `valid` has `N` entries.
    let tests = unsafe { for_valid_lanes(args.valid, n, each) };
    // SAFETY: `context` is the pointer Embree passed to this callback.
    unsafe { compat::count_prim_tests(args.context, tests) };
}
