//! Signed distance grids (Mitsuba's `sdfgrid`): both backends find the hits a scan of every
//! voxel finds, rays leaving a grid's surface do not find it again where they start, and
//! the two backends render the same image.

mod common;

use common::*;
use embray::accel::{AccelOptions, BackendKind, build};
use embray::compile::{EffectsMode, to_render_scene};
use embray::intersect_sdf::intersect_voxel;
use embray::ray::Ray;
use embray::render_scene::{Geometry, RenderScene};
use embray::render_space::RenderSpace;
use embray::scene::{SceneDesc, ShapeDesc};
use embray::splitmix::SplitMix64;
use embray::stats::TraversalCounters;
use glam::Vec3;

/// `tests/data/mitsuba/sdfgrid.xml` (two grids of a torus, analytic and smooth normals, one
/// placed by an instance that rotates it, over a floor) at `res` pixels a side.
fn sdf_scene(res: u32) -> SceneDesc {
    let path = repo_path("tests/data/mitsuba/sdfgrid.xml");
    let defines = vec![("res".to_owned(), res.to_string())];
    let (mut scenes, _) = embray::scene::xml::load_with_warnings(&path, &defines).unwrap();
    scenes.remove(0).scene
}

/// The closest grid hit (t, instance) among every voxel of every grid, each tested with the
/// ray in its grid's units (as the backends test it).
fn scan(scene: &RenderScene, ray: &Ray) -> Option<(f32, u32)> {
    let mut best: Option<(f32, u32)> = None;
    for (index, instance) in scene.instances.iter().enumerate() {
        let Geometry::SdfGrid(grid) = &scene.prototypes[instance.prototype as usize].geometry
        else {
            continue;
        };
        let m = instance.placement.object_from_render(ray.time).unwrap();
        let (o, d) = (m.transform_point3(ray.origin), m.transform_vector3(ray.dir));
        for prim in 0..grid.voxels.len() as u32 {
            let (voxel, corners) = grid.prim_corners(prim).unwrap();
            let tmax = best.map_or(ray.tmax, |(t, _)| t);
            if let Some(t) = intersect_voxel(o, d, ray.tmin, tmax, voxel, &corners) {
                if best.is_none_or(|(b, _)| t < b) {
                    best = Some((t, index as u32));
                }
            }
        }
    }
    best
}

fn grids_only(scene: &SceneDesc) -> RenderScene {
    let mut desc = scene.clone();
    desc.objects.retain(|o| matches!(o.shape, ShapeDesc::SdfGrid(_)));
    assert_eq!(desc.objects.len(), 2);
    to_render_scene(&desc, RenderSpace::Cameraworld, EffectsMode::Auto).unwrap()
}

#[test]
fn backends_find_the_hits_a_scan_of_every_voxel_finds() {
    let scene = grids_only(&sdf_scene(16));
    let mut rng = SplitMix64(11);
    let rays: Vec<Ray> = (0..3000)
        .map(|_| {
            // From around the camera towards the two tori (render space is camera-centred).
            let origin = rng.vec3(-1.0, 1.0);
            let target = Vec3::new(0.0, 6.0, -3.0)
                + rng.between(Vec3::new(-3.0, -1.5, -1.5), Vec3::new(3.0, 1.5, 1.5));
            Ray::new(origin, target - origin, f32::INFINITY)
        })
        .collect();
    let expected: Vec<_> = rays.iter().map(|r| scan(&scene, r)).collect();
    let hits = expected.iter().filter(|h| h.is_some()).count();
    assert!(hits > rays.len() / 5, "{hits} hits");
    for backend in backends() {
        let accel = build(backend, &scene, &AccelOptions::default()).unwrap();
        let mut counters = TraversalCounters::default();
        for (ray, want) in rays.iter().zip(&expected) {
            let got = accel.intersect(ray, &mut counters).map(|h| (h.t, h.geom_id));
            let agree = match (got, *want) {
                (None, None) => true,
                (Some((a, ga)), Some((b, gb))) => ga == gb && (a - b).abs() <= 1e-5 * b,
                _ => false,
            };
            assert!(agree, "{backend:?}: {ray:?}: {got:?}, the scan {want:?}");
            assert_eq!(accel.occluded(ray, &mut counters), want.is_some(), "{backend:?}: {ray:?}");
        }
    }
}

