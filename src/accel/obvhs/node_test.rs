//! A ray against the eight child boxes of a BVH node in one pass (8-wide through `wide`:
//! AVX where the target has it, two SSE halves otherwise).
//!
//! Each slab distance is `(plane − origin) · (1 / dir)`: two roundings of the exact value,
//! so its relative error is below 2ε whatever the magnitudes of plane and origin (a scene
//! 10⁷ units from the origin included), and rounding never changes its sign. Enlarging the
//! far distance by [`FAR_SCALE`] therefore never culls a box the ray's segment meets, and a
//! ray starting on a surface needs no margin behind its origin.

use glam::Vec3;
use wide::f32x8;

/// Direction components smaller than this count as zero: the ray runs parallel to that
/// axis's planes and meets a slab for all t or none. Any t a ray can reach stays far below
/// where this changes a result.
const TINY_DIRECTION: f32 = 1e-18;

/// More than the relative error of the near and far distances together (pbrt's `1 + 2γ₃`).
pub(super) const FAR_SCALE: f32 = 1.0 + 4.0 * f32::EPSILON;

/// Rows of a node's planes: min x, max x, min y, max y, min z, max z (lane i: child i).
pub(super) type Planes = [f32x8; 6];

/// A ray prepared for node tests.
pub(super) struct NodeRay {
    origin: Vec3,
    inv_dir: Vec3,
    /// Per axis, the row of the planes the ray meets first (min or max, by direction sign).
    near_rows: [usize; 3],
    /// Per axis, whether the direction is zero along it (see [`TINY_DIRECTION`]).
    parallel: [bool; 3],
    tmin: f32,
    pub tmax: f32,
}

impl NodeRay {
    pub(super) fn new(origin: Vec3, dir: Vec3, tmin: f32, tmax: f32) -> Self {
        let parallel = dir.abs().cmplt(Vec3::splat(TINY_DIRECTION));
        // Parallel axes' inverses are never used; 1 keeps them finite.
        let inv_dir = Vec3::select(parallel, Vec3::ONE, dir.recip());
        let row = |axis: usize| 2 * axis + usize::from(inv_dir[axis] < 0.0);
        NodeRay {
            origin,
            inv_dir,
            near_rows: [row(0), row(1), row(2)],
            parallel: parallel.into(),
            tmin,
            tmax,
        }
    }
}

