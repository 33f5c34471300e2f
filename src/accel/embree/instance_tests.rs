//! Instancing and motion blur: Embree against the obvhs backend (the reference semantics) on
//! shared, non-uniformly scaled, rotated and moving instances; Embree's interpolation of
//! moving transforms against `Trs::lerp`; what a static scene pays for motion support; and
//! the memory an extra instance costs.

use super::EmbreeAccel;
use super::device::Device;
use super::ffi;
use super::geometry_handle::GeometryHandle;
use super::scene::Scene;
use super::test_scenes::{Rng, grid, mesh, rays_through_boxes, shape, sphere, triangle_soup};
use crate::accel::{Accel, AccelError, AccelOptions};
use crate::ray::{Hit, Ray};
use crate::render_scene::{self, Instance, Placement, Prototype, RenderScene, Trs};
use crate::stats::TraversalCounters;
use glam::{Affine3A, Quat, Vec3};
use std::sync::Arc;

const NORMAL: AccelOptions = AccelOptions { count_traversal: false, ..AccelOptions::DEFAULT };
const COUNTING: AccelOptions = AccelOptions { count_traversal: true, ..AccelOptions::DEFAULT };

/// Adds a prototype; returns its index.
fn add_prototype(scene: &mut RenderScene, name: &str, geometry: render_scene::Geometry) -> u32 {
    scene.prototypes.push(Prototype { geometry, name: name.to_string() });
    (scene.prototypes.len() - 1) as u32
}

fn add_instance(scene: &mut RenderScene, prototype: u32, placement: Placement) -> u32 {
    let index = scene.instances.len();
    scene.instances.push(Instance {
        prototype,
        material: 0,
        placement,
        name: format!("instance {index}"),
    });
    index as u32
}

fn static_placement(trs: &Trs) -> Placement {
    let render_from_object = trs.to_affine();
    Placement::Static { render_from_object, object_from_render: render_from_object.inverse() }
}

fn random_rotation(rng: &mut Rng, max_angle: f32) -> Quat {
    Quat::from_axis_angle(rng.vec3(-1.0, 1.0).normalize_or(Vec3::X), rng.range(0.0, max_angle))
}

/// A rotated, non-uniformly scaled placement inside `[-spread, spread]^3`.
fn random_trs(rng: &mut Rng, spread: f32) -> Trs {
    Trs {
        translation: rng.vec3(-spread, spread),
        rotation: random_rotation(rng, std::f32::consts::TAU),
        scale: Vec3::new(rng.range(0.4, 1.6), rng.range(0.4, 1.6), rng.range(0.4, 1.6)),
    }
}

/// `start` moved, turned (up to ~2.5 rad) and rescaled.
fn random_motion(rng: &mut Rng, start: Trs) -> (Trs, Trs) {
    let end = Trs {
        translation: start.translation + rng.vec3(-1.5, 1.5),
        rotation: (random_rotation(rng, 2.5) * start.rotation).normalize(),
        scale: start.scale * Vec3::new(rng.range(0.6, 1.4), rng.range(0.6, 1.4), 1.2),
    };
    (start, end)
}

/// Which kind of instance a test scene's instance is, for per-kind hit counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Baked,
    SharedMesh,
    Ellipsoid,
    Moving,
}

/// (a) a 300-triangle prototype shared by 50 static instances with rotations and non-uniform
/// scales, (b) an ellipsoid (a sphere prototype scaled non-uniformly), (c) moving meshes and
/// a moving ellipsoid, plus baked shapes so both kinds of geometry id mix in one scene.
fn instanced_scene(moving: bool) -> (RenderScene, Vec<Kind>) {
    let mut rng = Rng(2024);
    let mut scene = super::test_scenes::render_scene(vec![
        shape("baked soup", triangle_soup(&mut rng, 100)),
        shape("baked ball", sphere(Vec3::new(1.0, -2.0, 0.5), 0.7)),
    ]);
    let mut kinds = vec![Kind::Baked; 2];
    let shared = add_prototype(&mut scene, "shared", triangle_soup(&mut rng, 300));
    for _ in 0..50 {
        let trs = random_trs(&mut rng, 5.0);
        add_instance(&mut scene, shared, static_placement(&trs));
        kinds.push(Kind::SharedMesh);
    }
    let ball = add_prototype(&mut scene, "ball", sphere(Vec3::new(0.2, -0.1, 0.3), 0.8));
    let ellipsoid = Trs {
        translation: Vec3::new(-1.0, 1.5, 0.5),
        rotation: Quat::from_rotation_z(0.6) * Quat::from_rotation_x(0.3),
        scale: Vec3::new(2.5, 0.6, 1.3),
    };
    add_instance(&mut scene, ball, static_placement(&ellipsoid));
    kinds.push(Kind::Ellipsoid);
    if moving {
        let terrain = add_prototype(&mut scene, "terrain", grid(8));
        for _ in 0..6 {
            let start = random_trs(&mut rng, 4.0);
            let (start, end) = random_motion(&mut rng, start);
            add_instance(&mut scene, terrain, Placement::Moving { start, end });
            kinds.push(Kind::Moving);
        }
        let start = random_trs(&mut rng, 3.0);
        let (start, end) = random_motion(&mut rng, start);
        add_instance(&mut scene, ball, Placement::Moving { start, end });
        kinds.push(Kind::Moving);
    }
    (scene, kinds)
}

