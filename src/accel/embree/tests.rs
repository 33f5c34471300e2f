//! The Embree backend against a brute-force linear scan, plus bad input and error reporting.

use super::EmbreeAccel;
use super::device::Device;
use super::ffi;
use super::geometry_handle::GeometryHandle;
use super::scene::Scene;
use super::test_scenes::*;
use crate::accel::{self, Accel, AccelError, AccelOptions, BackendKind};
use crate::ray::Ray;
use crate::stats::TraversalCounters;
use glam::Vec3;
use std::sync::Arc;

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

/// `AccelOptions::intersection` and `compact` reach the scene's flags.
#[test]
fn intersection_and_compact_set_the_scene_flags() {
    use crate::accel::Intersection;
    let scene = random_scene();
    for (intersection, test) in [
        (Intersection::Robust, ffi::RTCSceneFlags::ROBUST),
        (Intersection::Fast, ffi::RTCSceneFlags::NONE),
    ] {
        for (compact, layout) in
            [(false, ffi::RTCSceneFlags::NONE), (true, ffi::RTCSceneFlags::COMPACT)]
        {
            let options = AccelOptions { intersection, compact, ..AccelOptions::default() };
            let accel = EmbreeAccel::build(&scene, &options).unwrap();
            assert_eq!(accel.scene_flags(), test | layout, "{options:?}");
        }
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
