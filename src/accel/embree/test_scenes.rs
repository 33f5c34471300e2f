//! Fixtures of the Embree unit tests: small scenes, random rays and the brute-force reference.

use crate::accel::AccelOptions;
use crate::camera::Camera;
use crate::intersect::{intersect_sphere, intersect_triangle};
use crate::ray::{Hit, Ray};
use crate::render_scene::{self, RenderScene, Sphere, TriangleMesh};
use crate::shading::material::Material;
use glam::Vec3;

pub(super) use crate::splitmix::SplitMix64 as Rng;

/// A named shape of a test scene: a baked instance of its own prototype.
#[derive(Clone)]
pub(super) struct Shape {
    name: String,
    geometry: render_scene::Geometry,
}

/// A scene of baked shapes (`RenderScene::from_baked_shapes`), named as given; every
/// instance uses material 0.
pub(super) fn render_scene(shapes: Vec<Shape>) -> RenderScene {
    let names: Vec<String> = shapes.iter().map(|s| s.name.clone()).collect();
    let baked = shapes.into_iter().map(|s| (s.geometry, 0)).collect();
    let mut scene =
        crate::compile::baked_scene(Camera::default(), baked, vec![Material::default()]);
    for (i, name) in names.into_iter().enumerate() {
        scene.prototypes[i].name.clone_from(&name);
        scene.instances[i].name = name;
    }
    scene
}

pub(super) fn shape(name: &str, geometry: render_scene::Geometry) -> Shape {
    Shape { geometry, name: name.to_string() }
}

pub(super) fn mesh(positions: Vec<Vec3>, indices: Vec<[u32; 3]>) -> render_scene::Geometry {
    render_scene::Geometry::Triangles(TriangleMesh::new(positions, indices, None, None))
}

pub(super) fn sphere(center: Vec3, radius: f32) -> render_scene::Geometry {
    render_scene::Geometry::Sphere(Sphere { center, radius })
}

/// Independent small triangles scattered in [-1, 1]^3.
pub(super) fn triangle_soup(rng: &mut Rng, count: usize) -> render_scene::Geometry {
    let mut positions = Vec::new();
    for _ in 0..count {
        let c = rng.vec3(-1.0, 1.0);
        positions.extend((0..3).map(|_| c + rng.vec3(-0.3, 0.3)));
    }
    let indices = (0..count as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    mesh(positions, indices)
}

/// A bumpy height field: triangles share edges, so some rays hit exactly between two.
pub(super) fn grid(n: u32) -> render_scene::Geometry {
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (2.0 * i as f32 / n as f32 - 1.0, 2.0 * j as f32 / n as f32 - 1.0);
            positions.push(Vec3::new(x, y, 0.3 + 0.15 * (3.0 * x).sin() * (2.0 * y).cos()));
        }
    }
    let v = |i: u32, j: u32| j * (n + 1) + i;
    let mut indices = Vec::new();
    for j in 0..n {
        for i in 0..n {
            indices.push([v(i, j), v(i + 1, j), v(i + 1, j + 1)]);
            indices.push([v(i, j), v(i + 1, j + 1), v(i, j + 1)]);
        }
    }
    mesh(positions, indices)
}

/// Meshes and spheres interleaved, so geometry ids of both kinds are exercised.
pub(super) fn random_scene() -> RenderScene {
    let mut rng = Rng(7);
    render_scene(vec![
        shape("soup", triangle_soup(&mut rng, 300)),
        shape("ball", sphere(Vec3::new(0.5, -0.4, 0.2), 0.5)),
        shape("terrain", grid(12)),
        shape("pebble", sphere(Vec3::new(-0.6, 0.5, -0.3), 0.35)),
        shape("specks", triangle_soup(&mut rng, 40)),
    ])
}

pub(super) fn random_rays(count: usize) -> Vec<Ray> {
    rays_through_boxes(99, count, 2.0, 1.0, false)
}

