//! Boxes that repeat exactly, made distinct before obvhs builds over them.
//!
//! obvhs's PLOC merges a pair of neighbours (in Morton order) when each is the other's
//! cheapest partner. Among equal boxes every merge costs the same, its tie rule pairs each
//! node with its right neighbour, and only the last pair is mutual: one merge per pass, so
//! N copies of one triangle (or N instances at spacing 0) took N passes over N nodes
//! (40,000 copies: 45 s, where Embree takes 0.1 s). Each repeat of a box is grown by its own
//! small pad, so merge costs differ, many pairs merge per pass, and the build is
//! O(N log N) again. A grown box still bounds its primitive, so traversal stays exact; the
//! primitives themselves are untouched. Scenes without repeated boxes build as before.

use obvhs::aabb::Aabb;
use std::collections::HashMap;

/// `boxes` with every repeat after a box's first grown by a pad of its own (between 2⁻²⁰ and
/// 2⁻⁸ of the box's size); `None` if no box repeats.
pub(super) fn distinct_boxes(boxes: &[Aabb]) -> Option<Vec<Aabb>> {
    let bits = |b: &Aabb| {
        let (lo, hi) = (b.min.to_array(), b.max.to_array());
        [lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]].map(f32::to_bits)
    };
    let mut seen: HashMap<[u32; 6], u64> = HashMap::with_capacity(boxes.len());
    let mut grown = None::<Vec<Aabb>>;
    for (i, b) in boxes.iter().enumerate() {
        let repeats = seen.entry(bits(b)).or_insert(0);
        *repeats += 1;
        if *repeats == 1 {
            continue;
        }
        let grown = grown.get_or_insert_with(|| boxes.to_vec());
        grown[i] = padded(b, *repeats);
    }
    grown
}

/// `b` grown on every side by a pad that the repeat number `k` picks pseudo-randomly, so
/// that neighbouring repeats rarely get the same one.
fn padded(b: &Aabb, k: u64) -> Aabb {
    let extent = (b.max - b.min).max_element();
    let magnitude = b.min.abs().max(b.max.abs()).max_element();
    // A point-sized box still needs a pad that f32 can hold beside its coordinates.
    let size = extent.max(magnitude * 1e-3).max(f32::MIN_POSITIVE);
    let steps = (1 + crate::splitmix::mix64(k) % 4096) as f32;
    let pad = size * steps * (1.0 / (1 << 20) as f32);
    Aabb { min: b.min - pad, max: b.max + pad }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;

    /// Repeats are grown and still bound the box; the first of each, and a scene without
    /// repeats, are left alone.
    #[test]
    fn repeats_grow_and_still_bound_their_box() {
        let unit = Aabb { min: Vec3A::ZERO, max: Vec3A::ONE };
        let other = Aabb { min: Vec3A::splat(5.0), max: Vec3A::splat(6.0) };
        assert!(distinct_boxes(&[unit, other]).is_none());
        let grown = distinct_boxes(&[unit, other, unit, unit, other]).unwrap();
        assert_eq!((grown[0], grown[1]), (unit, other));
        for (i, original) in [(2, unit), (3, unit), (4, other)] {
            let b = grown[i];
            assert!(b.min.cmplt(original.min).all() && b.max.cmpgt(original.max).all(), "{i}");
            assert!((b.max - original.max).max_element() <= 1.0 / 256.0 + 1e-6, "{i}");
        }
        assert_ne!(grown[2], grown[3], "two repeats got the same pad");
        let point = Aabb { min: Vec3A::ZERO, max: Vec3A::ZERO };
        let grown = distinct_boxes(&[point, point]).unwrap();
        assert!(grown[1].max.x > 0.0);
    }

    /// PLOC over 4096 copies of one box chained them one merge a pass (a tree 4096 deep);
    /// over the grown copies many pairs merge a pass (137 deep: nested boxes do not make a
    /// balanced tree, but not a chain either).
    #[test]
    fn repeated_boxes_build_a_shallow_tree() {
        let unit = Aabb { min: Vec3A::ZERO, max: Vec3A::ONE };
        let params = obvhs::BvhBuildParams::medium_build();
        let build = |boxes: &[Aabb]| {
            let mut time = std::time::Duration::default();
            obvhs::bvh2::builder::build_bvh2(boxes, params, &mut time).depth(0)
        };
        let copies = vec![unit; 4096];
        assert!(build(&copies) > 1000, "obvhs no longer chains repeats: this module can go");
        let depth = build(&distinct_boxes(&copies).unwrap());
        assert!(depth <= 200, "a tree {depth} deep over 4096 boxes");
    }
}
