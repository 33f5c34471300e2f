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
