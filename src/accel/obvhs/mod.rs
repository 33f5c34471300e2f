//! Pure-Rust backend on the obvhs crate: every baked triangle mesh (already in render space)
//! in one BVH, as Embree's top scene holds them; one BVH per other prototype (bottom
//! level) and one over the other instances' bounds (top level: spheres, transformed and
//! moving instances). Transformed instances get the ray in object space; moving instances
//! have bounds over their whole motion at the top level only, and the exact transform at
//! the ray's time.
//!
//! obvhs builds each binary tree (PLOC, reinsertion, leaf collapse); [`WideBvh`] turns it
//! into an 8-wide one laid out for CPU traversal and walks it nearest child first, counting
//! node visits and primitive tests exactly. Triangles are tested with
//! `crate::intersect::intersect_triangle` (the hits are exactly its results), after a cheap
//! conservative test ([`EdgeTest`], four triangles of a leaf at once) that rejects most of
//! the triangles a ray passes outside of without its FMA-based edge functions.
//!
//! The top level's boxes are bounds of transformed boxes, rounded in f32, so its node ray
//! starts `NODE_RAY_BACKOFF` (in units of t) behind the ray: a ray leaving a transformed
//! instance's surface must not cull that instance's neighbours by a rounding. Mesh boxes
//! are exact, and need no such margin (see [`node_test`]).

mod blas;
mod edge_test;
mod node_test;
mod sdf_blas;
mod tie_break;
mod triangle_block;
mod wide_bvh;

use crate::accel::{Accel, AccelOptions, Observes};
use crate::intersect::intersect_sphere;
use crate::ray::{Hit, Ray};
use crate::render_scene::{Geometry, Placement, RenderScene, Sphere, Trs, transformed_bounds};
use crate::stats::TraversalCounters;
use blas::{MeshBlas, aabb_of, build_mesh_blas, build_wide, mesh_triangles, motion_bounds};
use edge_test::EdgeTest;
use glam::{Affine3A, Vec3};
use node_test::NodeRay;
use std::ops::ControlFlow;
use triangle_block::TriangleBlock;
use wide_bvh::WideBvh;

/// Far larger than the rounding of transformed bounds near the origin at any scale we render.
const NODE_RAY_BACKOFF: f32 = 1e-3;

enum Blas {
    Mesh(MeshBlas),
    Sphere(Sphere),
    SdfGrid(sdf_blas::SdfBlas),
}

/// How rays reach an instance's prototype.
enum InstanceTransform {
    Identity,
    Static(Affine3A),
    Moving { start: Trs, end: Trs },
}

struct BlasInstance {
    blas: u32,
    object_from_render: InstanceTransform,
}

/// One ray's query against a mesh BVH; `tmax` narrows as closer hits are found.
#[derive(Clone, Copy)]
struct MeshQuery {
    origin: Vec3,
    dir: Vec3,
    tmin: f32,
    tmax: f32,
    /// Stop at the first hit (shadow rays).
    any_hit: bool,
}

pub struct ObvhsAccel {
    /// Per prototype: its BVH, built only for prototypes that some non-baked instance
    /// places (baked meshes live in `baked`).
    blases: Vec<Option<Blas>>,
    instances: Vec<BlasInstance>,
    /// Every baked triangle mesh (already in render space) in one BVH, as Embree's top
    /// scene holds them: a ray tests all of them in one traversal, with no top level.
    baked: Option<MeshBlas>,
    /// Top level over the other instances' bounds (spheres, transformed and moving
    /// instances); `None` if there are none.
    tlas: Option<WideBvh>,
    /// Instance (geometry id) of each primitive slot of `tlas`.
    tlas_instances: Vec<u32>,
    count_traversal: bool,
}

