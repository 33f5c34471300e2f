//! Bottom-level structures: a wide BVH over triangles with their leaf blocks, and the
//! bounds of moving instances.

use super::triangle_block::{self, TriangleBlock};
use super::wide_bvh::WideBvh;
use crate::accel::BuildQuality;
use crate::render_scene::{TriangleMesh, Trs, transformed_bounds};
use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb;
use obvhs::bvh2::builder::build_bvh2;
use std::time::Duration;

/// Time samples used to bound a moving instance (plus a margin for rotation in between).
const MOTION_BOUND_STEPS: usize = 32;

pub(super) struct MeshBlas {
    pub(super) bvh: WideBvh,
    /// Per leaf of `bvh` (by leaf index), its triangles.
    pub(super) blocks: Vec<TriangleBlock>,
    /// Geometry id (instance index; only meaningful in the baked BVH, see
    /// [`ObvhsAccel::baked`]) and original triangle index of each primitive slot.
    pub(super) ids: Vec<(u32, u32)>,
}

pub(super) fn aabb_of(points: impl IntoIterator<Item = Vec3>) -> Aabb {
    let mut aabb = Aabb::empty();
    for p in points {
        aabb.extend(Vec3A::from(p));
    }
    aabb
}

/// obvhs's presets, with leaves no larger than a triangle block.
fn build_params(quality: BuildQuality) -> BvhBuildParams {
    let preset = match quality {
        BuildQuality::Low => BvhBuildParams::fastest_build(),
        BuildQuality::Medium => BvhBuildParams::medium_build(),
        BuildQuality::High => BvhBuildParams::slow_build(),
    };
    BvhBuildParams { max_prims_per_leaf: triangle_block::LANES as u32, ..preset }
}

/// The wide BVH over `boxes`, built through obvhs's binary tree (repeated boxes made
/// distinct first: `tie_break`), and each of its slots' primitive.
pub(super) fn build_wide(boxes: Vec<Aabb>, quality: BuildQuality) -> (WideBvh, Vec<u32>) {
    let boxes = super::tie_break::distinct_boxes(&boxes).unwrap_or(boxes);
    let bvh2 = build_bvh2(&boxes, build_params(quality), &mut Duration::default());
    WideBvh::new(&bvh2, &boxes)
}

/// A BVH over `triangles` (each with its geometry id and triangle index).
pub(super) fn build_mesh_blas(
    triangles: Vec<([Vec3; 3], (u32, u32))>,
    quality: BuildQuality,
) -> MeshBlas {
    let boxes: Vec<Aabb> = triangles.iter().map(|(t, _)| aabb_of(*t)).collect();
    let (bvh, slot_primitives) = build_wide(boxes, quality);
    let (triangles, ids): (Vec<_>, _) =
        slot_primitives.iter().map(|&i| triangles[i as usize]).unzip();
    let blocks =
        bvh.leaves().iter().map(|slots| TriangleBlock::new(&triangles, slots.clone())).collect();
    MeshBlas { bvh, blocks, ids }
}

pub(super) fn mesh_triangles(
    mesh: &TriangleMesh,
    geom_id: u32,
) -> impl Iterator<Item = ([Vec3; 3], (u32, u32))> {
    (0..mesh.indices.len() as u32).map(move |i| (mesh.triangle(i), (geom_id, i)))
}

/// Bounds of a moving instance over the whole shutter interval: the box at many times,
/// grown by how far a rotating corner can bulge between two samples.
pub(super) fn motion_bounds(start: &Trs, end: &Trs, lo: Vec3, hi: Vec3) -> Aabb {
    let mut aabb = Aabb::empty();
    for step in 0..=MOTION_BOUND_STEPS {
        let t = step as f32 / MOTION_BOUND_STEPS as f32;
        let (a, b) = transformed_bounds(&start.lerp(end, t).to_affine(), lo, hi);
        aabb.extend(Vec3A::from(a));
        aabb.extend(Vec3A::from(b));
    }
    let angle = start.rotation.angle_between(end.rotation);
    let step_angle = angle / MOTION_BOUND_STEPS as f32;
    let radius = (hi - lo).length() * 0.5 * start.scale.max(end.scale).max_element()
        + (lo + hi).abs().max_element() * start.scale.max(end.scale).max_element();
    let bulge = radius * (1.0 - (0.5 * step_angle).cos()) + 1e-5 * aabb.diagonal().length();
    Aabb::new(aabb.min - Vec3A::splat(bulge), aabb.max + Vec3A::splat(bulge))
}
