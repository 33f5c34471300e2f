//! obvhs's CWBVH re-laid out for CPU traversal: the same tree (same nodes, same leaves) with
//! each node's eight child boxes as plain f32 planes in SoA rows, and a traversal that
//! visits children nearest first and drops a stacked child as soon as a closer hit makes it
//! unreachable.
//!
//! The CWBVH is laid out for GPUs: 8-bit quantized child boxes (decoded on every visit and
//! up to 1/255 of the node larger than the child on each side) and children visited in an
//! order fixed by the ray's octant, with no distance on the stack. On a CPU the decoding
//! and the extra visits cost more than the memory the quantization saves. Here the child
//! boxes are the exact bounds of the primitives below them.

use super::node_test::{FAR_SCALE, NodeRay, Planes, child_hits};
use crate::stats::TraversalCounters;
use obvhs::aabb::Aabb;
use obvhs::cwbvh::CwBvh;
use std::ops::{ControlFlow, Range};
use wide::f32x8;

/// A child reference with this bit set is a leaf, the bits below its leaf index.
const LEAF: u32 = 1 << 31;

/// Stack entries kept on the call stack; trees needing more (only degenerate input
/// builds them) get a heap stack.
const INLINE_STACK: usize = 128;

/// One node: up to eight children, each an inner node or a leaf.
#[derive(Clone, Copy)]
#[repr(C, align(64))]
pub(super) struct WideNode {
    /// The children's boxes. Empty slots hold the inverted box +∞..−∞, which no ray meets.
    planes: Planes,
    /// Node index, or a leaf (see [`LEAF`]).
    children: [u32; 8],
}

pub(super) struct WideBvh {
    nodes: Vec<WideNode>,
    /// Per leaf (in leaf index order, the leaves of a node consecutive), its primitive slots.
    leaves: Vec<Range<u32>>,
    /// Stack entries a traversal can need at most (sorted pushes of every level's children).
    stack_depth: usize,
}

impl WideBvh {
    /// `cwbvh`'s tree with exact child boxes; `primitive_bounds[slot]` bounds the primitive
    /// at position `slot` of `cwbvh.primitive_indices`.
    pub(super) fn new(cwbvh: &CwBvh, primitive_bounds: &[Aabb]) -> Self {
        assert!(
            primitive_bounds.len() < LEAF as usize,
            "{} primitives in one BVH: more than the layout addresses",
            primitive_bounds.len()
        );
        let empty = WideNode {
            planes: [
                f32x8::INFINITY,
                f32x8::NEG_INFINITY,
                f32x8::INFINITY,
                f32x8::NEG_INFINITY,
                f32x8::INFINITY,
                f32x8::NEG_INFINITY,
            ],
            children: [0; 8],
        };
        let mut nodes = vec![empty; cwbvh.nodes.len()];
        let mut leaves = Vec::new();
        let mut node_bounds = vec![Aabb::empty(); nodes.len()];
        let mut depth_of = vec![0; nodes.len()];
        // obvhs appends a node's children after it: in reverse order every child is done
        // before its parent.
        for (index, source) in cwbvh.nodes.iter().enumerate().rev() {
            let node = &mut nodes[index];
            // Stack entries this subtree can need: its children pushed, then each child's
            // subtree with up to all its siblings still below it.
            let (mut count, mut deepest) = (0usize, 0);
            for child in (0..8).filter(|&child| !source.is_child_empty(child)) {
                let (bounds, reference) = if source.is_leaf(child) {
                    let (first, count) = source.child_primitives(child);
                    let slots = first as usize..(first + count) as usize;
                    let bounds =
                        primitive_bounds[slots].iter().fold(Aabb::empty(), |a, b| a.union(b));
                    let reference = LEAF | leaves.len() as u32;
                    leaves.push(first..first + count);
                    (bounds, reference)
                } else {
                    let child_index = source.child_node_index(child) as usize;
                    assert!(child_index > index, "obvhs stores children after their parent");
                    deepest = deepest.max(depth_of[child_index]);
                    (node_bounds[child_index], child_index as u32)
                };
                for axis in 0..3 {
                    node.planes[2 * axis].as_mut_array()[child] = bounds.min[axis];
                    node.planes[2 * axis + 1].as_mut_array()[child] = bounds.max[axis];
                }
                node_bounds[index] = node_bounds[index].union(&bounds);
                node.children[child] = reference;
                count += 1;
            }
            depth_of[index] = count.max(count.saturating_sub(1) + deepest);
        }
        let stack_depth = 1 + depth_of.first().copied().unwrap_or(0);
        WideBvh { nodes, leaves, stack_depth }
    }

