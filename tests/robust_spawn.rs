//! Spawned rays never re-hit the surface they leave, even at grazing angles far away.

mod common;

use common::*;
use embray::choice::Choice;
use embray::render_space::RenderSpace;
use glam::DVec3;

/// One large plane and a point light 2 units above it, 400 units away: the light arrives at
/// about 0.3° above the surface. The plane is the only geometry, so any occluded shadow ray
/// is a self-intersection.
const GRAZING_PLANE: &str = r#"
[camera]
lookfrom = [0.0, 30.0, 120.0]
lookat = [0.0, 0.0, 0.0]
vfov = 50.0
resolution = [48, 32]

[materials.white]
albedo = [0.8, 0.8, 0.8]

[[objects]]
type = "quad"
material = "white"
corner = [-1000.0, 0.0, -1000.0]
u = [2000.0, 0.0, 0.0]
v = [0.0, 0.0, 2000.0]

[[lights]]
type = "point"
position = [0.0, 2.0, -400.0]
intensity = [1e6, 1e6, 1e6]
"#;

#[test]
fn grazing_light_at_offset_1e6_causes_no_self_shadowing() {
    let scene = scene_from_str(GRAZING_PLANE);
    for backend in backends() {
        for space in [RenderSpace::Cameraworld, RenderSpace::World] {
            let mut o = options(&scene, backend, 4);
            o.offset = DVec3::new(1e6, 1e6, -1e6);
            o.render_space = space;
            o.max_depth = 2;
            let out = render_ok(&scene, &o);
            println!("{} {}: {:?}", backend.name(), space.name(), out.stats.shadow);
            assert!(out.stats.shadow.rays > 1000, "the test must trace shadow rays");
            assert_eq!(
                out.stats.shadow.hits,
                0,
                "{} {}: self-shadowed rays",
                backend.name(),
                space.name()
            );
            let lit = out.film.color.iter().filter(|c| c.x > 0.0).count();
            assert!(lit > out.film.color.len() / 2, "the plane must be lit");
        }
    }
}

/// A 20 km square tilted 37° about a skew axis, 10⁶ units from the origin, seen from 2 units
/// above it (so in `cameraworld` the huge triangle passes right by the origin): placed once
/// (baked into render space), twice (an instance), or moving; `kind` picks which.
fn tilted_plane_scene(kind: &str) -> embray::scene::SceneDesc {
    use common::build::*;
    use glam::DAffine3;
    let far = DVec3::new(1e6, -2e6, 1.5e6);
    let tilt = DAffine3::from_translation(far)
        * DAffine3::from_axis_angle(DVec3::new(1.0, 0.3, -0.2).normalize(), 37f64.to_radians());
    let eye = tilt.transform_point3(DVec3::new(100.0, 2.0, 50.0));
    let target = tilt.transform_point3(DVec3::new(300.0, 0.0, -200.0));
    let mut s = scene(camera(eye.to_array(), target.to_array(), 60.0, 8, 8));
    let m = add_material(&mut s, diffuse(0.5));
    let plane = quad([-1e4, 0.0, 1e4], [2e4, 0.0, 0.0], [0.0, 0.0, -2e4]);
    let mut object = object("plane", plane.clone(), m, tilt);
    if kind == "moving" {
        object.world_from_object_end =
            Some(DAffine3::from_translation(DVec3::new(3.0, 1.0, 0.0)) * tilt);
    }
    s.objects.push(object);
    if kind == "instanced" {
        let away = DAffine3::from_translation(far + DVec3::new(0.0, -1e5, 0.0));
        s.objects.push(embray::scene::ObjectDesc {
            name: "copy".into(),
            shape: plane,
            material: m,
            world_from_object: away,
            world_from_object_end: None,
        });
    }
    s
}

#[test]
fn rays_leaving_a_large_tilted_triangle_far_away_never_hit_it_again() {
    use embray::render::prepare_scene;
    for kind in ["baked", "instanced", "moving"] {
        let desc = tilted_plane_scene(kind);
        for backend in backends() {
            for space in [RenderSpace::Cameraworld, RenderSpace::World] {
                let mut o = options(&desc, backend, 1);
                o.render_space = space;
                let scene = prepare_scene(&desc, &o).unwrap();
                let placement = &scene.instances[0].placement;
                assert_eq!(placement.is_moving(), kind == "moving", "{kind}");
                assert_eq!(
                    matches!(placement, embray::render_scene::Placement::Baked { .. }),
                    kind == "baked",
                    "{kind}"
                );
                let (spawned, self_hits) = spawn_from_camera_hits(&scene, backend, 400, 17);
                println!(
                    "{kind} {} {}: {spawned} rays spawned, {self_hits} self-hits",
                    backend.name(),
                    space.name()
                );
                assert!(spawned > 1000, "{kind}: the camera must see the plane");
                assert_eq!(self_hits, 0, "{kind} {} {}", backend.name(), space.name());
            }
        }
    }
}

