//! A ray against all eight children of an obvhs CWBVH node in one pass.
//!
//! obvhs's own `CwBvhNode::intersect_ray` tests four children at a time with SSE intrinsics,
//! gathers the 8-bit quantized planes one lane at a time and clamps the entry distance to
//! 1e-4. This version is plain Rust over the node's arrays, which the compiler turns into
//! 8-wide vector code where the target has AVX2 (`.cargo/config.toml`) and 4-wide code
//! otherwise; it uses the ray's own `tmin` and never produces a NaN (see [`NodeRay::new`]).

use glam::Vec3;
use obvhs::cwbvh::node::CwBvhNode;

/// Directions smaller than this are replaced by it (with their sign) before inverting, so
/// `0 · ∞` cannot occur; any t a ray can reach stays far below where this changes a result.
const TINY_DIRECTION: f32 = 1e-18;

/// Slab distances carry a few roundings: the far distance is enlarged by more than their
/// relative error (pbrt's `1 + 2γ₃`), so a box the ray touches is never culled by them.
const FAR_SCALE: f32 = 1.0 + 4.0 * f32::EPSILON;

/// A ray prepared for node tests.
pub(super) struct NodeRay {
    origin: Vec3,
    inv_dir: Vec3,
    negative: [bool; 3],
    tmin: f32,
    pub tmax: f32,
}

impl NodeRay {
    pub(super) fn new(origin: Vec3, dir: Vec3, tmin: f32, tmax: f32) -> Self {
        let safe = |d: f32| if d.abs() < TINY_DIRECTION { TINY_DIRECTION.copysign(d) } else { d };
        let inv_dir = Vec3::new(1.0 / safe(dir.x), 1.0 / safe(dir.y), 1.0 / safe(dir.z));
        let negative = [inv_dir.x < 0.0, inv_dir.y < 0.0, inv_dir.z < 0.0];
        NodeRay { origin, inv_dir, negative, tmin, tmax }
    }
}

#[inline(always)]
fn max(a: f32, b: f32) -> f32 {
    if a > b { a } else { b }
}

#[inline(always)]
fn min(a: f32, b: f32) -> f32 {
    if a < b { a } else { b }
}

