//! Textured area emitters (`emission_texture`, Mitsuba's area emitter with a textured
//! radiance): light sampling must find the radiance a ray that hits the sampled point finds,
//! on every shape and placement an emitter can have (a baked quad, a mirrored one, boxes
//! placed as instances and mirrored, a rotated sphere, spheres placed as instances, a mesh
//! without texture coordinates); and the image is the same on both backends.

mod common;

use embray::accel::{AccelOptions, BackendKind};
use embray::film::Film;
use embray::ray::Ray;
use embray::splitmix::SplitMix64;
use embray::stats::TraversalCounters;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// A smooth texture, periodic in u and flat in u at the poles (v = 0, 1), so that nearby
/// coordinates give nearby colours everywhere on a quad or a sphere, seams included.
fn write_ramp(path: &std::path::Path) {
    let (w, h) = (64, 32);
    let mut film = Film::new(w, h);
    for (i, texel) in film.color.iter_mut().enumerate() {
        let (u, v) =
            (((i as u32 % w) as f32 + 0.5) / w as f32, ((i as u32 / w) as f32 + 0.5) / h as f32);
        let ring = 0.4 * (PI * v).sin();
        *texel = Vec3::new(
            0.5 + ring * (2.0 * PI * u).sin(),
            0.5 + ring * (2.0 * PI * u).cos(),
            0.2 + 0.6 * v,
        );
    }
    embray::output::write_exr(&film, path).unwrap();
}

const SCENE: &str = r#"
[camera]
lookfrom = [0, 1, -9]
lookat = [0, 1, 0]
vfov = 50
resolution = [24, 16]

[render]
spp = 4
max_depth = 3

[materials.grey]
albedo = [0.5, 0.5, 0.5]
[materials.lamp]
emission = [2, 1.5, 1]
emission_texture = { type = "image", file = "ramp.exr" }
[materials.two_sided_lamp]
two_sided_emission = true
emission_texture = { type = "image", file = "ramp.exr" }

[[objects]]
type = "quad"
material = "grey"
corner = [-8, 0, -8]
u = [16, 0, 0]
v = [0, 0, 16]

[[objects]]
type = "quad"
material = "lamp"
corner = [-3, 0.5, 1]
u = [1.5, 0.2, 0]
v = [0.1, 1.4, 0.3]

[[objects]]
type = "quad"
material = "two_sided_lamp"
corner = [0, 0, 0]
u = [1.2, 0, 0]
v = [0, 1, 0.2]
transform = [
  { scale = [-1, 1, 1] },
  { rotate = { axis = [0, 1, 0], degrees = 30 } },
  { translate = [-0.5, 2.2, 1.5] },
]

[[objects]]
type = "box"
material = "lamp"
min = [0, 0, 0]
max = [0.6, 0.8, 0.5]
transform = [{ scale = [-1, 1, 1] }, { translate = [2, 0.1, 0] }]
repeat = { count = [2, 1, 1], spacing = [1.3, 0, 0] }

[[objects]]
type = "sphere"
material = "lamp"
center = [0, 0, 0]
radius = 0.6
transform = [
  { rotate = { axis = [1, 0.3, 0], degrees = 50 } },
  { translate = [0.3, 1.1, -0.5] },
]

[[objects]]
type = "sphere"
material = "two_sided_lamp"
center = [0, 0, 0]
radius = 0.35
transform = [{ rotate = { axis = [0, 0, 1], degrees = -35 } }, { translate = [-2, 2.8, -1] }]
repeat = { count = [1, 1, 2], spacing = [0, 0, 1.1] }

[[objects]]
type = "mesh"
material = "lamp"
file = "tetrahedron.obj"
transform = [{ translate = [1.5, 2.5, 1.8] }]
"#;

/// A mesh without texture coordinates: a hit's are its barycentrics.
const TETRAHEDRON: &str =
    "v 0 0 0\nv 0.8 0 0\nv 0 0.8 0\nv 0 0 0.8\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

fn scene(name: &str) -> (common::command::TempDir, embray::scene::SceneDesc) {
    let dir = common::command::temp_dir(name);
    write_ramp(&dir.join("ramp.exr"));
    std::fs::write(dir.join("tetrahedron.obj"), TETRAHEDRON).unwrap();
    let path = dir.join("lamps.toml");
    std::fs::write(&path, SCENE).unwrap();
    let scene = embray::scene::load(&path).unwrap();
    (dir, scene)
}

