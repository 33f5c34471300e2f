//! The batched path tracer (paths advanced together a bounce at a time, rays traced in
//! packets, plain Lambertian bounces in vector lanes) renders exactly the scalar one's
//! image, ray counts included, and so does the reference (every BSDF through the general
//! code): on every bundled scene, on Mitsuba's render suite scenes and on the course's
//! path-tracing scenes, on both backends and with each of Embree's batch modes (and with
//! its fast triangle test).

mod common;

use common::*;
use embray::accel::{BackendKind, BatchMode, Intersection};
use embray::choice::Choice;
use embray::render::TILE_SIZE;
use embray::render_options::PathBatching;
use embray::scene::SceneDesc;
use embray::stats::BounceCounts;
use std::path::{Path, PathBuf};

/// Renders `scene` at `width`×`height`, `spp` samples, scalar and batched on every backend
/// (and Embree batch mode), and asserts the images and ray counts are the same.
/// Returns the bounces counted, summed over the backends.
fn assert_batched_is_scalar(
    name: &str,
    scene: &SceneDesc,
    width: u32,
    height: u32,
    spp: u32,
) -> BounceCounts {
    let mut counted = BounceCounts::default();
    let mut scene = scene.clone();
    scene.camera.width = width;
    scene.camera.height = height;
    scene.settings.crop = None;
    for backend in backends() {
        let mut scalar = options(&scene, backend, spp);
        scalar.paths = PathBatching::Reference;
        let general = render_ok(&scene, &scalar);
        scalar.paths = PathBatching::Scalar;
        let reference = render_ok(&scene, &scalar);
        assert!(reference.stats.total_rays() > 0, "{name}: traced nothing");
        let what = format!("{name} on {}", backend.name());
        assert!(general.film == reference.film, "{what}: the Lambertian lanes' image differs");
        let rays = |s: &embray::stats::RenderStats| (s.camera, s.shadow, s.indirect, s.traversal);
        assert_eq!(rays(&general.stats), rays(&reference.stats), "{what}: ray counts, lanes");
        let bounces = reference.stats.bounces;
        assert_eq!(general.stats.bounces.scalar, bounces.lanes + bounces.scalar, "{what}");
        counted += bounces;
        let modes: &[BatchMode] = match backend {
            BackendKind::Embree => &[BatchMode::Single, BatchMode::Packets8, BatchMode::Packets16],
            BackendKind::Obvhs => &[BatchMode::Packets8],
        };
        for &batch in modes {
            let mut batched = scalar.clone();
            batched.paths = PathBatching::Batched;
            batched.accel.batch = batch;
            let image = render_ok(&scene, &batched);
            let what = format!("{name} on {} with {batch:?}", backend.name());
            assert!(image.film == reference.film, "{what}: the batched image differs");
            assert_eq!(image.stats, reference.stats, "{what}: ray counts");
        }
        if backend == BackendKind::Embree {
            // Embree's fast triangle test: its own image, the same batched and scalar.
            let mut fast = scalar.clone();
            fast.accel.intersection = Intersection::Fast;
            let reference = render_ok(&scene, &fast);
            fast.paths = PathBatching::Batched;
            let image = render_ok(&scene, &fast);
            let what = format!("{name} on embree with the fast triangle test");
            assert!(image.film == reference.film, "{what}: the batched image differs");
            assert_eq!(image.stats, reference.stats, "{what}: ray counts");
        }
    }
    counted
}

