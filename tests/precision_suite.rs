//! The precision torture scenes: far from the origin `cameraworld` keeps every scene intact,
//! `world` does not; robust spawning never self-intersects where a fixed epsilon fails.

mod common;

use common::*;
use embray::bench::accuracy::{AccuracyOptions, default_scenes, run};
use embray::choice::Choice;
use embray::render_space::RenderSpace;
use embray::scene::{SceneDesc, load};
use embray::shading::spawn::SpawnMode;
use glam::DVec3;

fn torture_scenes() -> Vec<(String, SceneDesc)> {
    default_scenes()
        .into_iter()
        .filter(|p| p.to_string_lossy().contains("precision"))
        .map(|p| (p.file_stem().unwrap().to_string_lossy().into_owned(), load(&p).unwrap()))
        .collect()
}

#[test]
fn cameraworld_keeps_every_torture_scene_far_away_and_world_breaks_one() {
    let scenes = torture_scenes();
    assert!(scenes.len() >= 7);
    for backend in backends() {
        let mut world_failures = Vec::new();
        for (name, scene) in &scenes {
            let base = options(scene, backend, 2);
            let reference = render_ok(scene, &base).film;
            assert!(reference.color.iter().all(|c| c.is_finite()), "{name}: NaN at the origin");
            for offset in [1e6, 1e7] {
                let mut o = base.clone();
                o.offset = DVec3::splat(offset);
                let error = image_error(&render_ok(scene, &o).film, &reference);
                // Tolerance: relative MSE ≤ 1e-6 and no pixel off by more than 1 %.
                assert!(
                    error.relative_mse <= 1e-6
                        && error.fraction_off == 0.0
                        && error.non_finite == 0,
                    "{} {name} @ {offset:e} in cameraworld: {error:?}",
                    backend.name()
                );
            }
            let mut o = base.clone();
            o.offset = DVec3::splat(1e6);
            o.render_space = RenderSpace::World;
            let world = image_error(&render_ok(scene, &o).film, &reference);
            assert_eq!(world.non_finite, 0, "{name}: NaN in world space");
            if world.relative_mse > 1e-6 || world.fraction_off > 0.0 {
                world_failures.push(format!("{name} (rel. MSE {:.2e})", world.relative_mse));
            }
        }
        println!("{}: world space @ 1e6 fails on: {}", backend.name(), world_failures.join(", "));
        assert!(!world_failures.is_empty(), "the tolerance must be able to fail");
    }
}

#[test]
fn robust_spawning_never_self_intersects_and_epsilon_does() {
    let grazing = load(&repo_path("scenes/precision/grazing_plane.toml")).unwrap();
    let thin = load(&repo_path("scenes/precision/thin_walls.toml")).unwrap();
    for backend in backends() {
        let shadow = |scene: &SceneDesc, spawn: SpawnMode, offset: f64, space: RenderSpace| {
            let mut o = options(scene, backend, 2);
            o.spawn = spawn;
            o.offset = DVec3::splat(offset);
            o.render_space = space;
            render_ok(scene, &o).stats.shadow
        };
        for space in [RenderSpace::Cameraworld, RenderSpace::World] {
            let robust = shadow(&grazing, SpawnMode::Robust, 1e6, space);
            println!("{} robust {}: {robust:?}", backend.name(), space.name());
            assert!(robust.rays > 1000);
            assert_eq!(robust.hits, 0, "{} {}: self-intersections", backend.name(), space.name());
        }
        let acne = shadow(&grazing, SpawnMode::Epsilon(1e-4), 1e6, RenderSpace::World);
        let blocked = shadow(&thin, SpawnMode::Robust, 0.0, RenderSpace::Cameraworld).hits;
        let leaking = shadow(&thin, SpawnMode::Epsilon(1e-2), 0.0, RenderSpace::Cameraworld).hits;
        println!(
            "{}: epsilon 1e-4 self-shadows {} of {} shadow rays; thin walls block {blocked} \
             shadow rays with robust spawning, {leaking} with epsilon 1e-2",
            backend.name(),
            acne.hits,
            acne.rays
        );
        assert!(acne.hits > acne.rays / 10, "{}: epsilon should show acne", backend.name());
        assert!(
            blocked > 1000 && leaking < blocked / 10,
            "{}: epsilon should leak",
            backend.name()
        );
    }
}

#[test]
fn accuracy_report_runs_on_a_tiny_configuration() {
    let root = repo_path(".");
    let out = std::env::temp_dir().join(format!("embray-accuracy-{}", std::process::id()));
    let options = AccuracyOptions {
        scenes: vec![
            root.join("scenes/precision/thin_walls.toml"),
            root.join("scenes/cornell.toml"),
        ],
        offsets: vec![0.0, 1e6],
        backends: backends(),
        runs: 1,
        spp: 1,
        max_size: 16,
        threads: Some(2),
        out_dir: out.clone(),
        spawn_scenes: Some((
            root.join("scenes/precision/grazing_plane.toml"),
            root.join("scenes/precision/thin_walls.toml"),
        )),
        spawn_methods: vec![SpawnMode::Robust, SpawnMode::Epsilon(1e-2)],
    };
    let mut messages = 0;
    let report = run(&options, |_| messages += 1).unwrap();
    let rows = 2 * 2 * 3 * backends().len();
    assert_eq!(report.rows.len(), rows);
    assert!(messages >= rows);
    let csv = std::fs::read_to_string(out.join("report.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), rows + 1, "header + one line per configuration");
    let columns = lines[0].split(',').count();
    assert!(columns >= 15);
    for line in &lines[1..] {
        let fields: Vec<&str> = line.split(',').collect();
        assert_eq!(fields.len(), columns, "{line}");
        for field in &fields[4..] {
            field.parse::<f64>().unwrap_or_else(|_| panic!("not a number: {field} in {line}"));
        }
    }
    assert!(out.join("report.md").exists() && out.join("strip.png").exists());
    assert_eq!(report.spawn_rows.len(), 2 * backends().len());
    std::fs::remove_dir_all(&out).unwrap();
}
