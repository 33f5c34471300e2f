//! Light transport that is right by construction: shadow rays that reach their light,
//! concave emitters that keep their energy, and one handedness rule for mirrored objects.

mod common;

use common::build::*;
use common::*;
use embray::choice::Choice;
use embray::render_options::PathBatching;
use embray::sampling::SamplerKind;
use embray::scene::{MeshData, SceneDesc, ShapeDesc};
use glam::{DAffine3, DVec3, Vec3};
use std::sync::Arc;

/// A floor lit only by a 10×10 emissive quad 10⁴ units above it, looking down; with
/// `sheet`, a 1 mm thick slab twice the light's size 0.5 units below the light blocks it.
fn far_light_scene(sheet: bool) -> SceneDesc {
    let mut s = scene(camera([0.0, 50.0, 0.1], [0.0, 0.0, 0.0], 40.0, 16, 16));
    s.settings.max_depth = 1;
    add_floor(&mut s, 0.8, 100.0);
    add_ceiling_light(&mut s, [-5.0, -5.0], [10.0, 10.0], 1e4, 1e9);
    let grey = add_material(&mut s, diffuse(0.0));
    if sheet {
        let slab = DAffine3::from_translation(DVec3::new(-10.0, 1e4 - 0.5, -10.0))
            * DAffine3::from_scale(DVec3::new(20.0, 1e-3, 20.0));
        s.objects.push(object("sheet", ShapeDesc::Mesh(cube()), grey, slab));
    }
    s
}

#[test]
fn a_thin_sheet_just_in_front_of_a_far_light_blocks_it() {
    for backend in backends() {
        let lit = render_ok(&far_light_scene(false), &options(&far_light_scene(false), backend, 4));
        let blocked_scene = far_light_scene(true);
        let blocked = render_ok(&blocked_scene, &options(&blocked_scene, backend, 4));
        let (lit, blocked) = (film_mean(&lit.film), film_mean(&blocked.film));
        println!("{}: lit {lit}, behind the sheet {blocked}", backend.name());
        assert!(lit.x > 1.0, "{}: the control render must be lit ({lit})", backend.name());
        assert_eq!(blocked, Vec3::ZERO, "{}: light leaks past the sheet", backend.name());
    }
}

/// The unit cube [-1, 1]³ wound inwards (normals point into the box).
fn inward_cube() -> Arc<MeshData> {
    let outward = cube();
    Arc::new(MeshData {
        positions: outward.positions.iter().map(|p| *p * 2.0 - DVec3::ONE).collect(),
        indices: outward.indices.iter().map(|t| [t[0], t[2], t[1]]).collect(),
        normals: None,
        uvs: None,
        attributes: Vec::new(),
    })
}

#[test]
fn a_closed_emitter_seen_from_inside_is_a_furnace() {
    // Inside a closed box emitting E with albedo a, every direction sees E directly, plus
    // aE lit by it, and so on: with N surface interactions, each gathering direct light,
    // E · (1 + a + … + a^N) = E (1 − a^(N+1)) / (1 − a).
    let (emission, albedo, depth) = (1.0f32, 0.5f32, 4u32);
    let mut s = scene(camera([0.1, 0.2, 0.3], [0.5, -0.3, 0.9], 70.0, 16, 16));
    s.settings.max_depth = depth;
    let mut wall = emissive(emission);
    wall.albedo = Vec3::splat(albedo);
    let wall = add_material(&mut s, wall);
    s.objects.push(object("box", ShapeDesc::Mesh(inward_cube()), wall, DAffine3::IDENTITY));
    let expected = emission * (1.0 - albedo.powi(depth as i32 + 1)) / (1.0 - albedo);
    // Every backend with the default sampler, and every sampler on the first backend.
    let runs = backends().into_iter().map(|b| (b, SamplerKind::default())).chain(
        SamplerKind::ALL
            .iter()
            .filter(|&&k| k != SamplerKind::default())
            .map(|&k| (backends()[0], k)),
    );
    for (backend, sampler) in runs {
        let mut o = options(&s, backend, 64);
        o.sampler = sampler;
        let m = film_mean(&render_ok(&s, &o).film);
        println!("{} {sampler}: mean {m}, expected {expected}", backend.name());
        for c in m.to_array() {
            assert!(
                (c - expected).abs() < 0.01 * expected,
                "{} {sampler}: {m} vs {expected}",
                backend.name()
            );
        }
    }
}