    /// The leaves in leaf index order: each one's primitive slots.
    pub(super) fn leaves(&self) -> &[Range<u32>] {
        &self.leaves
    }

    /// Walks the nodes `ray` meets, nearest child first, handing each leaf's index to `leaf`
    /// (with `counters`; it narrows `ray.tmax` on a hit and breaks to stop the walk).
    #[inline(always)]
    pub(super) fn traverse<const COUNT: bool>(
        &self,
        ray: &mut NodeRay,
        counters: &mut TraversalCounters,
        leaf: impl FnMut(usize, &mut NodeRay, &mut TraversalCounters) -> ControlFlow<()>,
    ) {
        // Deeper trees than this come only from degenerate input; they get a heap stack.
        if self.stack_depth <= INLINE_STACK {
            self.walk::<COUNT>(&mut [(0, 0.0); INLINE_STACK], ray, counters, leaf)
        } else {
            self.walk::<COUNT>(&mut vec![(0, 0.0); self.stack_depth], ray, counters, leaf)
        }
    }

    fn walk<const COUNT: bool>(
        &self,
        stack: &mut [(u32, f32)],
        ray: &mut NodeRay,
        counters: &mut TraversalCounters,
        mut leaf: impl FnMut(usize, &mut NodeRay, &mut TraversalCounters) -> ControlFlow<()>,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let mut top = 0;
        // The child being entered: the root, then always the nearest child not yet entered.
        let mut current = 0u32;
        loop {
            if current & LEAF != 0 {
                if leaf((current & !LEAF) as usize, ray, counters).is_break() {
                    return;
                }
            } else {
                if COUNT {
                    counters.node_visits += 1;
                }
                let node = &self.nodes[current as usize];
                let (mut hits, t_near) = child_hits(&node.planes, ray);
                if hits != 0 {
                    let nearest = hits.trailing_zeros() as usize;
                    hits &= hits - 1;
                    if hits == 0 {
                        current = node.children[nearest];
                        continue;
                    }
                    let other = hits.trailing_zeros() as usize;
                    hits &= hits - 1;
                    if hits == 0 {
                        // Two children: enter the nearer, stack the farther.
                        let (near, far) = if t_near[other] < t_near[nearest] {
                            (other, nearest)
                        } else {
                            (nearest, other)
                        };
                        stack[top] = (node.children[far], t_near[far]);
                        top += 1;
                        current = node.children[near];
                        continue;
                    }
                    // More: stack them all, farthest at the bottom, and enter the top one.
                    let bottom = top;
                    for child in [nearest, other].into_iter().chain(BitIter(hits)) {
                        let entry = (node.children[child], t_near[child]);
                        let mut slot = top;
                        while slot > bottom && stack[slot - 1].1 < entry.1 {
                            stack[slot] = stack[slot - 1];
                            slot -= 1;
                        }
                        stack[slot] = entry;
                        top += 1;
                    }
                    top -= 1;
                    current = stack[top].0;
                    continue;
                }
            }
            // Pop the nearest stacked child that a hit found since has not put out of reach.
            loop {
                if top == 0 {
                    return;
                }
                top -= 1;
                let (reference, t_near) = stack[top];
                if t_near <= ray.tmax * FAR_SCALE {
                    current = reference;
                    break;
                }
            }
        }
    }
}

/// The indices of a mask's set bits, lowest first.
pub(super) struct BitIter(pub(super) u32);

impl Iterator for BitIter {
    type Item = usize;

    #[inline(always)]
    fn next(&mut self) -> Option<usize> {
        (self.0 != 0).then(|| {
            let bit = self.0.trailing_zeros() as usize;
            self.0 &= self.0 - 1;
            bit
        })
    }
}