/// Random rays through the scene's region with random shutter times, some with a `tmin`
/// or a finite `tmax`.
fn instanced_rays(count: usize) -> Vec<Ray> {
    rays_through_boxes(31, count, 9.0, 5.0, true)
}

#[test]
fn motion_geometries_only_for_moving_instances() {
    let baked = super::test_scenes::random_scene();
    assert_eq!(EmbreeAccel::build(&baked, &NORMAL).unwrap().motion_geometries(), 0);
    let (static_scene, _) = instanced_scene(false);
    for options in [NORMAL, COUNTING] {
        let accel = EmbreeAccel::build(&static_scene, &options).unwrap();
        assert_eq!(accel.motion_geometries(), 0, "static instances need no time steps");
    }
    let mut one_moving = static_scene.clone();
    let ball = one_moving.instances.last().unwrap().prototype;
    let start = Trs { translation: Vec3::ZERO, rotation: Quat::IDENTITY, scale: Vec3::ONE };
    let end = Trs { translation: Vec3::X, ..start };
    add_instance(&mut one_moving, ball, Placement::Moving { start, end });
    assert_eq!(EmbreeAccel::build(&one_moving, &NORMAL).unwrap().motion_geometries(), 1);
    let (moving, kinds) = instanced_scene(true);
    let expected = kinds.iter().filter(|&&k| k == Kind::Moving).count();
    assert_eq!(EmbreeAccel::build(&moving, &NORMAL).unwrap().motion_geometries(), expected);
}

/// The transform Embree reports for a geometry at `time`, as an affine map.
fn embree_transform(geometry: &GeometryHandle, time: f32) -> Affine3A {
    let mut m = [0.0f32; 12];
    // SAFETY: a live instance geometry; Embree writes 12 floats (3x4, column major).
    unsafe {
        ffi::rtcGetGeometryTransform(
            geometry.handle(),
            time,
            ffi::RTCFormat::FLOAT3X4_COLUMN_MAJOR,
            m.as_mut_ptr().cast(),
        );
    }
    Affine3A::from_cols_array(&m)
}

fn max_difference(a: &Affine3A, b: &Affine3A) -> f32 {
    let (a, b) = (a.to_cols_array(), b.to_cols_array());
    a.iter().zip(&b).map(|(x, y)| (x - y).abs()).fold(0.0, f32::max)
}