/// A mirrored (x → −x) glass cube with Beer absorption in front of a mirrored emissive cube,
/// both lifted off a floor; with `shared`, each cube's mesh is also placed once more out of sight, so
/// the visible copies are instances (the mesh transformed at trace time) instead of meshes
/// baked into render space.
fn mirrored_scene(shared: bool) -> SceneDesc {
    let mut s = scene(camera([0.0, 2.0, 8.0], [0.0, 0.5, 0.0], 45.0, 32, 24));
    s.settings.max_depth = 6;
    let floor = add_material(&mut s, diffuse(0.7));
    let mut glass = diffuse(0.0);
    glass.specular = embray::scene::Specular::dielectric(1.5, Vec3::new(0.2, 0.5, 0.9));
    let glass = add_material(&mut s, glass);
    let light = add_material(&mut s, emissive(4.0));
    let mirror = |at: DVec3| {
        DAffine3::from_translation(at) * DAffine3::from_scale(DVec3::new(-1.5, 1.5, 1.5))
    };
    let glass_mesh = cube();
    let light_mesh = cube();
    s.objects.push(object(
        "floor",
        quad([-20.0, 0.0, 20.0], [40.0, 0.0, 0.0], [0.0, 0.0, -40.0]),
        floor,
        DAffine3::IDENTITY,
    ));
    s.objects.push(object(
        "glass",
        ShapeDesc::Mesh(glass_mesh.clone()),
        glass,
        mirror(DVec3::new(0.8, 0.3, 1.0)),
    ));
    s.objects.push(object(
        "light",
        ShapeDesc::Mesh(light_mesh.clone()),
        light,
        mirror(DVec3::new(0.5, 0.3, -2.0)),
    ));
    if shared {
        // Below the floor and not emitting, so they change neither the image nor the
        // light selection.
        let away = DAffine3::from_translation(DVec3::new(0.0, -100.0, 0.0));
        s.objects.push(object("glass again", ShapeDesc::Mesh(glass_mesh), floor, away));
        s.objects.push(object("light again", ShapeDesc::Mesh(light_mesh), floor, away));
    }
    s
}

#[test]
fn mirrored_objects_render_alike_baked_and_instanced() {
    for backend in backends() {
        let (baked, instanced) = (mirrored_scene(false), mirrored_scene(true));
        let baked = render_ok(&baked, &options(&baked, backend, 16));
        let instanced = render_ok(&instanced, &options(&instanced, backend, 16));
        let error = image_error(&instanced.film, &baked.film);
        let (b, i) = (film_mean(&baked.film), film_mean(&instanced.film));
        println!("{}: baked mean {b}, instanced mean {i}, {error:?}", backend.name());
        assert!(b.x > 0.1, "{}: the scene must be lit ({b})", backend.name());
        // Observed 3e-13 (Embree) and 8e-13 (obvhs): rounding of the transforms only. Before
        // one handedness rule the baked emitter shone inwards and the image was black.
        assert!(error.relative_mse < 1e-10, "{}: {error:?}", backend.name());
    }
}

/// The path tracer's last ray looks only for light: where no ray can find any (no emitter,
/// environment or background), it is not traced, and the image is the same. Inside a
/// closed box lit by a point light, a grey background (which no ray can reach) makes it
/// traced: the same image bit for bit, with more rays, on both backends and both ways of
/// advancing paths.
#[test]
fn the_last_ray_is_traced_only_where_rays_can_find_light() {
    let box_scene = |background: f32| {
        scene_from_str(&format!(
            "[camera]\nlookfrom = [0.0, 0.0, 1.5]\nlookat = [0.0, 0.0, 0.0]\nvfov = 60.0\n\
             resolution = [16, 16]\n[render]\nmax_depth = 3\nbackground = [{background}, \
             {background}, {background}]\n[materials.grey]\nalbedo = [0.6, 0.6, 0.6]\n\
             [[objects]]\ntype = \"box\"\nmaterial = \"grey\"\nmin = [-2.0, -2.0, -2.0]\n\
             max = [2.0, 2.0, 2.0]\n[[lights]]\ntype = \"point\"\nposition = [0.0, 1.0, 0.0]\n\
             intensity = [5.0, 5.0, 5.0]\n"
        ))
    };
    let (dark, grey) = (box_scene(0.0), box_scene(0.5));
    for backend in backends() {
        for paths in [PathBatching::Batched, PathBatching::Scalar] {
            let render = |s: &SceneDesc| {
                let mut o = options(s, backend, 4);
                o.paths = paths;
                render_ok(s, &o)
            };
            let (skipped, traced) = (render(&dark), render(&grey));
            let what = format!("{} {paths:?}", backend.name());
            assert!(film_mean(&skipped.film).x > 0.01, "{what}: the box must be lit");
            assert_eq!(skipped.film.color, traced.film.color, "{what}: the images differ");
            let (a, b) = (skipped.stats.indirect.rays, traced.stats.indirect.rays);
            assert!(b > a && a > 0, "{what}: {a} rays without light to find, {b} with");
            assert_eq!(traced.stats.indirect.hits, traced.stats.indirect.rays, "{what}: closed");
        }
    }
}
