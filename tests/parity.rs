//! Same scene, same seed: the Embree and obvhs backends give the same image and the same ray
//! counts, for every bundled scene.

mod common;

use common::*;
use embray::accel::BackendKind;
use embray::scene::{SceneDesc, load};

/// Every `scenes/*.toml`, at most 64 pixels on a side.
fn bundled_scenes() -> Vec<(String, SceneDesc)> {
    let mut scenes = Vec::new();
    let mut paths: Vec<_> = std::fs::read_dir(repo_path("scenes"))
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    paths.sort();
    for path in paths {
        let mut scene = load(&path).unwrap();
        let scale = 64.0 / scene.camera.width.max(scene.camera.height) as f64;
        if scale < 1.0 {
            scene.camera.width = ((scene.camera.width as f64 * scale).round() as u32).max(1);
            scene.camera.height = ((scene.camera.height as f64 * scale).round() as u32).max(1);
        }
        scenes.push((path.file_name().unwrap().to_string_lossy().into_owned(), scene));
    }
    scenes
}

fn within(a: u64, b: u64, fraction: f64) -> bool {
    (a as f64 - b as f64).abs() <= fraction * a.max(b) as f64
}

#[test]
fn every_bundled_scene_renders_alike_on_both_backends() {
    if backends().len() < 2 {
        eprintln!("skipped: only one backend compiled in");
        return;
    }
    let scenes = bundled_scenes();
    assert!(scenes.len() >= 2);
    for (name, scene) in scenes {
        let embree = render_ok(&scene, &options(&scene, BackendKind::Embree, 4));
        let obvhs = render_ok(&scene, &options(&scene, BackendKind::Obvhs, 4));
        let error = image_error(&obvhs.film, &embree.film);
        let (e, o) = (embree.stats, obvhs.stats);
        println!("{name}: {error:?}");
        println!("  embree {e:?}\n  obvhs  {o:?}");
        // Tolerance: the two backends use different triangle tests (Embree's own vs ours), so
        // a path may occasionally diverge at an edge; the images must otherwise be equal.
        assert!(error.relative_mse < 1e-4, "{name}: {error:?}");
        assert!(error.fraction_off < 0.01, "{name}: {error:?}");
        assert_eq!(error.non_finite, 0);
        assert_eq!(e.camera.rays, o.camera.rays, "{name}");
        for (kind, a, b) in [
            ("camera", e.camera, o.camera),
            ("shadow", e.shadow, o.shadow),
            ("indirect", e.indirect, o.indirect),
        ] {
            assert!(within(a.rays, b.rays, 1e-3), "{name} {kind} rays: {a:?} vs {b:?}");
            assert!(within(a.hits, b.hits, 1e-3), "{name} {kind} hits: {a:?} vs {b:?}");
        }
    }
}
