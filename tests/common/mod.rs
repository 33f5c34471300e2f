//! Helpers shared by the integration tests: tiny scenes, renders and image comparison.
#![allow(dead_code)]

use embray::accel::BackendKind;
#[allow(unused_imports)]
pub use embray::image_error::image_error;
use embray::render::{RenderOptions, RenderOutput, render};
use embray::scene::{SceneDesc, load, load_str};
use std::path::{Path, PathBuf};

pub fn repo_path(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(relative)
}

/// The bundled default scene, at a test-sized resolution.
pub fn cornell(width: u32, height: u32) -> SceneDesc {
    let mut scene = load(&repo_path("scenes/cornell.toml")).expect("default scene loads");
    scene.camera.width = width;
    scene.camera.height = height;
    scene
}

pub fn scene_from_str(text: &str) -> SceneDesc {
    load_str(text, &repo_path("tests/inline.toml")).expect("test scene loads")
}

/// Options for a small deterministic test render.
pub fn options(scene: &SceneDesc, backend: BackendKind, spp: u32) -> RenderOptions {
    let mut o = RenderOptions::for_scene(scene);
    o.spp = spp;
    o.seed = 7;
    o.backend = backend;
    o
}

pub fn render_ok(scene: &SceneDesc, options: &RenderOptions) -> RenderOutput {
    render(scene, options).expect("render succeeds")
}

/// Backends compiled into this build.
pub fn backends() -> Vec<BackendKind> {
    BackendKind::compiled()
}

/// Property-test settings: `default_cases` cases from the fixed `default_seed`, unless
/// `EMBRAY_PROPTEST_CASES` and `EMBRAY_PROPTEST_SEED` (a number, or `random`) say otherwise.
pub fn proptest_config(default_cases: u32, default_seed: u64) -> proptest::test_runner::Config {
    use proptest::test_runner::{Config, RngSeed};
    let cases = std::env::var("EMBRAY_PROPTEST_CASES").ok().and_then(|n| n.parse().ok());
    let seed = match std::env::var("EMBRAY_PROPTEST_SEED").ok().as_deref() {
        Some("random") => RngSeed::Random,
        Some(n) => RngSeed::Fixed(n.parse().expect("a number or random")),
        None => RngSeed::Fixed(default_seed),
    };
    Config {
        cases: cases.unwrap_or(default_cases),
        failure_persistence: None,
        rng_seed: seed,
        ..Config::default()
    }
}

/// The mean colour of a film.
pub fn film_mean(film: &embray::film::Film) -> glam::Vec3 {
    film.color.iter().copied().sum::<glam::Vec3>() / film.color.len() as f32
}

/// Form factor from a point to a parallel rectangle of sides `a`, `b` whose corner is
/// `h` straight above it (the standard closed form).
pub fn corner_form_factor(a: f64, b: f64, h: f64) -> f64 {
    let (x, y) = (a / h, b / h);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * std::f64::consts::PI)
}

/// Fails unless `message` contains every one of `parts`.
#[track_caller]
pub fn assert_contains(message: &str, parts: &[&str]) {
    for part in parts {
        assert!(message.contains(part), "expected {part:?} in the message:\n{message}");
    }
}

/// Programmatic scenes for effect tests (independent of the file format).
pub mod scene_files;

/// The command line, run as a user runs it.
pub mod command;

pub mod build {
    use embray::scene::*;
    use glam::{DAffine3, DVec3, Vec2, Vec3};
    use std::sync::Arc;

    pub fn camera(
        lookfrom: [f64; 3],
        lookat: [f64; 3],
        vfov: f64,
        width: u32,
        height: u32,
    ) -> CameraDesc {
        CameraDesc::pinhole(
            DVec3::from_array(lookfrom),
            DVec3::from_array(lookat),
            vfov,
            width,
            height,
        )
    }

    pub fn scene(camera: CameraDesc) -> SceneDesc {
        SceneDesc {
            source: "test".into(),
            reading_bytes: 0,
            camera,
            settings: RenderSettings::default(),
            materials: Vec::new(),
            objects: Vec::new(),
            lights: Vec::new(),
        }
    }

    pub fn add_material(scene: &mut SceneDesc, material: MaterialDesc) -> u32 {
        scene.materials.push(material);
        (scene.materials.len() - 1) as u32
    }

    pub fn diffuse(albedo: f32) -> MaterialDesc {
        MaterialDesc { name: "diffuse".into(), albedo: Vec3::splat(albedo), ..Default::default() }
    }

    pub fn emissive(radiance: f32) -> MaterialDesc {
        MaterialDesc {
            name: "light".into(),
            albedo: Vec3::ZERO,
            emission: Vec3::splat(radiance),
            ..Default::default()
        }
    }

    pub fn object(
        name: &str,
        shape: ShapeDesc,
        material: u32,
        world_from_object: DAffine3,
    ) -> ObjectDesc {
        ObjectDesc {
            name: name.into(),
            shape,
            material,
            world_from_object,
            world_from_object_end: None,
        }
    }

    pub fn sphere(radius: f64) -> ShapeDesc {
        ShapeDesc::Sphere { center: DVec3::ZERO, radius }
    }

    /// A parallelogram as two triangles with uvs.
    pub fn quad(corner: [f64; 3], u: [f64; 3], v: [f64; 3]) -> ShapeDesc {
        let (c, u, v) = (DVec3::from_array(corner), DVec3::from_array(u), DVec3::from_array(v));
        ShapeDesc::Mesh(Arc::new(MeshData {
            positions: vec![c, c + u, c + u + v, c + v],
            indices: vec![[0, 1, 2], [0, 2, 3]],
            normals: None,
            uvs: Some(vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y]),
            attributes: Vec::new(),
        }))
    }

    /// A diffuse floor: the square of half-side `half` in the plane y = 0, facing up.
    pub fn add_floor(scene: &mut SceneDesc, albedo: f32, half: f64) -> u32 {
        let m = add_material(scene, diffuse(albedo));
        let shape = quad([-half, 0.0, half], [2.0 * half, 0.0, 0.0], [0.0, 0.0, -2.0 * half]);
        scene.objects.push(object("floor", shape, m, DAffine3::IDENTITY));
        m
    }

    /// An emissive rectangle at height `y`, `size` = (x, z) extents from `corner` = (x, z),
    /// facing down (u × v = −y).
    pub fn add_ceiling_light(
        scene: &mut SceneDesc,
        corner: [f64; 2],
        size: [f64; 2],
        y: f64,
        radiance: f32,
    ) {
        let m = add_material(scene, emissive(radiance));
        let shape = quad([corner[0], y, corner[1]], [size[0], 0.0, 0.0], [0.0, 0.0, size[1]]);
        scene.objects.push(object("light", shape, m, DAffine3::IDENTITY));
    }

    /// A closed unit cube [0,1]³ with outward winding.
    pub fn cube() -> Arc<MeshData> {
        let positions = (0..8)
            .map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
            .collect();
        let quads =
            [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
        let indices = quads.iter().flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).collect();
        Arc::new(MeshData { positions, indices, normals: None, uvs: None, attributes: Vec::new() })
    }
}