/// Embree's interpolation of a quaternion-decomposed motion is `Trs::lerp`'s: lerp of
/// translation and scale, shortest-arc slerp of the rotation (to Embree's approximate
/// `acos`/`sincos`). Also: the static transform reads back exactly.
#[test]
fn embree_interpolates_motion_as_trs_lerp() {
    let device = Arc::new(Device::new("").unwrap());
    let mut child =
        Scene::new(&device, ffi::RTCBuildQuality::MEDIUM, ffi::RTCSceneFlags::ROBUST).unwrap();
    let tri = [Vec3::ZERO, Vec3::X, Vec3::Y];
    child.attach(GeometryHandle::triangles(&device, &tri, &[[0, 1, 2]]).unwrap(), 0).unwrap();
    let child = Arc::new(child.commit().unwrap());
    let mut rng = Rng(77);
    let mut worst = 0.0f32;
    for case in 0..200 {
        let start = random_trs(&mut rng, 5.0);
        let (start, mut end) = random_motion(&mut rng, start);
        if case % 4 == 0 {
            // The same rotation with the opposite sign: both must take the short arc.
            end.rotation = -end.rotation;
        }
        if case % 4 == 1 {
            // Turns of almost 180 degrees and tiny turns (Embree lerps below ~1.8 degrees).
            let angle = if case % 8 == 1 { 3.1 } else { 0.01 };
            end.rotation = (Quat::from_axis_angle(Vec3::Z, angle) * start.rotation).normalize();
        }
        let geometry = GeometryHandle::moving_instance(&device, &child, &start, &end).unwrap();
        assert_eq!(geometry.time_steps(), 2);
        for step in 0..=16 {
            let time = step as f32 / 16.0;
            let expected = start.lerp(&end, time).to_affine();
            let got = embree_transform(&geometry, time);
            let scale = expected.to_cols_array().iter().fold(1.0f32, |m, x| m.max(x.abs()));
            let difference = max_difference(&got, &expected) / scale;
            worst = worst.max(difference);
            assert!(difference < 2e-5, "case {case}, time {time}: {got:?} vs {expected:?}");
        }
        let fixed = start.to_affine();
        let geometry = GeometryHandle::static_instance(&device, &child, &fixed).unwrap();
        assert_eq!(geometry.time_steps(), 1);
        assert_eq!(embree_transform(&geometry, 0.5), fixed);
    }
    println!("largest difference from Trs::lerp, relative to the largest entry: {worst:e}");
}

/// A single-instance scene of `geometry` placed by `placement`.
fn one_instance(geometry: render_scene::Geometry, placement: Placement) -> RenderScene {
    let mut scene = super::test_scenes::render_scene(Vec::new());
    let p = add_prototype(&mut scene, "thing", geometry);
    add_instance(&mut scene, p, placement);
    scene
}

/// Embree gives the sphere callbacks the ray in object space, direction not renormalised,
/// so `t` is the render-space ray's: exact values on an ellipsoid.
#[test]
fn ellipsoid_hits_are_in_render_space_t() {
    let trs = Trs {
        translation: Vec3::new(0.0, 0.0, -10.0),
        rotation: Quat::IDENTITY,
        scale: Vec3::new(4.0, 2.0, 1.0),
    };
    let scene = one_instance(sphere(Vec3::ZERO, 1.0), static_placement(&trs));
    for options in [NORMAL, COUNTING] {
        let accel = EmbreeAccel::build(&scene, &options).unwrap();
        let mut c = TraversalCounters::default();
        let along = |origin: Vec3, dir: Vec3| {
            let ray = Ray::new(origin, dir, f32::INFINITY);
            accel.intersect(&ray, &mut TraversalCounters::default()).map(|h| (h.t, h.geom_id))
        };
        let cases = [
            (Vec3::new(10.0, 0.0, -10.0), Vec3::NEG_X, 6.0),
            (Vec3::new(10.0, 0.0, -10.0), Vec3::new(-2.0, 0.0, 0.0), 3.0),
            (Vec3::new(0.0, 10.0, -10.0), Vec3::NEG_Y, 8.0),
            (Vec3::ZERO, Vec3::new(0.0, 0.0, -0.5), 18.0),
            // x = 3: the ellipse's half height there is 2 * sqrt(1 - (3/4)^2).
            (Vec3::new(3.0, 2.5, -10.0), Vec3::NEG_Y, 2.5 - 2.0 * (1.0f32 - 0.5625).sqrt()),
        ];
        for (origin, dir, t) in cases {
            let (hit_t, geom_id) = along(origin, dir).expect("a hit");
            assert!((hit_t - t).abs() < 1e-5 * t && geom_id == 0, "{origin} {dir}: {hit_t} vs {t}");
        }
        // Beyond the ellipsoid's x extent of 4.
        assert_eq!(along(Vec3::new(4.1, 2.5, -10.0), Vec3::NEG_Y), None);
        let ray = Ray::new(Vec3::new(10.0, 0.0, -10.0), Vec3::NEG_X, 5.5);
        assert!(accel.intersect(&ray, &mut c).is_none() && !accel.occluded(&ray, &mut c));
        let ray = Ray { tmax: 6.5, ..ray };
        assert!(accel.occluded(&ray, &mut c));
        assert_eq!(c.node_visits, 0);
    }
}