/// Which children the ray's segment `[tmin, tmax]` meets (bit i for child i), and where it
/// enters each.
#[inline(always)]
pub(super) fn child_hits(planes: &Planes, ray: &NodeRay) -> (u32, [f32; 8]) {
    let slab = |axis: usize| {
        let near = ray.near_rows[axis];
        let origin = f32x8::splat(ray.origin[axis]);
        if ray.parallel[axis] {
            // All t where the origin lies between the planes (entered at 0), else none.
            let outside = planes[near].simd_gt(origin) | origin.simd_gt(planes[near ^ 1]);
            return (outside & f32x8::INFINITY, f32x8::INFINITY);
        }
        let inv_dir = f32x8::splat(ray.inv_dir[axis]);
        ((planes[near] - origin) * inv_dir, (planes[near ^ 1] - origin) * inv_dir)
    };
    let ((near_x, far_x), (near_y, far_y), (near_z, far_z)) = (slab(0), slab(1), slab(2));
    // No lane is NaN (finite origin, nonzero finite inverse, planes finite or ±∞ with an
    // empty slot's inverted box), so the fast min/max are exact. `tmin` is at least 0.
    let near = near_x.fast_max(near_y).fast_max(near_z.fast_max(f32x8::splat(ray.tmin)));
    let far = far_x.fast_min(far_y).fast_min(far_z.fast_min(f32x8::splat(ray.tmax)));
    let hits = near.simd_le(far * f32x8::splat(FAR_SCALE)).to_bitmask();
    (hits, near.to_array())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::splitmix::SplitMix64 as Rng;
    use glam::DVec3;

    /// Whether the segment [tmin, tmax] of the ray meets the box, in f64.
    fn segment_meets(o: DVec3, d: DVec3, tmin: f64, tmax: f64, lo: DVec3, hi: DVec3) -> bool {
        let (mut near, mut far) = (tmin, tmax);
        for axis in 0..3 {
            if d[axis] == 0.0 {
                if o[axis] < lo[axis] || o[axis] > hi[axis] {
                    return false;
                }
                continue;
            }
            let (a, b) = ((lo[axis] - o[axis]) / d[axis], (hi[axis] - o[axis]) / d[axis]);
            near = near.max(a.min(b));
            far = far.min(a.max(b));
        }
        near <= far
    }

    /// Never culls a box the ray segment meets (computed exactly), and reports none it
    /// misses by more than a hair: random boxes at scales 1e-3 to 1e7 and offsets up to
    /// 1e7, random and axis-aligned rays, rays starting inside boxes and on their faces,
    /// finite and infinite segments.
    #[test]
    fn child_hits_are_the_exact_box_hits_up_to_a_hair() {
        let mut rng = Rng(11);
        let (mut checked, mut hits) = (0usize, 0usize);
        for (scale, offset) in [(1e-3, 0.0), (1.0, 0.0), (1e3, 0.0), (1e6, 0.0), (1.0, 1e7)] {
            for k in 0..20_000 {
                let boxes: [(Vec3, Vec3); 8] = std::array::from_fn(|_| {
                    let c = rng.vec3(-0.5 * scale, 0.5 * scale) + Vec3::splat(offset);
                    let h = rng.vec3(-0.2 * scale, 0.2 * scale).abs();
                    (c - h, c + h)
                });
                let row = |f: &dyn Fn(&(Vec3, Vec3)) -> f32| f32x8::new(boxes.each_ref().map(f));
                let planes: Planes = [
                    row(&|b| b.0.x),
                    row(&|b| b.1.x),
                    row(&|b| b.0.y),
                    row(&|b| b.1.y),
                    row(&|b| b.0.z),
                    row(&|b| b.1.z),
                ];
                let mut origin = rng.vec3(-0.75 * scale, 0.75 * scale) + Vec3::splat(offset);
                if k % 4 == 1 {
                    // On a face of one of the boxes.
                    let (lo, hi) = boxes[k % 8];
                    origin = lo + (hi - lo) * rng.vec3(0.0, 1.0);
                    origin[k % 3] = if k % 8 < 4 { lo[k % 3] } else { hi[k % 3] };
                }
                let mut dir = rng.vec3(-1.0, 1.0).normalize_or(Vec3::X);
                if k % 5 == 0 {
                    let axis = dir.abs().max_position();
                    dir = Vec3::ZERO;
                    dir[axis] = if k % 2 == 0 { 1.0 } else { -1.0 };
                }
                let tmax = if k % 3 == 0 { f32::INFINITY } else { rng.unit() * scale };
                let ray = NodeRay::new(origin, dir, 0.0, tmax);
                let (mask, _) = child_hits(&planes, &ray);
                let (o, d) = (origin.as_dvec3(), dir.as_dvec3());
                for (child, (lo, hi)) in boxes.iter().enumerate() {
                    let (lo, hi) = (lo.as_dvec3(), hi.as_dvec3());
                    let ours = mask & (1 << child) != 0;
                    let exact = segment_meets(o, d, 0.0, tmax as f64, lo, hi);
                    let grow = (hi - lo) * 1e-5 + DVec3::splat(offset as f64 * 1e-6);
                    let generous = segment_meets(o, d, 0.0, tmax as f64, lo - grow, hi + grow);
                    assert!(ours || !exact, "culled a box: {origin} {dir} {tmax} {lo} {hi}");
                    assert!(!ours || generous, "hit a missed box: {origin} {dir} {tmax}");
                    checked += 1;
                    hits += usize::from(exact);
                }
            }
        }
        assert!(hits > checked / 10, "{hits} of {checked} boxes hit: too few to test");
    }
}