/// A ray spawned from a grid hit, into the side the geometric normal faces, does not meet
/// the surface it leaves.
#[test]
fn rays_leaving_a_grid_do_not_hit_it_where_they_start() {
    let scene = grids_only(&sdf_scene(16));
    let mut rng = SplitMix64(5);
    for backend in backends() {
        let accel = build(backend, &scene, &AccelOptions::default()).unwrap();
        let mut counters = TraversalCounters::default();
        let (mut leaving, mut returned) = (0, 0);
        for _ in 0..3000 {
            let target = Vec3::new(0.0, 6.0, -3.0) + rng.vec3(-2.0, 2.0);
            let ray = Ray::new(Vec3::ZERO, target, f32::INFINITY);
            let Some(hit) = accel.intersect(&ray, &mut counters) else { continue };
            let si = embray::shading::surface::interaction(&scene, &ray, &hit);
            let n = si.surface.normal;
            let mut dir = rng.vec3(-1.0, 1.0).normalize_or_zero();
            if dir.dot(n) < 0.0 {
                dir = -dir;
            }
            let next = accel.intersect(&si.surface.spawn_ray(dir, 0.0), &mut counters);
            leaving += 1;
            returned += next.is_some_and(|h| h.geom_id == hit.geom_id && h.t < 1e-3) as usize;
        }
        assert!(leaving > 500, "{leaving} hits");
        assert_eq!(returned, 0, "{backend:?}: {returned} of {leaving} rays hit where they left");
    }
}

#[test]
#[cfg_attr(
    not(all(feature = "embree", feature = "obvhs")),
    ignore = "needs both backends compiled in (the default features)"
)]
fn both_backends_render_a_grid_alike() {
    let scene = sdf_scene(32);
    let embree = render_ok(&scene, &options(&scene, BackendKind::Embree, 4));
    let obvhs = render_ok(&scene, &options(&scene, BackendKind::Obvhs, 4));
    let error = image_error(&obvhs.film, &embree.film);
    assert!(error.relative_mse < 1e-6, "{error:?}");
    assert!(error.fraction_off < 1e-3, "{error:?}");
}

/// A grid's placement composes its 1/voxels scale into the object's transform; a transform
/// invertible in f32 alone but singular once composed is refused, not placed.
#[test]
fn a_grid_singular_once_scaled_to_its_voxels_is_refused() {
    let mut desc = sdf_scene(8);
    desc.objects.retain(|o| matches!(o.shape, ShapeDesc::SdfGrid(_)));
    desc.objects.truncate(1);
    // Determinant 2e-38, a normal f32; over the grid's voxels it is subnormal.
    let squashed = glam::DVec3::new(1e-19, 1e-19, 2.0);
    desc.objects[0].world_from_object = glam::DAffine3::from_scale(squashed);
    let error = to_render_scene(&desc, RenderSpace::Cameraworld, EffectsMode::Auto).unwrap_err();
    assert!(error.to_string().contains(&desc.objects[0].name), "{error}");
}

/// `embray info` lists grids, and a grid placed once (always by a transform) is not
/// instancing.
#[test]
fn info_lists_grids_and_a_lone_grid_is_not_instancing() {
    let desc = sdf_scene(8);
    let scene = to_render_scene(&desc, RenderSpace::Cameraworld, EffectsMode::Auto).unwrap();
    let features = embray::info::features(&scene);
    assert!(features.contains(&"signed distance grids"), "{features:?}");
    assert!(!features.contains(&"instancing"), "{features:?}");
}
