//! Coherent rays (the renderer's camera rays) traced eight at a time through the baked BVH:
//! one walk of the tree for the whole packet, each node tested against every ray and each
//! leaf's triangles against every ray, so a node's memory is fetched once for eight rays.
//!
//! Exactly the single-ray hits, ties included: the packet's walk visits, in the same octant
//! order, every node a ray's own walk would (a node is culled only when every ray culls it,
//! and a ray's `tmax` at any point is at most what its own walk would have there), so each
//! ray meets the triangles of its own walk in the same order, plus some it cannot hit
//! closer. The non-baked instances are then traced ray by ray.

use super::edge_test::RayEdgeTest;
use super::node_test::{NodeRay, child_hits};
use super::{NODE_RAY_BACKOFF, ObvhsAccel};
use crate::accel::{Hit, Ray};
use crate::stats::TraversalCounters;
use glam::{UVec2, Vec3A};
use obvhs::traverse;

/// Rays per packet.
pub(super) const WIDTH: usize = 8;

impl ObvhsAccel {
    /// Closest hits of up to [`WIDTH`] rays traced as a packet, if they can be one: all valid,
    /// all in one direction octant (so they share the walk's child order), and a baked BVH
    /// to walk. Returns false, leaving `hits` alone, otherwise.
    pub(super) fn trace_packet(&self, rays: &[Ray], hits: &mut [Option<Hit>]) -> bool {
        let (Some(mesh), Some(first)) = (&self.baked, rays.first()) else { return false };
        let octant = |r: &Ray| (r.dir.x < 0.0, r.dir.y < 0.0, r.dir.z < 0.0);
        if rays.len() > WIDTH || !rays.iter().all(|r| r.is_valid() && octant(r) == octant(first)) {
            return false;
        }
        let mut tmax = [0.0; WIDTH];
        let mut closest: [Option<Hit>; WIDTH] = [None; WIDTH];
        // Lanes past the packet's rays repeat the last one and are never read.
        let lane_ray = |lane: usize| &rays[lane.min(rays.len() - 1)];
        let mut node_rays: [NodeRay; WIDTH] = std::array::from_fn(|lane| {
            let r = lane_ray(lane);
            tmax[lane] = r.tmax;
            ObvhsAccel::node_ray(r.origin, r.dir, r.tmax)
        });
        let edges: [RayEdgeTest; WIDTH] =
            std::array::from_fn(|lane| RayEdgeTest::new(lane_ray(lane).origin, lane_ray(lane).dir));
        let active = rays.len();
        // Each ray's own hit mask for the node tested last.
        let mut lane_hits = [0u32; WIDTH];
        let mut primitive_base = 0;
        let mut state = mesh.bvh.new_traversal(Vec3A::from(first.dir));
        let mut node;
        traverse!(
            mesh.bvh,
            node,
            state,
            {
                let mut hit_children = 0;
                primitive_base = node.primitive_base_idx;
                for (node_ray, lane_hits) in node_rays[..active].iter().zip(&mut lane_hits) {
                    *lane_hits = child_hits(node, node_ray, state.oct_inv4);
                    hit_children |= *lane_hits;
                }
                hit_children
            },
            {
                // The primitives handed out belong to the node tested last; a ray whose
                // own test missed this one's leaf cannot hit it.
                let bit = 1u32 << (state.primitive_id - primitive_base);
                let index = state.primitive_id as usize;
                let tri = &mesh.triangles[index];
                for (lane, ray) in rays.iter().enumerate() {
                    if lane_hits[lane] & bit == 0 {
                        continue;
                    }
                    if let Some((t, u, v)) =
                        edges[lane].intersect(ray.dir, ray.tmin, tmax[lane], tri)
                    {
                        tmax[lane] = t;
                        node_rays[lane].tmax = t + NODE_RAY_BACKOFF;
                        let (geom_id, prim_id) = mesh.ids[index];
                        closest[lane] = Some(Hit { t, geom_id, prim_id, u, v });
                    }
                }
            }
        );
        let mut counters = TraversalCounters::default();
        for (lane, (ray, hit)) in rays.iter().zip(hits).enumerate() {
            *hit = self.trace_tlas::<false>(ray, tmax[lane], closest[lane], &mut counters, false);
        }
        true
    }
}
