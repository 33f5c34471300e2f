//! Pure-Rust backend on the obvhs crate: one CWBVH per prototype (bottom level) and one CWBVH
//! over the instances' bounds (top level), traversed with obvhs's `traverse!` macro so node
//! visits and primitive tests can be counted exactly. Transformed instances get the ray in
//! object space; moving instances have bounds over their whole motion at the top level only,
//! and the exact transform at the ray's time.
//!
//! obvhs's node test clamps the entry distance to 1e-4 (`node::EPSILON`), which would cull
//! boxes the ray enters and leaves within 1e-4 of its origin — exactly where a spawned ray
//! meets the neighbouring wall in a corner. Node tests therefore use the ray with its origin
//! moved back by `NODE_RAY_BACKOFF` (in units of t); primitive tests use the real ray.

use crate::accel::{Accel, AccelOptions, Hit, Observes, Ray};
use crate::geometry::{intersect_sphere, intersect_triangle};
use crate::render_scene::{
    Geometry, Placement, RenderScene, Sphere, TriangleMesh, Trs, transformed_bounds,
};
use crate::stats::TraversalCounters;
use glam::{Affine3A, UVec2, Vec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::builder::build_cwbvh;
use obvhs::ray::Ray as BvhRay;
use obvhs::{BvhBuildParams, traverse};
use std::time::Duration;

/// Larger than obvhs's internal 1e-4 node epsilon, with margin for rounding.
const NODE_RAY_BACKOFF: f32 = 1e-3;

/// Time samples used to bound a moving instance (plus a margin for rotation in between).
const MOTION_BOUND_STEPS: usize = 32;

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

pub struct ObvhsAccel {
    blases: Vec<Blas>,
    instances: Vec<BlasInstance>,
    /// Top level over instance bounds; `None` for an empty scene.
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

fn build_mesh_blas(mesh: &TriangleMesh) -> MeshBlas {
    let tris: Vec<[Vec3; 3]> = (0..mesh.indices.len() as u32).map(|i| mesh.triangle(i)).collect();
    let boxes: Vec<Aabb> = tris.iter().map(|t| aabb_of(*t)).collect();
    let bvh = build_cwbvh(&boxes, build_params(), &mut Duration::default());
    let triangles = bvh.primitive_indices.iter().map(|&i| tris[i as usize]).collect();
    let prim_ids = bvh.primitive_indices.clone();
    MeshBlas { bvh, triangles, prim_ids }
}

/// Bounds of a moving instance over the whole shutter interval: the box at many times,
/// grown by how far a rotating corner can bulge between two samples.
fn motion_bounds(start: &Trs, end: &Trs, lo: Vec3, hi: Vec3) -> Aabb {
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

impl ObvhsAccel {
    pub fn build(scene: &RenderScene, options: &AccelOptions) -> Self {
        let blases: Vec<Blas> = scene
            .prototypes
            .iter()
            .map(|p| match &p.geometry {
                Geometry::Triangles(mesh) => Blas::Mesh(build_mesh_blas(mesh)),
                Geometry::Sphere(s) => Blas::Sphere(*s),
            })
            .collect();
        let mut instances = Vec::with_capacity(scene.instances.len());
        let mut bounds = Vec::with_capacity(scene.instances.len());
        for instance in &scene.instances {
            let (lo, hi) = scene.prototypes[instance.prototype as usize].geometry.bounds();
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
            bounds.push(aabb);
        }
        let tlas = (!bounds.is_empty())
            .then(|| build_cwbvh(&bounds, build_params(), &mut Duration::default()));
        ObvhsAccel { blases, instances, tlas, count_traversal: options.count_traversal }
    }

    fn node_ray(origin: Vec3, dir: Vec3, tmax: f32) -> BvhRay {
        let origin = origin - dir * NODE_RAY_BACKOFF;
        BvhRay::new(Vec3A::from(origin), Vec3A::from(dir), 0.0, tmax + NODE_RAY_BACKOFF)
    }

    /// Closest hit within one mesh for the ray (`origin`, `dir`), narrowing `tmax`.
    #[allow(clippy::too_many_arguments)]
    fn intersect_mesh<const COUNT: bool>(
        mesh: &MeshBlas,
        origin: Vec3,
        dir: Vec3,
        tmin: f32,
        tmax: &mut f32,
        counters: &mut TraversalCounters,
        any_hit: bool,
    ) -> Option<(f32, u32, f32, f32)> {
        let mut closest = None;
        let mut node_ray = Self::node_ray(origin, dir, *tmax);
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
                    if let Some((t, u, v)) =
                        intersect_triangle(origin, dir, tmin, *tmax, &mesh.triangles[index])
                    {
                        *tmax = t;
                        node_ray.tmax = t + NODE_RAY_BACKOFF;
                        closest = Some((t, mesh.prim_ids[index], u, v));
                        if any_hit {
                            break 'traversal;
                        }
                    }
                }
            );
        }
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
            Blas::Mesh(mesh) => {
                Self::intersect_mesh::<COUNT>(mesh, origin, dir, ray.tmin, tmax, counters, any_hit)
            }
            Blas::Sphere(s) => {
                if COUNT {
                    counters.prim_tests += 1;
                }
                let t = intersect_sphere(origin, dir, ray.tmin, *tmax, s.center, s.radius)?;
                *tmax = t;
                Some((t, 0, 0.0, 0.0))
            }
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
        let mut node_ray = Self::node_ray(ray.origin, ray.dir, tmax);
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
                    let instance = &self.instances[geom_id as usize];
                    if let Some((t, prim_id, u, v)) = self
                        .intersect_instance::<COUNT>(instance, ray, &mut tmax, counters, any_hit)
                    {
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
