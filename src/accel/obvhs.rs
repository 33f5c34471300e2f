//! Pure-Rust backend on the obvhs crate: one CWBVH per shape (bottom level) and one CWBVH over
//! the shapes' bounds (top level), traversed with obvhs's `traverse!` macro so node visits and
//! primitive tests can be counted exactly.
//!
//! obvhs's node test clamps the entry distance to 1e-4 (`node::EPSILON`), which would cull
//! boxes the ray enters and leaves within 1e-4 of its origin — exactly where a spawned ray
//! meets the neighbouring wall in a corner. Node tests therefore use the ray with its origin
//! moved back by `NODE_RAY_BACKOFF` (in units of t); primitive tests use the real ray.

use crate::accel::{Accel, AccelOptions, Hit, Observes, Ray};
use crate::geometry::{intersect_sphere, intersect_triangle};
use crate::render_scene::{Geometry, RenderScene, Sphere};
use crate::stats::TraversalCounters;
use glam::{UVec2, Vec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::builder::build_cwbvh;
use obvhs::ray::Ray as BvhRay;
use obvhs::{BvhBuildParams, traverse};
use std::time::Duration;

/// Larger than obvhs's internal 1e-4 node epsilon, with margin for rounding.
const NODE_RAY_BACKOFF: f32 = 1e-3;

struct MeshBlas {
    bvh: CwBvh,
    /// Triangles in BVH leaf order, so a leaf's primitives are contiguous in memory.
    triangles: Vec<[Vec3; 3]>,
    /// Original triangle index of each entry of `triangles`.
    prim_ids: Vec<u32>,
}

enum Blas {
    Mesh(MeshBlas),
    Sphere(Sphere),
}

pub struct ObvhsAccel {
    blases: Vec<Blas>,
    /// Top level over shape bounds; `None` for an empty scene.
    tlas: Option<CwBvh>,
    count_traversal: bool,
}

fn aabb_of(points: impl IntoIterator<Item = Vec3>) -> Aabb {
    let mut aabb = Aabb::empty();
    for p in points {
        aabb.extend(Vec3A::from(p));
    }
    aabb
}

fn build_params() -> BvhBuildParams {
    BvhBuildParams::medium_build()
}

fn build_mesh_blas(mesh: &crate::render_scene::TriangleMesh) -> (MeshBlas, Aabb) {
    let tris: Vec<[Vec3; 3]> = (0..mesh.indices.len() as u32).map(|i| mesh.triangle(i)).collect();
    let boxes: Vec<Aabb> = tris.iter().map(|t| aabb_of(*t)).collect();
    let bvh = build_cwbvh(&boxes, build_params(), &mut Duration::default());
    let triangles = bvh.primitive_indices.iter().map(|&i| tris[i as usize]).collect();
    let prim_ids = bvh.primitive_indices.clone();
    let bounds = boxes.iter().fold(Aabb::empty(), |acc, b| acc.union(b));
    (MeshBlas { bvh, triangles, prim_ids }, bounds)
}

impl ObvhsAccel {
    pub fn build(scene: &RenderScene, options: &AccelOptions) -> Self {
        let mut blases = Vec::with_capacity(scene.shapes.len());
        let mut bounds = Vec::with_capacity(scene.shapes.len());
        for shape in &scene.shapes {
            match &shape.geometry {
                Geometry::Triangles(mesh) => {
                    let (blas, aabb) = build_mesh_blas(mesh);
                    blases.push(Blas::Mesh(blas));
                    bounds.push(aabb);
                }
                Geometry::Sphere(s) => {
                    blases.push(Blas::Sphere(*s));
                    let r = Vec3::splat(s.radius);
                    bounds.push(aabb_of([s.center - r, s.center + r]));
                }
            }
        }
        let tlas = (!bounds.is_empty())
            .then(|| build_cwbvh(&bounds, build_params(), &mut Duration::default()));
        ObvhsAccel { blases, tlas, count_traversal: options.count_traversal }
    }

    fn node_ray(ray: &Ray, tmax: f32) -> BvhRay {
        let origin = ray.origin - ray.dir * NODE_RAY_BACKOFF;
        BvhRay::new(Vec3A::from(origin), Vec3A::from(ray.dir), 0.0, tmax + NODE_RAY_BACKOFF)
    }

    /// Closest hit within one mesh, narrowing `closest` (t, prim id, u, v).
    fn intersect_mesh<const COUNT: bool>(
        mesh: &MeshBlas,
        ray: &Ray,
        closest: &mut Option<(f32, u32, f32, f32)>,
        tmax: &mut f32,
        counters: &mut TraversalCounters,
        any_hit: bool,
    ) {
        let mut node_ray = Self::node_ray(ray, *tmax);
        let mut state = mesh.bvh.new_traversal(node_ray.direction);
        let mut node;
        'traversal: {
            traverse!(
                mesh.bvh,
                node,
                state,
                {
                    if COUNT {
                        counters.node_visits += 1;
                    }
                    node.intersect_ray(&node_ray, state.oct_inv4)
                },
                {
                    if COUNT {
                        counters.prim_tests += 1;
                    }
                    let index = state.primitive_id as usize;
                    let tri = &mesh.triangles[index];
                    if let Some((t, u, v)) =
                        intersect_triangle(ray.origin, ray.dir, ray.tmin, *tmax, tri)
                    {
                        *tmax = t;
                        node_ray.tmax = t + NODE_RAY_BACKOFF;
                        *closest = Some((t, mesh.prim_ids[index], u, v));
                        if any_hit {
                            break 'traversal;
                        }
                    }
                }
            );
        }
    }

    fn trace<const COUNT: bool>(
        &self,
        ray: &Ray,
        counters: &mut TraversalCounters,
        any_hit: bool,
    ) -> Option<Hit> {
        let tlas = self.tlas.as_ref()?;
        let mut tmax = ray.tmax;
        let mut best: Option<Hit> = None;
        let mut node_ray = Self::node_ray(ray, tmax);
        let mut state = tlas.new_traversal(node_ray.direction);
        let mut node;
        'traversal: {
            traverse!(
                tlas,
                node,
                state,
                {
                    if COUNT {
                        counters.node_visits += 1;
                    }
                    node.intersect_ray(&node_ray, state.oct_inv4)
                },
                {
                    let geom_id = tlas.primitive_indices[state.primitive_id as usize];
                    let mut closest = None;
                    match &self.blases[geom_id as usize] {
                        Blas::Mesh(mesh) => Self::intersect_mesh::<COUNT>(
                            mesh,
                            ray,
                            &mut closest,
                            &mut tmax,
                            counters,
                            any_hit,
                        ),
                        Blas::Sphere(s) => {
                            if COUNT {
                                counters.prim_tests += 1;
                            }
                            if let Some(t) = intersect_sphere(
                                ray.origin, ray.dir, ray.tmin, tmax, s.center, s.radius,
                            ) {
                                tmax = t;
                                closest = Some((t, 0, 0.0, 0.0));
                            }
                        }
                    }
                    if let Some((t, prim_id, u, v)) = closest {
                        node_ray.tmax = t + NODE_RAY_BACKOFF;
                        best = Some(Hit { t, geom_id, prim_id, u, v });
                        if any_hit {
                            break 'traversal;
                        }
                    }
                }
            );
        }
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

    fn observes(&self) -> Observes {
        Observes { node_visits: self.count_traversal, prim_tests: self.count_traversal }
    }
}