#[test]
fn light_samples_find_the_radiance_a_ray_finds_there() {
    let (_dir, desc) = scene("textured-emitters-samples");
    let space = embray::render_space::RenderSpace::Cameraworld;
    let scene =
        embray::compile::to_render_scene(&desc, space, embray::compile::EffectsMode::Auto).unwrap();
    let textured = scene.lights.emitters.iter().filter(|e| e.emission_map.is_some()).count();
    // Two triangles a quad (quads are not merged when textured), 12 a box, 1 a sphere, 4
    // the tetrahedron.
    assert_eq!(textured, 2 + 2 + 2 * 12 + 1 + 2 + 4, "{} emitters", scene.lights.emitters.len());
    let backend = common::backends()[0];
    let accel = embray::accel::build(backend, &scene, &AccelOptions::default()).unwrap();
    let camera = desc.camera.lookfrom.as_vec3();
    let mut rng = SplitMix64(5);
    let mut counters = TraversalCounters::default();
    let (mut compared, mut geoms) = (0, std::collections::BTreeSet::new());
    for _ in 0..40_000 {
        // Points around the lamps (in render space: the camera is at its origin).
        let reference = rng.vec3(-4.0, 4.0) + Vec3::new(0.0, 2.0, 1.0) - camera;
        let (pick, u) = (Vec2::new(rng.unit(), rng.unit()), Vec2::new(rng.unit(), rng.unit()));
        let Some(sample) = scene.lights.sample_emitter(reference, pick, u) else { continue };
        let to = sample.point - reference;
        let ray = Ray::new(reference, to, 1.0 + 1e-3);
        let Some(hit) = accel.intersect(&ray, &mut counters) else { continue };
        let si = embray::shading::surface::interaction(&scene, &ray, &hit);
        // Only where the ray finds the sampled point itself (not something in front of it).
        if hit.geom_id != sample.geom_id || (si.surface.point - sample.point).length() > 1e-4 {
            continue;
        }
        let material = &scene.materials[si.material as usize];
        let found = material.emission_seen(si.front_face, si.uv);
        let cosine = sample.emitted_cosine(-to.normalize());
        if cosine <= 0.0 {
            assert_eq!(found, Vec3::ZERO, "{reference}: behind a one-sided emitter");
            continue;
        }
        let error = (found - sample.emission).abs().max_element();
        assert!(
            error < 2e-3,
            "{reference} → {}: sampled {} vs hit {found}",
            sample.point,
            sample.emission
        );
        compared += 1;
        geoms.insert(hit.geom_id);
    }
    // Every emissive instance (two quads, two boxes, three spheres, the tetrahedron) was
    // compared, often.
    assert_eq!(geoms.len(), 8, "{geoms:?}");
    assert!(compared > 5_000, "{compared}");
}

/// As `tests/parity.rs` has it for the bundled scenes: the backends' triangle tests differ
/// in their last bits (a path may end differently at an edge), so the images agree to
/// rounding.
#[test]
#[cfg_attr(
    not(all(feature = "embree", feature = "obvhs")),
    ignore = "needs both backends compiled in (the default features)"
)]
fn both_backends_render_the_same_image() {
    let (_dir, scene) = scene("textured-emitters-backends");
    let render = |backend| {
        let mut options = common::options(&scene, backend, 4);
        options.seed = 3;
        common::render_ok(&scene, &options)
    };
    let (embree, obvhs) = (render(BackendKind::Embree), render(BackendKind::Obvhs));
    assert!(embree.film.color.iter().filter(|c| c.max_element() > 0.0).count() > 100);
    let error = common::image_error(&obvhs.film, &embree.film);
    assert!(error.relative_mse < 1e-9, "{error:?}");
    assert_eq!(error.non_finite, 0);
}

/// `embray convert` writes the texture back, and what it writes reads back the same; a
/// texture needs uv coordinates (a solid pattern is refused by name).
#[test]
fn emission_textures_round_trip_through_toml_and_need_coordinates() {
    let (dir, scene) = scene("textured-emitters-toml");
    let mut writer = embray::scene::toml_writer::TomlWriter::new(dir.join("meshes"));
    writer.write(&scene, &dir.join("back.toml"), "round trip").unwrap();
    let back = embray::scene::load(&dir.join("back.toml")).unwrap();
    let textures = |s: &embray::scene::SceneDesc| {
        s.materials.iter().map(|m| (m.emission, m.emission_texture.clone())).collect::<Vec<_>>()
    };
    assert!(textures(&scene).iter().filter(|(_, t)| t.is_some()).count() == 2);
    assert_eq!(textures(&back), textures(&scene));
    let solid = SCENE.replace(
        r#"emission_texture = { type = "image", file = "ramp.exr" }
[materials.two"#,
        r#"emission_texture = { type = "perlin", scale = 2 }
[materials.two"#,
    );
    assert_ne!(solid, SCENE);
    let err = embray::scene::load_str(&solid, &dir.join("solid.toml")).unwrap_err().to_string();
    assert!(
        err.contains("materials.lamp.emission_texture.type") && err.contains("perlin"),
        "{err}"
    );
}
