//! Pure-Rust backend on the obvhs crate: every baked triangle mesh (already in render space)
//! in one CWBVH, as Embree's top scene holds them; one CWBVH per other prototype (bottom
//! level) and one over the other instances' bounds (top level: spheres, transformed and
//! moving instances). Traversed with obvhs's `traverse!` macro so node visits and primitive
//! tests can be counted exactly. Transformed instances get the ray in object space; moving
//! instances have bounds over their whole motion at the top level only, and the exact
//! transform at the ray's time.
//!
//! obvhs's node test clamps the entry distance to 1e-4 (`node::EPSILON`), which would cull
//! boxes the ray enters and leaves within 1e-4 of its origin — exactly where a spawned ray
//! meets the neighbouring wall in a corner. Node tests therefore use the ray with its origin
//! moved back by `NODE_RAY_BACKOFF` (in units of t); primitive tests use the real ray.
//!
//! Triangles are tested with `crate::geometry::intersect_triangle` (the hits are exactly
//! its results), after a cheap conservative test ([`EdgeTest`]) that rejects most of the
//! triangles a ray passes outside of without its FMA-based edge functions.

use crate::accel::{Accel, AccelOptions, BuildQuality, Hit, Observes, Ray};
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
    /// Geometry id (instance index; only meaningful in the baked BVH, see
    /// [`ObvhsAccel::baked`]) and original triangle index of each entry of `triangles`.
    ids: Vec<(u32, u32)>,
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
    /// Per prototype: its BVH, built only for prototypes that some non-baked instance
    /// places (baked meshes live in `baked`).
    blases: Vec<Option<Blas>>,
    instances: Vec<BlasInstance>,
    /// Every baked triangle mesh (already in render space) in one BVH, as Embree's top
    /// scene holds them: a ray tests all of them in one traversal, with no top level.
    baked: Option<MeshBlas>,
    /// Top level over the other instances' bounds (spheres, transformed and moving
    /// instances); `None` if there are none.
    tlas: Option<CwBvh>,
    /// Instance (geometry id) of each primitive of `tlas`.
    tlas_instances: Vec<u32>,
    count_traversal: bool,
}

fn aabb_of(points: impl IntoIterator<Item = Vec3>) -> Aabb {
    let mut aabb = Aabb::empty();
    for p in points {
        aabb.extend(Vec3A::from(p));
    }
    aabb
}

fn build_params(quality: BuildQuality) -> BvhBuildParams {
    match quality {
        BuildQuality::Low => BvhBuildParams::fastest_build(),
        BuildQuality::Medium => BvhBuildParams::medium_build(),
        BuildQuality::High => BvhBuildParams::slow_build(),
    }
}

/// The per-ray part of `geometry::intersect_triangle` (Woop et al.'s permutation, with the
/// axis the direction is largest along, `KZ`, last, and shear), and a conservative version
/// of its edge test.
///
/// `intersect_triangle` returns `None` whenever its three edge functions (computed with FMA,
/// falling back to f64 for zeros) have mixed signs. Each of those is a·b − c·d of the same
/// sheared vertex coordinates computed here (same operations, so the same bits), and its
/// sign is always the sign of the exact a·b − c·d (Kahan's FMA form is exact for a zero and
/// within 2 ulps otherwise; the f64 fallback rounds once). Here a·b − c·d is computed in
/// plain f32 with an error bound: where the estimate exceeds its bound its sign is the exact
/// sign, so two such estimates of opposite signs prove the exact test returns `None`.
/// Only then does [`EdgeTest::may_hit`] say no; `intersect_triangle` decides the rest.
struct EdgeTest<const KZ: usize> {
    origin: Vec3,
    shear: (f32, f32),
}

/// `intersect_triangle`'s `permute` for `dir.abs().max_position() == KZ`.
#[inline(always)]
fn permute<const KZ: usize>(v: Vec3) -> Vec3 {
    match KZ {
        0 => Vec3::new(v.y, v.z, v.x),
        1 => Vec3::new(v.z, v.x, v.y),
        _ => Vec3::new(v.x, v.y, v.z),
    }
}

impl<const KZ: usize> EdgeTest<KZ> {
    /// As `intersect_triangle` sets up for `dir`, whose largest component is `KZ`.
    #[inline(always)]
    fn new(origin: Vec3, dir: Vec3) -> Self {
        let d = permute::<KZ>(dir);
        EdgeTest { origin, shear: (-d.x / d.z, -d.y / d.z) }
    }