#[test]
fn bundled_scenes_render_the_same_batched_and_scalar() {
    let mut files: Vec<PathBuf> = std::fs::read_dir(repo_path("scenes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 8, "the bundled scenes: {files:?}");
    // A whole tile's batch (its pixels' paths advanced together) and cut ones beside it,
    // whatever the tile size.
    let (width, height) = (40.max(TILE_SIZE + 8), 30.max(TILE_SIZE));
    for file in files {
        let scene = embray::scene::load(&file).unwrap();
        let name = file.display().to_string();
        let counted = assert_batched_is_scalar(&name, &scene, width, height, 2);
        // The Cornell box is Lambertian throughout, and some of its points are near its
        // lamp: the comparison is not vacuous, for the lanes nor for the lights sampled
        // one lane at a time.
        if file.ends_with("cornell.toml") {
            assert!(counted.lanes > 1000, "the Cornell box's bounces in lanes: {counted:?}");
            assert!(counted.near_lights > 10, "lit one lane at a time: {counted:?}");
        }
    }
}

/// A plain Lambertian mesh with vertex normals takes the lanes' short way with its
/// interpolated normal (no bundled scene has one): a band of a sphere, its vertices shared
/// so that its computed normals bend, in the Cornell box.
#[test]
fn smooth_plain_meshes_render_the_same_batched_and_scalar() {
    let dir = std::env::temp_dir().join(format!("embray-smooth-band-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (rings, segments) = (6u32, 12u32);
    let mut obj = String::new();
    for ring in 1..rings {
        let theta = std::f64::consts::PI * f64::from(ring) / f64::from(rings);
        for segment in 0..segments {
            let phi = std::f64::consts::TAU * f64::from(segment) / f64::from(segments);
            let (x, y, z) = (theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin());
            obj +=
                &format!("v {} {} {}\n", 278.0 + 120.0 * x, 200.0 + 120.0 * y, 280.0 + 120.0 * z);
        }
    }
    for ring in 0..rings - 2 {
        for segment in 0..segments {
            let at = |r: u32, s: u32| r * segments + s % segments + 1;
            let (a, b) = (at(ring, segment), at(ring, segment + 1));
            let (c, d) = (at(ring + 1, segment), at(ring + 1, segment + 1));
            obj += &format!("f {a} {b} {c}\nf {b} {d} {c}\n");
        }
    }
    std::fs::write(dir.join("band.obj"), obj).unwrap();
    let cornell = std::fs::read_to_string(repo_path("scenes/cornell.toml")).unwrap();
    let band =
        "[[objects]]\ntype = \"mesh\"\nfile = \"band.obj\"\nmaterial = \"white\"\nsmooth = true\n";
    std::fs::write(dir.join("s.toml"), format!("{cornell}\n{band}")).unwrap();
    let scene = embray::scene::load(&dir.join("s.toml")).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let counted = assert_batched_is_scalar("a smooth band in the Cornell box", &scene, 24, 24, 2);
    assert!(counted.lanes > 500, "bounces in lanes: {counted:?}");
}

/// The scenes of every `.xml` file under `dir` (each camera's, for a course file).
fn xml_scenes(dir: &Path) -> Vec<(String, SceneDesc)> {
    let mut files = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(dir) = pending.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                pending.push(path);
            } else if path.extension().is_some_and(|e| e == "xml") {
                files.push(path);
            }
        }
    }
    files.sort();
    let mut scenes = Vec::new();
    for file in files {
        // The suite also holds scenes embray refuses by design (tests/mitsuba/suite.rs).
        let Ok((loaded, _)) = embray::scene::xml::load_with_warnings(&file, &[]) else { continue };
        for (i, camera) in loaded.into_iter().enumerate() {
            scenes.push((format!("{} camera {i}", file.display()), camera.scene));
        }
    }
    scenes
}

#[test]
#[cfg_attr(not(mitsuba_data), ignore = "needs Mitsuba's suite at ../shared/data/mitsuba")]
fn mitsuba_suite_scenes_render_the_same_batched_and_scalar() {
    let scenes = xml_scenes(&repo_path("../shared/data/mitsuba/tests/scenes"));
    assert!(scenes.len() >= 19, "the suite's scenes that load: {}", scenes.len());
    for (name, scene) in scenes {
        assert_batched_is_scalar(&name, &scene, 24, 18, 2);
    }
}

#[test]
#[cfg_attr(not(course_data), ignore = "needs the CENG795 packs at ../shared/data/ceng795")]
fn course_path_tracing_scenes_render_the_same_batched_and_scalar() {
    let scenes = xml_scenes(&repo_path("../shared/data/ceng795/2022/hw6/pathTracing/inputs"));
    assert!(scenes.len() >= 2, "the course's path-tracing boxes: {}", scenes.len());
    for (name, scene) in scenes {
        assert_batched_is_scalar(&name, &scene, 24, 18, 2);
    }
}
