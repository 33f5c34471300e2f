//! `embray tonemap` remakes a render's PNG from its EXR with any curve `render` offers (the
//! same bytes as the render's own PNG), and the photographic operator's options are refused
//! under another curve instead of changing nothing.

mod common;

use common::command::{GOOD_SCENE, embray, temp_dir};

#[test]
fn a_renders_png_is_remade_from_its_exr_with_the_same_curve() {
    let dir = temp_dir("tonemap-curves");
    std::fs::write(dir.join("scene.toml"), GOOD_SCENE).unwrap();
    for curve in ["aces", "reinhard", "photographic"] {
        let exr = format!("{curve}.exr");
        let args = ["render", "scene.toml", "-q", "--spp", "2", "--tonemap", curve, "-o", &exr];
        let out = embray(&args, &dir);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let remade = format!("{curve}-again.png");
        let out = embray(&["tonemap", &exr, "--tonemap", curve, "-o", &remade], &dir);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        assert_eq!(
            std::fs::read(dir.join(format!("{curve}.png"))).unwrap(),
            std::fs::read(dir.join(&remade)).unwrap(),
            "{curve}"
        );
    }
}

#[test]
fn photographic_options_under_another_curve_are_refused() {
    let dir = temp_dir("tonemap-options");
    std::fs::write(dir.join("scene.toml"), GOOD_SCENE).unwrap();
    let out = embray(&["render", "scene.toml", "-q", "--spp", "1", "--key", "0.5"], &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("--key sets the photographic operator, but the PNG's curve is aces"));
    assert!(!dir.join("scene.exr").exists(), "refused before rendering");
    let out = embray(&["render", "scene.toml", "-q", "--spp", "1", "-o", "x.exr"], &dir);
    assert!(out.status.success());
    let args = ["tonemap", "x.exr", "--tonemap", "reinhard", "--gamma", "1", "-o", "y.png"];
    let out = embray(&args, &dir);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--gamma sets the photographic"));
}