    /// False only if `intersect_triangle(origin, dir, .., tri)` certainly returns `None`.
    #[inline(always)]
    fn may_hit(&self, tri: &[Vec3; 3]) -> bool {
        let (sx, sy) = self.shear;
        // `permute(v - origin)`, then `p.x += sx * p.z; p.y += sy * p.z`, as there.
        let sheared = |v: Vec3| {
            let p = permute::<KZ>(v - self.origin);
            (p.x + sx * p.z, p.y + sy * p.z)
        };
        let (p0, p1, p2) = (sheared(tri[0]), sheared(tri[1]), sheared(tri[2]));
        // Sign of a·b − c·d: 1 or -1 where certain, 0 where not.
        let sign = |a: f32, b: f32, c: f32, d: f32| {
            let (ab, cd) = (a * b, c * d);
            let estimate = ab - cd;
            // Two products and a difference, each within half an ulp: 4 ε is twice the
            // bound; the absolute term covers subnormal products.
            let bound = (ab.abs() + cd.abs()) * (4.0 * f32::EPSILON) + 1e-36;
            // NaN and infinities compare false both ways: left to the exact test.
            (estimate > bound, estimate < -bound)
        };
        let e0 = sign(p1.0, p2.1, p1.1, p2.0);
        let e1 = sign(p2.0, p0.1, p2.1, p0.0);
        let e2 = sign(p0.0, p1.1, p0.1, p1.0);
        let positive = e0.0 | e1.0 | e2.0;
        let negative = e0.1 | e1.1 | e2.1;
        !(negative & positive)
    }

    /// False only if `intersect_triangle(origin, dir, tmin, tmax, tri)` certainly returns
    /// `None` because its `t` lies outside `[tmin, tmax]` (or it has no `t`): computes `t`
    /// exactly as it does (same operations, same bits) and applies its own test.
    #[inline(always)]
    fn in_range(&self, dir: Vec3, tmin: f32, tmax: f32, tri: &[Vec3; 3]) -> bool {
        let normal = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
        let denom = dir.dot(normal);
        let t = (tri[0] - self.origin).dot(normal) / denom;
        // `intersect_triangle` refuses a zero or non-finite `denom` too; the `t` this gives
        // then is NaN or infinite, or is refused by the exact test anyway.
        t > 0.0 && t >= tmin && t <= tmax
    }
}

/// A BVH over `triangles` (each with its geometry id and triangle index).
fn build_mesh_blas(triangles: Vec<([Vec3; 3], (u32, u32))>, quality: BuildQuality) -> MeshBlas {
    let boxes: Vec<Aabb> = triangles.iter().map(|(t, _)| aabb_of(*t)).collect();
    let bvh = build_cwbvh(&boxes, build_params(quality), &mut Duration::default());
    let (triangles, ids) = bvh.primitive_indices.iter().map(|&i| triangles[i as usize]).unzip();
    MeshBlas { bvh, triangles, ids }
}

