//! A leaf's triangles (at most four) stored lane by lane, so one ray is pre-tested against
//! all of them at once ([`super::edge_test::EdgeTest::may_hit_block`]).

use glam::Vec3;
use std::ops::Range;
use wide::f32x4;

/// Triangles one leaf can hold (the build caps obvhs's leaves at this).
pub(super) const LANES: usize = 4;

pub(super) struct TriangleBlock {
    /// `vertices[vertex][axis]`, lane i holding triangle i; unused lanes repeat triangle 0.
    pub(super) vertices: [[f32x4; 3]; 3],
    /// The triangles' primitive slots (lane i: slot `slots.start + i`).
    pub(super) slots: Range<u32>,
}

impl TriangleBlock {
    /// The triangles of `slots` (at most [`LANES`]).
    pub(super) fn new(triangles: &[[Vec3; 3]], slots: Range<u32>) -> Self {
        let block = &triangles[slots.start as usize..slots.end as usize];
        assert!(!block.is_empty() && block.len() <= LANES, "{} triangles in a leaf", block.len());
        let vertices = std::array::from_fn(|vertex| {
            std::array::from_fn(|axis| {
                f32x4::new(std::array::from_fn(|lane| {
                    block[lane.min(block.len() - 1)][vertex][axis]
                }))
            })
        });
        TriangleBlock { vertices, slots }
    }

    /// Triangle `lane`, exactly as stored.
    #[inline(always)]
    pub(super) fn triangle(&self, lane: usize) -> [Vec3; 3] {
        self.vertices
            .map(|v| Vec3::new(v[0].as_array()[lane], v[1].as_array()[lane], v[2].as_array()[lane]))
    }

    /// Lanes holding a triangle: bit i for lane i.
    #[inline(always)]
    pub(super) fn lane_mask(&self) -> u32 {
        (1 << (self.slots.end - self.slots.start)) - 1
    }
}
