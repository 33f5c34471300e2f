//! The Embree backend against a brute-force linear scan, plus bad input and error reporting.

use super::EmbreeAccel;
use super::device::Device;
use super::ffi;
use super::geometry_handle::GeometryHandle;
use super::scene::Scene;
use crate::accel::{self, Accel, AccelError, AccelOptions, BackendKind};
use crate::camera::Camera;
use crate::intersect::{intersect_sphere, intersect_triangle};
use crate::ray::{Hit, Ray};
use crate::render_scene::{self, RenderScene, Sphere, TriangleMesh};
use crate::shading::material::Material;
use crate::stats::TraversalCounters;
use glam::Vec3;
use std::sync::Arc;

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
    render_scene::Geometry::Triangles(TriangleMesh { positions, indices, normals: None, uvs: None })
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
const MODES: [AccelOptions; 2] = [
    AccelOptions { count_traversal: false, ..AccelOptions::DEFAULT },
    AccelOptions { count_traversal: true, ..AccelOptions::DEFAULT },
];

#[test]
fn closest_hits_match_brute_force() {
    for options in &MODES {
        closest_hits_match_brute_force_in(options);
    }
}

fn closest_hits_match_brute_force_in(options: &AccelOptions) {
    let scene = random_scene();
    let accel = EmbreeAccel::build(&scene, options).unwrap();
    let rays = random_rays(4000);
    let mut counters = TraversalCounters::default();
    let (mut hits, mut grazes, mut sphere_hits) = (0, 0, 0);
    for (k, ray) in rays.iter().enumerate() {
        let embree = accel.intersect(ray, &mut counters);
        let brute = brute_force(&scene, ray);
        match (embree, brute) {
            (Some(e), Some(b)) if (e.geom_id, e.prim_id) == (b.geom_id, b.prim_id) => {
                hits += 1;
                if is_sphere(&scene, &b) {
                    // Both call `intersect_sphere` with the same ray: identical bits.
                    assert_eq!(e.t.to_bits(), b.t.to_bits(), "ray {k}: sphere t {e:?} vs {b:?}");
                    sphere_hits += 1;
                } else if options.count_traversal {
                    // Counting mode runs `intersect_triangle` too: identical bits.
                    assert_eq!(e, b, "ray {k}");
                } else {
                    assert!(close(e.t, b.t), "ray {k}: t {e:?} vs {b:?}");
                    assert!((e.u - b.u).abs() < 1e-3 && (e.v - b.v).abs() < 1e-3, "ray {k}");
                }
            }
            (None, None) => {}
            (e, b) if is_graze(&scene, ray, e, b) => grazes += 1,
            (e, b) => panic!("ray {k} {ray:?}: embree {e:?}, brute force {b:?}"),
        }
    }
    assert!(hits > 1000 && sphere_hits > 100, "too few hits to mean anything: {hits}");
    assert!(grazes * 1000 < rays.len(), "{grazes} grazing disagreements");
}

#[test]
fn occlusion_matches_brute_force() {
    for options in &MODES {
        occlusion_matches_brute_force_in(options);
    }
}

fn occlusion_matches_brute_force_in(options: &AccelOptions) {
    let scene = random_scene();
    let accel = EmbreeAccel::build(&scene, options).unwrap();
    let rays = random_rays(4000);
    let mut counters = TraversalCounters::default();
    let (mut occluded, mut grazes) = (0, 0);
    for (k, ray) in rays.iter().enumerate() {
        let brute = brute_force(&scene, ray);
        let embree = accel.occluded(ray, &mut counters);
        occluded += embree as usize;
        if embree != brute.is_some() {
            let closest = accel.intersect(ray, &mut counters);
            assert!(
                is_graze(&scene, ray, closest, brute),
                "ray {k} {ray:?}: embree occluded = {embree}, brute force {brute:?}"
            );
            grazes += 1;
        }
    }
    assert!(occluded > 1000 && occluded < 3900, "{occluded} of 4000 occluded");
    assert!(grazes * 1000 < rays.len(), "{grazes} grazing disagreements");
}

#[test]
fn sphere_respects_ray_interval() {
    let scene = render_scene(vec![shape("ball", sphere(Vec3::new(0.0, 0.0, -5.0), 1.0))]);
    let accel = EmbreeAccel::build(&scene, &AccelOptions::default()).unwrap();
    let mut c = TraversalCounters::default();
    let mut ray = Ray::new(Vec3::ZERO, Vec3::NEG_Z, f32::INFINITY);
    assert_eq!(accel.intersect(&ray, &mut c).map(|h| h.t), Some(4.0));
    ray.tmin = 5.0; // past the near side: the far side is hit
    assert_eq!(accel.intersect(&ray, &mut c).map(|h| h.t), Some(6.0));
    ray.tmin = 0.0;
    ray.tmax = 3.5; // stops short of the sphere
    assert_eq!(accel.intersect(&ray, &mut c), None);
    assert!(!accel.occluded(&ray, &mut c));
    ray.tmax = 4.5;
    assert!(accel.occluded(&ray, &mut c));
}