fn mesh_triangles(
    mesh: &TriangleMesh,
    geom_id: u32,
) -> impl Iterator<Item = ([Vec3; 3], (u32, u32))> {
    (0..mesh.indices.len() as u32).map(move |i| (mesh.triangle(i), (geom_id, i)))
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
                    });
                    bounds.push(aabb);
                    tlas_instances.push(index as u32);
                }
            }
        }
        let baked =
            (!baked_triangles.is_empty()).then(|| build_mesh_blas(baked_triangles, quality));
        let tlas = (!bounds.is_empty())
            .then(|| build_cwbvh(&bounds, build_params(quality), &mut Duration::default()));
        ObvhsAccel {
            blases,
            instances,
            baked,
            tlas,
            tlas_instances,
            count_traversal: options.count_traversal,
        }
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
    ) -> Option<(f32, (u32, u32), f32, f32)> {
        // One traversal per permutation of the triangle test, so it is known at compile time.
        match dir.abs().max_position() {
            0 => Self::intersect_mesh_axes::<COUNT, 0>(
                mesh, origin, dir, tmin, tmax, counters, any_hit,
            ),
            1 => Self::intersect_mesh_axes::<COUNT, 1>(
                mesh, origin, dir, tmin, tmax, counters, any_hit,
            ),
            _ => Self::intersect_mesh_axes::<COUNT, 2>(
                mesh, origin, dir, tmin, tmax, counters, any_hit,
            ),
        }
    }

    /// `intersect_mesh` for a ray whose direction is largest along axis `KZ`.
    #[allow(clippy::too_many_arguments)]
    fn intersect_mesh_axes<const COUNT: bool, const KZ: usize>(
        mesh: &MeshBlas,
        origin: Vec3,
        dir: Vec3,
        tmin: f32,
        tmax: &mut f32,
        counters: &mut TraversalCounters,
        any_hit: bool,
    ) -> Option<(f32, (u32, u32), f32, f32)> {
        let mut closest = None;
        let edges = EdgeTest::<KZ>::new(origin, dir);
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
                    let tri = &mesh.triangles[index];
                    let candidate = edges.may_hit(tri) && edges.in_range(dir, tmin, *tmax, tri);
                    if let Some((t, u, v)) = candidate
                        .then(|| intersect_triangle(origin, dir, tmin, *tmax, tri))
                        .flatten()
                    {
                        *tmax = t;
                        node_ray.tmax = t + NODE_RAY_BACKOFF;
                        closest = Some((t, mesh.ids[index], u, v));
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
            Some(Blas::Mesh(mesh)) => {
                Self::intersect_mesh::<COUNT>(mesh, origin, dir, ray.tmin, tmax, counters, any_hit)
                    .map(|(t, (_, prim_id), u, v)| (t, prim_id, u, v))
            }
            Some(Blas::Sphere(s)) => {
                if COUNT {
                    counters.prim_tests += 1;
                }
                let t = intersect_sphere(origin, dir, ray.tmin, *tmax, s.center, s.radius)?;
                *tmax = t;
                Some((t, 0, 0.0, 0.0))
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
            let hit = Self::intersect_mesh::<COUNT>(
                baked, ray.origin, ray.dir, ray.tmin, &mut tmax, counters, any_hit,
            );
            if let Some((t, (geom_id, prim_id), u, v)) = hit {
                best = Some(Hit { t, geom_id, prim_id, u, v });
                if any_hit {
                    return best;
                }
            }
        }
        let Some(tlas) = &self.tlas else { return best };
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
                    let tlas_index = tlas.primitive_indices[state.primitive_id as usize];
                    let geom_id = self.tlas_instances[tlas_index as usize];
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

#[cfg(test)]
mod tests {
    use super::*;

    /// splitmix64 over a counter.
    struct Rng(u64);

    impl Rng {
        fn unit(&mut self) -> f32 {
            self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
        }

        fn vec3(&mut self, scale: f32) -> Vec3 {
            Vec3::new(self.unit() - 0.5, self.unit() - 0.5, self.unit() - 0.5) * scale
        }
    }

    fn edge_test(origin: Vec3, dir: Vec3) -> impl Fn(&[Vec3; 3], f32, f32) -> bool {
        let kz = dir.abs().max_position();
        let (e0, e1, e2) = (
            EdgeTest::<0>::new(origin, dir),
            EdgeTest::<1>::new(origin, dir),
            EdgeTest::<2>::new(origin, dir),
        );
        move |tri: &[Vec3; 3], tmin: f32, tmax: f32| match kz {
            0 => e0.may_hit(tri) && e0.in_range(dir, tmin, tmax, tri),
            1 => e1.may_hit(tri) && e1.in_range(dir, tmin, tmax, tri),
            _ => e2.may_hit(tri) && e2.in_range(dir, tmin, tmax, tri),
        }
    }

    /// The pre-tests never reject a triangle `intersect_triangle` hits: on random rays, on
    /// rays through vertices, edge points and shared edges, axis-aligned rays, and at scales
    /// from 1e-6 to 1e6; and they reject most misses.
    #[test]
    fn pre_tests_only_reject_what_the_exact_test_misses() {
        let mut rng = Rng(5);
        let (mut hits, mut misses, mut rejected) = (0, 0, 0);
        for k in 0..200_000 {
            let scale = [1e-6, 1e-3, 1.0, 1e3, 1e6][k % 5];
            let tri = [rng.vec3(scale), rng.vec3(scale), rng.vec3(scale)];
            let origin = rng.vec3(4.0 * scale) + Vec3::splat(scale * [0.0, 1e3][k / 5 % 2]);
            // Aim at a vertex, an edge point, the centre, or anywhere.
            let (a, b) = (rng.unit(), rng.unit());
            let target = match k / 10 % 4 {
                0 => tri[k % 3],
                1 => tri[k % 3] + (tri[(k + 1) % 3] - tri[k % 3]) * a,
                2 => (tri[0] + tri[1] + tri[2]) / 3.0,
                _ => tri[0] + (tri[1] - tri[0]) * a + (tri[2] - tri[0]) * b,
            };
            let mut dir = target - origin;
            if k % 7 == 0 {
                // Axis-aligned: ties in the permutation, zero shear.
                let axis = dir.abs().max_position();
                dir = Vec3::ZERO;
                dir[axis] = 1.0;
            }
            if dir == Vec3::ZERO || !dir.is_finite() {
                continue;
            }
            let tmax = if k % 3 == 0 { f32::INFINITY } else { rng.unit() * 2.0 };
            let tmin = if k % 4 == 0 { rng.unit() * 0.5 } else { 0.0 };
            let exact = intersect_triangle(origin, dir, tmin, tmax, &tri);
            let may_hit = edge_test(origin, dir);
            let candidate = may_hit(&tri, tmin, tmax);
            match exact {
                Some(_) => {
                    hits += 1;
                    assert!(candidate, "ray {k}: {origin} {dir} [{tmin}, {tmax}] {tri:?}");
                }
                None => {
                    misses += 1;
                    rejected += usize::from(!candidate);
                }
            }
        }
        println!("{hits} hits, {misses} misses, {rejected} rejected by the pre-tests");
        assert!(hits > 20_000 && rejected * 10 > misses * 8, "{hits} {misses} {rejected}");
    }
}
