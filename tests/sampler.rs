//! The samplers: unbiased (each converges to the analytic answer), and the default
//! Owen-scrambled Sobol sampler converges faster than independent numbers.

mod common;

use common::build::*;
use common::*;
use embray::choice::Choice;
use embray::film::Film;
use embray::sampling::SamplerKind;
use embray::scene::SceneDesc;
use glam::{DAffine3, DVec3};

/// A white-ish floor under a 4×2 emitter 1.5 above it, seen through a very narrow camera
/// aimed at the point below the emitter's centre (every pixel sees about that point).
fn quad_light_scene() -> (SceneDesc, f64) {
    let mut s = scene(camera([0.0, 1.0, 0.0], [0.0, 0.0, 0.0], 0.01, 8, 8));
    s.camera.up = DVec3::Z;
    s.settings.max_depth = 1;
    let (albedo, radiance) = (0.6f32, 2.0f32);
    add_floor(&mut s, albedo, 50.0);
    add_ceiling_light(&mut s, [-2.0, -1.0], [4.0, 2.0], 1.5, radiance);
    // Irradiance E = π L F; the floor's radiance ρ E / π = ρ L F.
    let form_factor = 4.0 * corner_form_factor(2.0, 1.0, 1.5);
    (s, (albedo * radiance) as f64 * form_factor)
}

#[test]
fn every_sampler_matches_the_analytic_form_factor() {
    let (scene, expected) = quad_light_scene();
    for &sampler in SamplerKind::ALL {
        let mut o = options(&scene, backends()[0], 1024);
        o.sampler = sampler;
        let m = film_mean(&render_ok(&scene, &o).film);
        let error = (m.x as f64 / expected - 1.0).abs();
        println!("{sampler}: {} against {expected:.6} ({:.3} %)", m.x, 100.0 * error);
        assert!(error < 0.005, "{sampler}: {m} vs {expected}");
    }
}

/// Soft shadows: a sphere between a large square light and the floor.
fn soft_shadow_scene() -> SceneDesc {
    let mut s = scene(camera([0.0, 4.0, 6.0], [0.0, 0.0, 0.0], 40.0, 24, 24));
    s.settings.max_depth = 1;
    let floor = add_floor(&mut s, 0.7, 20.0);
    add_ceiling_light(&mut s, [-2.0, -2.0], [4.0, 4.0], 3.0, 3.0);
    s.objects.push(object(
        "ball",
        sphere(0.7),
        floor,
        DAffine3::from_translation(DVec3::new(0.0, 1.0, 0.0)),
    ));
    s
}

fn rmse(a: &Film, b: &Film) -> f64 {
    let sum: f64 =
        a.color.iter().zip(&b.color).map(|(x, y)| (*x - *y).length_squared() as f64).sum();
    (sum / a.color.len() as f64).sqrt()
}

/// At 64 spp the Sobol sampler's RMSE is at least 2× lower than with independent numbers
/// (measured: 2.46×). The quad light is one emitter sampled by solid angle, so the light
/// point's Sobol pair stays stratified over the whole light.
#[test]
fn sobol_converges_faster_than_independent_numbers() {
    let scene = soft_shadow_scene();
    let backend = backends()[0];
    let mut reference_options = options(&scene, backend, 8192);
    reference_options.sampler = SamplerKind::Stratified;
    reference_options.seed = 99;
    let reference = render_ok(&scene, &reference_options).film;
    let error_of = |sampler: SamplerKind| {
        let mut o = options(&scene, backend, 64);
        o.sampler = sampler;
        rmse(&render_ok(&scene, &o).film, &reference)
    };
    let (sobol, stratified, independent) = (
        error_of(SamplerKind::Sobol),
        error_of(SamplerKind::Stratified),
        error_of(SamplerKind::Independent),
    );
    println!(
        "RMSE at 64 spp: sobol {sobol:.5}, stratified {stratified:.5}, independent {independent:.5} \
         (independent / sobol = {:.2})",
        independent / sobol
    );
    assert!(independent / sobol >= 2.0, "sobol {sobol} vs independent {independent}");
}

#[test]
fn sobol_images_are_the_same_for_any_thread_count() {
    let scene = soft_shadow_scene();
    for backend in backends() {
        let mut o = options(&scene, backend, 16);
        o.threads = Some(1);
        let one = render_ok(&scene, &o).film;
        o.threads = Some(2);
        let two = render_ok(&scene, &o).film;
        assert_eq!(one, two, "{}", backend.name());
    }
}

/// A scene's `seed` and `jitter = false` are `--seed`'s and `--no-jitter`'s defaults, and
/// the flags override them: the same image, bit for bit, either way.
#[test]
fn a_scenes_seed_and_jitter_are_the_flags_defaults() {
    use common::command::{GOOD_SCENE, embray, temp_dir};
    let dir = temp_dir("scene-seed-jitter");
    let with_render = |lines: &str| {
        GOOD_SCENE.replace("[materials.white]", &format!("[render]\n{lines}\n[materials.white]"))
    };
    for (file, text) in [
        ("plain.toml", GOOD_SCENE.to_string()),
        ("seeded.toml", with_render("seed = 2")),
        ("centred.toml", with_render("jitter = false")),
    ] {
        std::fs::write(dir.join(file), text).unwrap();
    }
    let render = |name: &str, args: &[&str]| {
        let output = format!("{name}.exr");
        let out = embray(&[&["render", "-o", &output, "--quiet"], args].concat(), &dir);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        output
    };
    // The EXRs' headers name their scene files, so their pixels are compared.
    let same = |a: &str, b: &str| {
        let out = embray(&["compare", a, b], &dir);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        text.contains("RMSE 0.000000,") && text.contains("(largest difference 0.0000 %)")
    };
    let seed_2 = render("seed-2", &["plain.toml", "--seed", "2"]);
    assert!(same(&render("seeded", &["seeded.toml"]), &seed_2), "the scene's seed");
    let seed_1 = render("seed-1", &["plain.toml", "--seed", "1"]);
    assert!(same(&render("seeded-1", &["seeded.toml", "--seed", "1"]), &seed_1), "--seed wins");
    assert!(!same(&seed_1, &seed_2), "seeds 1 and 2 give the same image");
    let centred = render("centred", &["plain.toml", "--no-jitter"]);
    assert!(same(&render("centred-scene", &["centred.toml"]), &centred), "the scene's jitter");
    assert!(!same(&render("jittered", &["plain.toml"]), &centred), "--no-jitter changed nothing");
}