impl ObvhsAccel {
    pub fn build(scene: &RenderScene, options: &AccelOptions) -> Self {
        let quality = options.build_quality;
        let mut blases: Vec<Option<Blas>> = scene.prototypes.iter().map(|_| None).collect();
        let mut baked_triangles = Vec::new();
        let mut instances = Vec::with_capacity(scene.instances.len());
        let mut bounds = Vec::new();
        let mut tlas_instances = Vec::new();
        for (index, instance) in scene.instances.iter().enumerate() {
            let geometry = &scene.prototypes[instance.prototype as usize].geometry;
            let (lo, hi) = geometry.bounds();
            let (object_from_render, aabb) = match &instance.placement {
                Placement::Baked { .. } => (InstanceTransform::Identity, aabb_of([lo, hi])),
                Placement::Static { render_from_object, object_from_render } => {
                    let (a, b) = transformed_bounds(render_from_object, lo, hi);
                    (InstanceTransform::Static(*object_from_render), aabb_of([a, b]))
                }
                Placement::Moving { start, end } => (
                    InstanceTransform::Moving { start: *start, end: *end },
                    motion_bounds(start, end, lo, hi),
                ),
            };
            instances.push(BlasInstance { blas: instance.prototype, object_from_render });
            match (geometry, &instance.placement) {
                (Geometry::Triangles(mesh), Placement::Baked { .. }) => {
                    baked_triangles.extend(mesh_triangles(mesh, index as u32));
                }
                _ => {
                    blases[instance.prototype as usize].get_or_insert_with(|| match geometry {
                        Geometry::Triangles(mesh) => {
                            Blas::Mesh(build_mesh_blas(mesh_triangles(mesh, 0).collect(), quality))
                        }
                        Geometry::Sphere(s) => Blas::Sphere(*s),
                        Geometry::SdfGrid(grid) => {
                            Blas::SdfGrid(sdf_blas::SdfBlas::build(grid.clone(), quality))
                        }
                    });
                    bounds.push(aabb);
                    tlas_instances.push(index as u32);
                }
            }
        }
        let baked =
            (!baked_triangles.is_empty()).then(|| build_mesh_blas(baked_triangles, quality));
        let tlas = (!bounds.is_empty()).then(|| {
            let (bvh, slot_primitives) = build_wide(std::mem::take(&mut bounds), quality);
            tlas_instances = slot_primitives.iter().map(|&i| tlas_instances[i as usize]).collect();
            bvh
        });
        ObvhsAccel {
            blases,
            instances,
            baked,
            tlas,
            tlas_instances,
            count_traversal: options.count_traversal,
        }
    }

    fn node_ray(origin: Vec3, dir: Vec3, tmax: f32) -> NodeRay {
        NodeRay::new(origin - dir * NODE_RAY_BACKOFF, dir, 0.0, tmax + NODE_RAY_BACKOFF)
    }

    /// Closest hit within one mesh for `query`, narrowing `query.tmax`.
    fn intersect_mesh<const COUNT: bool>(
        mesh: &MeshBlas,
        query: &mut MeshQuery,
        counters: &mut TraversalCounters,
    ) -> Option<(f32, (u32, u32), f32, f32)> {
        // One traversal per permutation of the triangle test, so it is known at compile time.
        match query.dir.abs().max_position() {
            0 => Self::intersect_mesh_axes::<COUNT, 0>(mesh, query, counters),
            1 => Self::intersect_mesh_axes::<COUNT, 1>(mesh, query, counters),
            _ => Self::intersect_mesh_axes::<COUNT, 2>(mesh, query, counters),
        }
    }

    /// `intersect_mesh` for a ray whose direction is largest along axis `KZ`.
    fn intersect_mesh_axes<const COUNT: bool, const KZ: usize>(
        mesh: &MeshBlas,
        query: &mut MeshQuery,
        counters: &mut TraversalCounters,
    ) -> Option<(f32, (u32, u32), f32, f32)> {
        let MeshQuery { origin, dir, tmin, any_hit, .. } = *query;
        let tmax = &mut query.tmax;
        let mut closest = None;
        let edges = EdgeTest::<KZ>::new(origin, dir);
        let mut node_ray = NodeRay::new(origin, dir, 0.0, *tmax);
        mesh.bvh.traverse::<COUNT>(&mut node_ray, counters, |leaf, node_ray, counters| {
            let block = &mesh.blocks[leaf];
            if COUNT {
                counters.prim_tests += block.slots.len() as u64;
            }
            let mut candidates = edges.may_hit_block(block);
            while candidates != 0 {
                let lane = candidates.trailing_zeros() as usize;
                candidates &= candidates - 1;
                let tri = block.triangle(lane);
                let Some((t, u, v)) = edges.intersect_candidate(dir, tmin, *tmax, &tri) else {
                    continue;
                };
                *tmax = t;
                node_ray.tmax = t;
                closest = Some((t, mesh.ids[block.slots.start as usize + lane], u, v));
                if any_hit {
                    return ControlFlow::Break(());
                }
            }
            ControlFlow::Continue(())
        });
        closest
    }

    fn intersect_instance<const COUNT: bool>(
        &self,
        instance: &BlasInstance,
        ray: &Ray,
        tmax: &mut f32,
        counters: &mut TraversalCounters,
        any_hit: bool,
    ) -> Option<(f32, u32, f32, f32)> {
        let object_from_render = match &instance.object_from_render {
            InstanceTransform::Identity => None,
            InstanceTransform::Static(m) => Some(*m),
            InstanceTransform::Moving { start, end } => {
                Some(start.lerp(end, ray.time.clamp(0.0, 1.0)).to_affine().inverse())
            }
        };
        // An affine map keeps t: the object-space direction is not renormalised.
        let (origin, dir) = match object_from_render {
            None => (ray.origin, ray.dir),
            Some(m) => (m.transform_point3(ray.origin), m.transform_vector3(ray.dir)),
        };
        match &self.blases[instance.blas as usize] {
            Some(Blas::Mesh(mesh)) => {
                let mut query = MeshQuery { origin, dir, tmin: ray.tmin, tmax: *tmax, any_hit };
                let hit = Self::intersect_mesh::<COUNT>(mesh, &mut query, counters);
                *tmax = query.tmax;
                hit.map(|(t, (_, prim_id), u, v)| (t, prim_id, u, v))
            }
            Some(Blas::Sphere(s)) => {
                if COUNT {
                    counters.prim_tests += 1;
                }
                let t = intersect_sphere(origin, dir, ray.tmin, *tmax, s.center, s.radius)?;
                *tmax = t;
                Some((t, 0, 0.0, 0.0))
            }
            Some(Blas::SdfGrid(grid)) => {
                let hit = grid.intersect::<COUNT>((origin, dir), ray.tmin, tmax, counters, any_hit);
                hit.map(|(t, prim)| (t, prim, 0.0, 0.0))
            }
            // Every instance in the top level has its prototype's BVH (see `build`).
            None => None,
        }
    }