/// A moving instance is where `Trs::lerp` puts it at the ray's time.
#[test]
fn moving_instance_is_where_trs_lerp_puts_it() {
    let start =
        Trs { translation: Vec3::new(-4.0, 0.0, 0.0), rotation: Quat::IDENTITY, scale: Vec3::ONE };
    let end = Trs {
        translation: Vec3::new(4.0, 0.0, 0.0),
        rotation: Quat::from_rotation_z(std::f32::consts::FRAC_PI_2),
        scale: Vec3::new(1.0, 3.0, 1.0),
    };
    // A unit quad in the xy plane at z = 0 (object space), as two triangles.
    let quad = mesh(
        vec![
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(-1.0, 1.0, 0.0),
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    );
    let scene = one_instance(quad, Placement::Moving { start, end });
    for options in [NORMAL, COUNTING] {
        let accel = EmbreeAccel::build(&scene, &options).unwrap();
        assert_eq!(accel.motion_geometries(), 1);
        let mut c = TraversalCounters::default();
        for step in 0..=20 {
            let time = step as f32 / 20.0;
            let placed = start.lerp(&end, time).to_affine();
            for corner in [Vec3::new(0.9, 0.8, 0.0), Vec3::new(-0.7, -0.95, 0.0)] {
                let p = placed.transform_point3(corner);
                let mut ray = Ray::new(p + Vec3::new(0.0, 0.0, 5.0), Vec3::NEG_Z, f32::INFINITY);
                ray.time = time;
                let hit = accel.intersect(&ray, &mut c);
                let hit = hit.unwrap_or_else(|| panic!("time {time}, corner {corner}: missed"));
                assert!((hit.t - 5.0).abs() < 1e-4, "time {time}: {hit:?}");
                // Barycentrics are the object-space triangle's.
                let tri = [[0, 1, 2], [0, 2, 3]][hit.prim_id as usize];
                let v = [
                    Vec3::new(-1.0, -1.0, 0.0),
                    Vec3::new(1.0, -1.0, 0.0),
                    Vec3::new(1.0, 1.0, 0.0),
                    Vec3::new(-1.0, 1.0, 0.0),
                ];
                let local =
                    v[tri[0]] * (1.0 - hit.u - hit.v) + v[tri[1]] * hit.u + v[tri[2]] * hit.v;
                assert!((local - corner).length() < 1e-4, "time {time}: {local} vs {corner}");
                // The same point at a very different time is somewhere else.
                ray.time = if time < 0.5 { 1.0 } else { 0.0 };
                assert!(accel.intersect(&ray, &mut c).is_none(), "time {time}: {ray:?}");
            }
        }
    }
}

/// Counting mode counts the user-triangle tests made inside child scenes.
#[test]
fn counting_mode_counts_tests_through_instances() {
    let (scene, _) = instanced_scene(true);
    let accel = EmbreeAccel::build(&scene, &COUNTING).unwrap();
    let rays = instanced_rays(2000);
    let counts = |accel: &EmbreeAccel| -> Vec<u64> {
        rays.iter()
            .map(|ray| {
                let mut c = TraversalCounters::default();
                accel.intersect(ray, &mut c);
                accel.occluded(ray, &mut c);
                c.prim_tests
            })
            .collect()
    };
    let first = counts(&accel);
    assert_eq!(counts(&accel), first, "deterministic");
    let mut instanced_hits = 0;
    for (ray, &tests) in rays.iter().zip(&first) {
        let mut c = TraversalCounters::default();
        if let Some(hit) = accel.intersect(ray, &mut c) {
            assert!(c.prim_tests >= 1 && tests >= 2, "{ray:?} {hit:?}");
            instanced_hits += usize::from(hit.geom_id >= 2);
        }
    }
    assert!(instanced_hits > 300, "{instanced_hits}");
    // One triangle, instanced: a ray through it tests exactly that one triangle.
    let trs = Trs {
        translation: Vec3::new(0.0, 0.0, -3.0),
        rotation: Quat::IDENTITY,
        scale: Vec3::splat(2.0),
    };
    let scene = one_instance(
        mesh(vec![Vec3::ZERO, Vec3::X, Vec3::Y], vec![[0, 1, 2]]),
        static_placement(&trs),
    );
    let accel = EmbreeAccel::build(&scene, &COUNTING).unwrap();
    let mut c = TraversalCounters::default();
    let hit =
        accel.intersect(&Ray::new(Vec3::new(0.5, 0.5, 0.0), Vec3::NEG_Z, f32::INFINITY), &mut c);
    assert_eq!(hit.map(|h| (h.geom_id, h.prim_id, h.t)), Some((0, 0, 3.0)));
    assert_eq!(c.prim_tests, 1);
}

mod limits;
/// Against the obvhs backend, the reference semantics.
#[cfg(feature = "obvhs")]
mod versus_obvhs;