/// Slivers: triangles 10⁴ long and 10⁻² wide (their cross product is tiny against their
/// edges, so the rounded normal tilts), tilted, seen from close by.
#[test]
fn rays_leaving_sliver_triangles_never_hit_them_again() {
    use common::build::*;
    use embray::render::prepare_scene;
    use embray::scene::{MeshData, ShapeDesc};
    use glam::DAffine3;
    use std::sync::Arc;
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    for i in 0..40u32 {
        let z = i as f64 * 0.02;
        let base = positions.len() as u32;
        positions.push(DVec3::new(-5e3, 0.0, z));
        positions.push(DVec3::new(5e3, 0.0, z + 0.003));
        positions.push(DVec3::new(5e3, 0.0, z + 0.013));
        indices.push([base, base + 1, base + 2]);
    }
    let mesh =
        Arc::new(MeshData { positions, indices, normals: None, uvs: None, attributes: Vec::new() });
    let tilt = DAffine3::from_translation(DVec3::new(3e5, 1e5, -2e5))
        * DAffine3::from_axis_angle(DVec3::new(0.3, 1.0, 0.5).normalize(), 0.7);
    let eye = tilt.transform_point3(DVec3::new(4000.0, 0.5, 0.4));
    let target = tilt.transform_point3(DVec3::new(4000.3, 0.0, 0.4));
    let mut s = scene(camera(eye.to_array(), target.to_array(), 60.0, 16, 16));
    let m = add_material(&mut s, diffuse(0.5));
    s.objects.push(object("slivers", ShapeDesc::Mesh(mesh), m, tilt));
    let mut total_self_hits = 0;
    for backend in backends() {
        for space in [RenderSpace::Cameraworld, RenderSpace::World] {
            let mut o = options(&s, backend, 1);
            o.render_space = space;
            let scene = prepare_scene(&s, &o).unwrap();
            let (spawned, self_hits) = spawn_from_camera_hits(&scene, backend, 2000, 3);
            println!(
                "{} {}: {spawned} rays spawned, {self_hits} self-hits",
                backend.name(),
                space.name()
            );
            assert!(spawned > 1000, "the camera must see the slivers");
            total_self_hits += self_hits;
        }
    }
    assert_eq!(total_self_hits, 0);
}

/// Traces `camera_rays` random camera rays (at random shutter times) into `scene`; from each
/// hit, spawns 8 rays in random directions on either side of the surface, grazing ones
/// included, and counts those that hit the same object again. The scenes passed here are
/// single planes, so every such hit is a self-intersection. Returns (spawned, self-hits).
fn spawn_from_camera_hits(
    scene: &embray::render_scene::RenderScene,
    backend: embray::accel::BackendKind,
    camera_rays: usize,
    seed: u64,
) -> (usize, usize) {
    use embray::accel::{AccelOptions, build};
    use embray::shading::spawn::SpawnMode;
    use embray::shading::surface::interaction;
    use embray::splitmix::SplitMix64;
    use embray::stats::TraversalCounters;
    use glam::{Vec2, Vec3};
    let accel = build(backend, scene, &AccelOptions::default()).unwrap();
    let (w, h) = (scene.camera.width as f32, scene.camera.height as f32);
    let mut counters = TraversalCounters::default();
    let mut rng = SplitMix64(seed);
    let (mut spawned, mut self_hits) = (0, 0);
    for _ in 0..camera_rays {
        let raster = Vec2::new(rng.range(0.0, w), rng.range(0.0, h));
        let mut ray = scene.camera.generate_ray(raster, None);
        ray.time = rng.unit();
        let Some(hit) = accel.intersect(&ray, &mut counters) else { continue };
        let si = interaction(scene, &ray, &hit);
        for _ in 0..8 {
            let dir = rng.vec3(-1.0, 1.0).normalize_or_zero();
            if dir == Vec3::ZERO || dir.dot(si.surface.normal) == 0.0 {
                continue;
            }
            let next = SpawnMode::Robust.ray(&si.surface, dir, ray.time);
            spawned += 1;
            if let Some(again) = accel.intersect(&next, &mut counters) {
                self_hits += (again.geom_id == hit.geom_id) as usize;
            }
        }
    }
    (spawned, self_hits)
}
