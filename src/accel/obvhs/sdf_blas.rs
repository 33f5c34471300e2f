//! A signed distance grid's bottom level: a wide BVH over its voxels' boxes, each voxel
//! tested with `crate::intersect_sdf::intersect_voxel` (the function Embree's callbacks
//! call, so both backends find the same hits).

use super::blas::{aabb_of, build_wide};
use super::node_test::NodeRay;
use super::wide_bvh::WideBvh;
use crate::accel::BuildQuality;
use crate::intersect_sdf::intersect_voxel;
use crate::sdf_grid::SdfGrid;
use crate::stats::TraversalCounters;
use glam::Vec3;
use std::ops::ControlFlow;
use std::sync::Arc;

pub(super) struct SdfBlas {
    grid: Arc<SdfGrid>,
    bvh: WideBvh,
    /// The primitive (voxel) of each slot of `bvh`.
    prims: Vec<u32>,
}

impl SdfBlas {
    pub(super) fn build(grid: Arc<SdfGrid>, quality: BuildQuality) -> Self {
        let boxes = grid.boxes.iter().map(|&(lo, hi)| aabb_of([lo, hi])).collect();
        let (bvh, prims) = build_wide(boxes, quality);
        SdfBlas { grid, bvh, prims }
    }

    pub(super) fn memory_bytes(&self) -> usize {
        self.bvh.memory_bytes() + self.prims.capacity() * size_of::<u32>()
    }

    /// The closest hit in `[tmin, *tmax]` (narrowing `*tmax`) as (t, primitive), or the
    /// first found when `any_hit`.
    pub(super) fn intersect<const COUNT: bool>(
        &self,
        (origin, dir): (Vec3, Vec3),
        tmin: f32,
        tmax: &mut f32,
        counters: &mut TraversalCounters,
        any_hit: bool,
    ) -> Option<(f32, u32)> {
        let mut closest = None;
        let mut node_ray = NodeRay::new(origin, dir, 0.0, *tmax);
        self.bvh.traverse::<COUNT>(&mut node_ray, counters, |leaf, node_ray, counters| {
            for slot in self.bvh.leaves()[leaf].clone() {
                if COUNT {
                    counters.prim_tests += 1;
                }
                let prim = self.prims[slot as usize];
                let Some((voxel, corners)) = self.grid.prim_corners(prim) else { continue };
                let Some(t) = intersect_voxel(origin, dir, tmin, *tmax, voxel, &corners) else {
                    continue;
                };
                *tmax = t;
                node_ray.tmax = t;
                closest = Some((t, prim));
                if any_hit {
                    return ControlFlow::Break(());
                }
            }
            ControlFlow::Continue(())
        });
        closest
    }
}