/// obvhs's hit mask for `node` (what `CwBvhNode::intersect_ray` returns, for the children
/// the ray's segment `[tmin, tmax]` overlaps), for the traversal octant `oct_inv4`.
#[inline(always)]
pub(super) fn child_hits(node: &CwBvhNode, ray: &NodeRay, oct_inv4: u32) -> u32 {
    // The planes of a child are p + q · 2^e for the 8-bit q of each axis.
    let extent = |e: u8| f32::from_bits((e as u32) << 23);
    let scale = Vec3::new(extent(node.e[0]), extent(node.e[1]), extent(node.e[2])) * ray.inv_dir;
    let offset = (node.p - ray.origin) * ray.inv_dir;
    let near_far = |negative: bool, lo: &'_ [u8; 8], hi: &'_ [u8; 8]| -> ([u8; 8], [u8; 8]) {
        if negative { (*hi, *lo) } else { (*lo, *hi) }
    };
    let (near_x, far_x) = near_far(ray.negative[0], &node.child_min_x, &node.child_max_x);
    let (near_y, far_y) = near_far(ray.negative[1], &node.child_min_y, &node.child_max_y);
    let (near_z, far_z) = near_far(ray.negative[2], &node.child_min_z, &node.child_max_z);
    let (child_bits, bit_index) = node.get_child_and_index_bits(oct_inv4);
    let (child_bits, bit_index) = (child_bits.to_le_bytes(), bit_index.to_le_bytes());
    let mut hits = 0u32;
    for i in 0..8 {
        let t_near = max(
            max(near_x[i] as f32 * scale.x + offset.x, near_y[i] as f32 * scale.y + offset.y),
            max(near_z[i] as f32 * scale.z + offset.z, ray.tmin),
        );
        let t_far = min(
            min(far_x[i] as f32 * scale.x + offset.x, far_y[i] as f32 * scale.y + offset.y),
            min(far_z[i] as f32 * scale.z + offset.z, ray.tmax),
        );
        let hit = t_near <= t_far * FAR_SCALE;
        hits |= if hit { (child_bits[i] as u32) << bit_index[i] } else { 0 };
    }
    hits
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Rng;
    use glam::{DVec3, Vec3A};
    use obvhs::BvhBuildParams;
    use obvhs::aabb::Aabb;
    use obvhs::cwbvh::builder::build_cwbvh;

    /// Child `child`'s box exactly as its planes define it (p + q · 2^e, in f64), grown by
    /// `margin` of the node's size.
    fn child_box(node: &CwBvhNode, child: usize, margin: f64) -> (DVec3, DVec3) {
        let extent = |e: u8| f32::from_bits((e as u32) << 23) as f64;
        let e = DVec3::new(extent(node.e[0]), extent(node.e[1]), extent(node.e[2]));
        let p = node.p.as_dvec3();
        let q = |v: &[u8; 8]| v[child] as f64;
        let lo =
            p + e * DVec3::new(q(&node.child_min_x), q(&node.child_min_y), q(&node.child_min_z));
        let hi =
            p + e * DVec3::new(q(&node.child_max_x), q(&node.child_max_y), q(&node.child_max_z));
        let grow = e * 255.0 * margin;
        (lo - grow, hi + grow)
    }

    /// Whether the segment [tmin, tmax] of the ray meets the box, in f64.
    fn segment_meets(o: DVec3, d: DVec3, tmin: f64, tmax: f64, (lo, hi): (DVec3, DVec3)) -> bool {
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

    /// The mask `child_hits` would return if it tested exactly the children `hit` says.
    fn mask_of(node: &CwBvhNode, oct_inv4: u32, hit: impl Fn(usize) -> bool) -> u32 {
        let (child_bits, bit_index) = node.get_child_and_index_bits(oct_inv4);
        let (child_bits, bit_index) = (child_bits.to_le_bytes(), bit_index.to_le_bytes());
        (0..8)
            .filter(|&i| hit(i))
            .map(|i| (child_bits[i] as u32) << bit_index[i])
            .fold(0, |a, b| a | b)
    }

    /// Never culls a child box the ray segment meets (computed exactly), and reports none it
    /// misses by more than a hair — over random boxes at scales 1e-3 to 1e6, random and
    /// axis-aligned rays, rays starting inside boxes and finite and infinite segments.
    #[test]
    fn child_hits_are_the_exact_box_hits_up_to_a_hair() {
        let mut rng = Rng(11);
        let (mut checked, mut hits) = (0usize, 0usize);
        for scale in [1e-3, 1.0, 1e3, 1e6] {
            let boxes: Vec<Aabb> = (0..400)
                .map(|_| {
                    let c = rng.vec3(-0.5 * scale, 0.5 * scale);
                    let h = rng.vec3(-0.05 * scale, 0.05 * scale).abs();
                    Aabb::new(Vec3A::from(c - h), Vec3A::from(c + h))
                })
                .collect();
            let bvh = build_cwbvh(&boxes, BvhBuildParams::medium_build(), &mut Default::default());
            for k in 0..2000 {
                let origin = rng.vec3(-0.75 * scale, 0.75 * scale);
                let mut dir = rng.vec3(-1.0, 1.0).normalize_or(Vec3::X);
                if k % 5 == 0 {
                    let axis = dir.abs().max_position();
                    dir = Vec3::ZERO;
                    dir[axis] = if k % 2 == 0 { 1.0 } else { -1.0 };
                }
                let tmax = if k % 3 == 0 { f32::INFINITY } else { rng.unit() * scale };
                let ray = NodeRay::new(origin, dir, 0.0, tmax);
                let oct_inv4 = bvh.new_traversal(Vec3A::from(dir)).oct_inv4;
                let (o, d) = (origin.as_dvec3(), dir.as_dvec3());
                for node in &bvh.nodes {
                    let ours = child_hits(node, &ray, oct_inv4);
                    let seg = |margin| {
                        move |i| segment_meets(o, d, 0.0, tmax as f64, child_box(node, i, margin))
                    };
                    let exact = mask_of(node, oct_inv4, seg(0.0));
                    let generous = mask_of(node, oct_inv4, seg(1e-5));
                    assert_eq!(ours & exact, exact, "culled a box: {origin} {dir} {tmax}");
                    assert_eq!(ours & !generous, 0, "hit a missed box: {origin} {dir} {tmax}");
                    checked += 1;
                    hits += usize::from(exact != 0);
                }
            }
        }
        assert!(hits > 5_000, "{hits} of {checked} nodes hit: too few to test");
    }
}