#[test]
fn invalid_rays_miss_without_reaching_embree() {
    let scene =
        render_scene(vec![shape("ball", sphere(Vec3::ZERO, 1.0)), shape("terrain", grid(2))]);
    let accel = EmbreeAccel::build(&scene, &AccelOptions::default()).unwrap();
    let mut c = TraversalCounters::default();
    let good = Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::NEG_Z, f32::INFINITY);
    assert!(accel.intersect(&good, &mut c).is_some() && accel.occluded(&good, &mut c));
    let nan = f32::NAN;
    let bad = [
        Ray { origin: Vec3::new(nan, 0.0, 5.0), ..good },
        Ray { origin: Vec3::new(0.0, f32::INFINITY, 5.0), ..good },
        Ray { dir: Vec3::new(0.0, 0.0, nan), ..good },
        Ray { dir: Vec3::new(0.0, f32::NEG_INFINITY, -1.0), ..good },
        Ray { dir: Vec3::ZERO, ..good },
        Ray { tmin: -1.0, ..good },
        Ray { tmin: nan, ..good },
        Ray { tmax: nan, ..good },
        Ray { tmin: 2.0, tmax: 1.0, ..good },
        Ray { time: nan, ..good },
        // Finite, but beyond what Embree's assertion accepts.
        Ray { origin: Vec3::new(0.0, 0.0, 1e30), ..good },
        Ray { dir: Vec3::new(0.0, 0.0, -1e20), ..good },
    ];
    for ray in &bad {
        assert_eq!(accel.intersect(ray, &mut c), None, "{ray:?}");
        assert!(!accel.occluded(ray, &mut c), "{ray:?}");
    }
}

#[test]
fn empty_scene_has_no_hits() {
    let accel = EmbreeAccel::build(&render_scene(Vec::new()), &AccelOptions::default()).unwrap();
    let mut c = TraversalCounters::default();
    for ray in random_rays(100) {
        assert_eq!(accel.intersect(&ray, &mut c), None);
        assert!(!accel.occluded(&ray, &mut c));
    }
}

fn build_error(shapes: Vec<Shape>) -> String {
    match EmbreeAccel::build(&render_scene(shapes), &AccelOptions::default()) {
        Err(AccelError::Embree(msg)) => msg,
        Err(e) => panic!("unexpected error {e}"),
        Ok(_) => panic!("bad input was accepted"),
    }
}

#[test]
fn bad_meshes_are_errors_naming_the_shape() {
    let tri = vec![Vec3::ZERO, Vec3::X, Vec3::Y];
    let ok = shape("fine", mesh(tri.clone(), vec![[0, 1, 2]]));
    let msg = build_error(vec![ok.clone(), shape("broken", mesh(tri.clone(), vec![[0, 1, 3]]))]);
    assert!(msg.contains("instance 1 ('broken')") && msg.contains("vertex 3"), "{msg}");
    let msg = build_error(vec![shape("hollow", mesh(tri.clone(), Vec::new()))]);
    assert!(msg.contains("'hollow'") && msg.contains("no triangles"), "{msg}");
    let nan_vertex = vec![Vec3::ZERO, Vec3::X, Vec3::new(0.0, f32::NAN, 0.0)];
    let msg = build_error(vec![shape("nan", mesh(nan_vertex, vec![[0, 1, 2]]))]);
    assert!(msg.contains("'nan'") && msg.contains("not finite"), "{msg}");
    let msg = build_error(vec![ok, shape("void", sphere(Vec3::ZERO, f32::NAN))]);
    assert!(msg.contains("'void'"), "{msg}");
}

#[test]
fn embree_errors_arrive_through_the_callback() {
    let device = Device::new("").unwrap();
    device.check().unwrap();
    // SAFETY: a live device; the geometry is released below. A 13-byte stride is not a
    // multiple of 4, which Embree reports as an error (and allocates nothing).
    unsafe {
        let geometry = ffi::rtcNewGeometry(device.handle(), ffi::RTCGeometryType::TRIANGLE);
        let buffer = ffi::rtcSetNewGeometryBuffer(
            geometry,
            ffi::RTCBufferType::VERTEX,
            0,
            ffi::RTCFormat::FLOAT3,
            13,
            3,
        );
        assert!(buffer.is_null());
        ffi::rtcReleaseGeometry(geometry);
    }
    match device.check() {
        Err(AccelError::Embree(msg)) => assert!(!msg.is_empty()),
        other => panic!("expected an Embree error, got {other:?}"),
    }
    device.check().expect("checking clears the error");
}

#[test]
fn attaching_two_geometries_with_one_id_is_an_error() {
    let device = Arc::new(Device::new("").unwrap());
    let mut scene =
        Scene::new(&device, ffi::RTCBuildQuality::MEDIUM, ffi::RTCSceneFlags::ROBUST).unwrap();
    let tri = [Vec3::ZERO, Vec3::X, Vec3::Y];
    scene.attach(GeometryHandle::triangles(&device, &tri, &[[0, 1, 2]]).unwrap(), 0).unwrap();
    let second = GeometryHandle::triangles(&device, &tri, &[[0, 1, 2]]).unwrap();
    assert!(matches!(scene.attach(second, 0), Err(AccelError::Embree(_))));
}

#[test]
fn device_config_with_nul_is_an_error() {
    assert!(matches!(Device::new("threads=1\0"), Err(AccelError::Embree(_))));
}

#[test]
fn queries_from_many_threads_through_the_trait() {
    let scene = random_scene();
    let accel = accel::build(BackendKind::Embree, &scene, &AccelOptions::default()).unwrap();
    assert_eq!(accel.name(), "embree");
    assert_eq!(accel.observes(), crate::accel::Observes::default());
    let rays = random_rays(2000);
    let mut c = TraversalCounters::default();
    let serial: Vec<_> = rays.iter().map(|r| accel.intersect(r, &mut c)).collect();
    std::thread::scope(|s| {
        let workers: Vec<_> = rays
            .chunks(500)
            .map(|chunk| {
                let accel = &accel;
                s.spawn(move || {
                    let mut c = TraversalCounters::default();
                    chunk.iter().map(|r| accel.intersect(r, &mut c)).collect::<Vec<_>>()
                })
            })
            .collect();
        let parallel: Vec<_> = workers.into_iter().flat_map(|w| w.join().unwrap()).collect();
        assert_eq!(parallel, serial);
    });
}