    fn trace<const COUNT: bool>(
        &self,
        ray: &Ray,
        counters: &mut TraversalCounters,
        any_hit: bool,
    ) -> Option<Hit> {
        let mut tmax = ray.tmax;
        let mut best: Option<Hit> = None;
        if let Some(baked) = &self.baked {
            let mut query =
                MeshQuery { origin: ray.origin, dir: ray.dir, tmin: ray.tmin, tmax, any_hit };
            let hit = Self::intersect_mesh::<COUNT>(baked, &mut query, counters);
            tmax = query.tmax;
            if let Some((t, (geom_id, prim_id), u, v)) = hit {
                best = Some(Hit { t, geom_id, prim_id, u, v });
                if any_hit {
                    return best;
                }
            }
        }
        self.trace_tlas::<COUNT>(ray, tmax, best, counters, any_hit)
    }

    /// The top-level part of [`ObvhsAccel::trace`]: `ray` against the non-baked instances,
    /// given the closest hit `best` (within `tmax`) found so far.
    fn trace_tlas<const COUNT: bool>(
        &self,
        ray: &Ray,
        mut tmax: f32,
        mut best: Option<Hit>,
        counters: &mut TraversalCounters,
        any_hit: bool,
    ) -> Option<Hit> {
        let Some(tlas) = &self.tlas else { return best };
        let mut node_ray = Self::node_ray(ray.origin, ray.dir, tmax);
        tlas.traverse::<COUNT>(&mut node_ray, counters, |leaf, node_ray, counters| {
            for slot in tlas.leaves()[leaf].clone() {
                let slot = slot as usize;
                let geom_id = self.tlas_instances[slot];
                let instance = &self.instances[geom_id as usize];
                let Some((t, prim_id, u, v)) =
                    self.intersect_instance::<COUNT>(instance, ray, &mut tmax, counters, any_hit)
                else {
                    continue;
                };
                node_ray.tmax = t + NODE_RAY_BACKOFF;
                best = Some(Hit { t, geom_id, prim_id, u, v });
                if any_hit {
                    return ControlFlow::Break(());
                }
            }
            ControlFlow::Continue(())
        });
        best
    }
}

impl Accel for ObvhsAccel {
    fn name(&self) -> &'static str {
        "obvhs"
    }

    fn intersect(&self, ray: &Ray, counters: &mut TraversalCounters) -> Option<Hit> {
        if !ray.is_valid() {
            return None;
        }
        if self.count_traversal {
            self.trace::<true>(ray, counters, false)
        } else {
            self.trace::<false>(ray, counters, false)
        }
    }

    fn occluded(&self, ray: &Ray, counters: &mut TraversalCounters) -> bool {
        if !ray.is_valid() {
            return false;
        }
        if self.count_traversal {
            self.trace::<true>(ray, counters, true).is_some()
        } else {
            self.trace::<false>(ray, counters, true).is_some()
        }
    }

    fn memory_bytes(&self) -> Option<usize> {
        let mesh = |m: &MeshBlas| {
            m.bvh.memory_bytes()
                + m.blocks.capacity() * size_of::<TriangleBlock>()
                + m.ids.capacity() * size_of::<(u32, u32)>()
        };
        let blases = self.blases.iter().flatten().map(|b| match b {
            Blas::Mesh(m) => mesh(m),
            Blas::Sphere(_) => size_of::<Sphere>(),
            Blas::SdfGrid(grid) => grid.memory_bytes(),
        });
        Some(
            blases.sum::<usize>()
                + self.baked.as_ref().map_or(0, mesh)
                + self.tlas.as_ref().map_or(0, WideBvh::memory_bytes)
                + self.tlas_instances.capacity() * size_of::<u32>()
                + self.instances.capacity() * size_of::<BlasInstance>(),
        )
    }

    fn observes(&self) -> Observes {
        Observes { node_visits: self.count_traversal, prim_tests: self.count_traversal }
    }
}