/// `count` rays from a cube of half-side `origin_half` towards one of half-side
/// `target_half`, some with a raised `tmin` or a finite `tmax`; `timed` rays also get
/// shutter times (every 8th exactly 0 or 1).
pub(super) fn rays_through_boxes(
    seed: u64,
    count: usize,
    origin_half: f32,
    target_half: f32,
    timed: bool,
) -> Vec<Ray> {
    let mut rng = Rng(seed);
    (0..count)
        .map(|k| {
            let origin = rng.vec3(-origin_half, origin_half);
            let target = rng.vec3(-target_half, target_half);
            let mut ray = Ray::new(origin, (target - origin) * rng.range(0.3, 3.0), f32::INFINITY);
            if timed {
                ray.time = rng.range(0.0, 1.0);
                if k % 8 == 0 {
                    ray.time = [0.0, 1.0][k / 8 % 2];
                }
            }
            if k % 4 == 1 {
                ray.tmin = rng.range(0.0, 0.5);
            }
            if k % 2 == 1 {
                ray.tmax = ray.tmin + rng.range(0.1, 2.0);
            }
            ray
        })
        .collect()
}

/// The reference: every primitive tested, closest hit kept (first one on exact ties). For
/// scenes of baked shapes only.
pub(super) fn brute_force(scene: &RenderScene, ray: &Ray) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for (g, instance) in scene.instances.iter().enumerate() {
        assert!(matches!(instance.placement, render_scene::Placement::Baked { .. }));
        let (o, d, tmin) = (ray.origin, ray.dir, ray.tmin);
        match &scene.prototype_of(g as u32).geometry {
            render_scene::Geometry::Triangles(m) => {
                for p in 0..m.indices.len() as u32 {
                    let tmax = best.map_or(ray.tmax, |h| h.t);
                    let hit = intersect_triangle(o, d, tmin, tmax, &m.triangle(p));
                    if let Some((t, u, v)) = hit.filter(|&(t, ..)| best.is_none_or(|h| t < h.t)) {
                        best = Some(Hit { t, geom_id: g as u32, prim_id: p, u, v });
                    }
                }
            }
            render_scene::Geometry::Sphere(sp) => {
                let tmax = best.map_or(ray.tmax, |h| h.t);
                let hit = intersect_sphere(o, d, tmin, tmax, sp.center, sp.radius);
                if let Some(t) = hit.filter(|&t| best.is_none_or(|h| t < h.t)) {
                    best = Some(Hit { t, geom_id: g as u32, prim_id: 0, u: 0.0, v: 0.0 });
                }
            }
            render_scene::Geometry::SdfGrid(_) => unreachable!("grids are never baked"),
        }
    }
    best
}

pub(super) fn is_sphere(scene: &RenderScene, hit: &Hit) -> bool {
    matches!(scene.prototype_of(hit.geom_id).geometry, render_scene::Geometry::Sphere(_))
}

pub(super) fn close(a: f32, b: f32) -> bool {
    (a - b).abs() <= 1e-4 * b.abs().max(1e-2)
}

/// A disagreement the two methods may legitimately have: a triangle hit within rounding of
/// an edge (the neighbour may claim it), two hits at the same distance, or a hit within
/// rounding of the ray's ends.
pub(super) fn is_graze(scene: &RenderScene, ray: &Ray, a: Option<Hit>, b: Option<Hit>) -> bool {
    let near_edge = |h: &Hit| !is_sphere(scene, h) && h.u.min(h.v).min(1.0 - h.u - h.v) < 1e-3;
    let near_end = |h: &Hit| close(h.t, ray.tmin) || close(h.t, ray.tmax);
    let same_t = matches!((a, b), (Some(a), Some(b)) if close(a.t, b.t));
    same_t || [a, b].iter().flatten().any(|h| near_edge(h) || near_end(h))
}

/// Both modes: normal (Embree's triangles) and counting (user-geometry triangles).
pub(super) const MODES: [AccelOptions; 2] = [
    AccelOptions { count_traversal: false, ..AccelOptions::DEFAULT },
    AccelOptions { count_traversal: true, ..AccelOptions::DEFAULT },
];
