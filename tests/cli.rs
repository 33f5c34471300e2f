//! The `embray` command as a user runs it: good renders write both images; bad input gives a
//! clear message, a non-zero exit, no panic and no output file.

mod common;

use common::command::{GOOD_SCENE, embray, temp_dir};
use std::process::Command;

/// Writes `scene` (and extra files) into a fresh folder, renders it, and checks that the
/// command failed cleanly with a message containing every one of `expected`.
fn assert_rejected(
    name: &str,
    scene: Option<&str>,
    extra: &[(&str, &str)],
    args: &[&str],
    expected: &[&str],
) {
    let dir = temp_dir(name);
    if let Some(text) = scene {
        std::fs::write(dir.join("scene.toml"), text).unwrap();
    }
    for (file, text) in extra {
        std::fs::write(dir.join(file), text).unwrap();
    }
    let mut all_args = vec!["render", "scene.toml", "-o", "out.exr", "--quiet"];
    all_args.extend_from_slice(args);
    let out = embray(&all_args, &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{name}: should fail; stderr: {stderr}");
    assert!(!stderr.contains("panicked"), "{name}: panicked: {stderr}");
    for needle in expected {
        assert!(stderr.contains(needle), "{name}: message lacks '{needle}': {stderr}");
    }
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("out"))
        .collect();
    assert!(leftovers.is_empty(), "{name}: output written despite the error: {leftovers:?}");
}

#[test]
fn render_writes_exr_and_png() {
    let dir = temp_dir("good");
    std::fs::write(dir.join("scene.toml"), GOOD_SCENE).unwrap();
    let out = embray(&["render", "scene.toml", "-o", "img.exr", "--spp", "2", "--stats"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(dir.join("img.exr").metadata().unwrap().len() > 0);
    let png = image::open(dir.join("img.png")).unwrap().to_rgb8();
    assert_eq!(png.dimensions(), (16, 12));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("camera") && stdout.contains("shadow"), "stats table: {stdout}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("Mrays/s"), "summary line: {stderr}");
}

#[test]
fn build_options_are_reported_and_keep_the_image() {
    let dir = temp_dir("build-options");
    std::fs::write(dir.join("scene.toml"), GOOD_SCENE).unwrap();
    let base = ["render", "scene.toml", "--spp", "2", "--quiet"];
    let render = |extra: &[&str], name: &str| {
        let exr = format!("{name}.exr");
        let json = format!("{name}.json");
        let mut args = base.to_vec();
        args.extend_from_slice(&["-o", &exr, "--stats-json", &json]);
        args.extend_from_slice(extra);
        let out = embray(&args, &dir);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let stats: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join(&json)).unwrap()).unwrap();
        (image::open(dir.join(format!("{name}.png"))).unwrap().to_rgb8(), stats)
    };
    let (default_png, default_stats) = render(&[], "default");
    assert_eq!(default_stats["build_quality"], "medium");
    assert_eq!(default_stats["batch"], "native");
    assert_eq!(default_stats["compact"], false);
    let options = [
        ["--build-quality", "low", "--batch", "single", "--compact"].as_slice(),
        ["--build-quality", "high", "--batch", "packets16"].as_slice(),
    ];
    for (i, extra) in options.iter().enumerate() {
        let (png, stats) = render(extra, &format!("options{i}"));
        assert_eq!(stats["build_quality"], extra[1], "{stats}");
        assert_eq!(stats["batch"], extra[3], "{stats}");
        assert!(png == default_png, "{extra:?} changed the image");
    }
    let out = embray(&["render", "scene.toml", "--build-quality", "best"], &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && stderr.contains("low, medium, high"), "{stderr}");
}

/// The files in `dir`, sorted, leaving out the scene.
fn written(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != "scene.toml")
        .collect();
    names.sort();
    names
}

/// `-o` writes the format its extension names and nothing else beside a display image;
/// `--png` alone writes only that image; with neither, the images are named after the scene.
#[test]
fn outputs_follow_their_extensions_and_the_scene_name() {
    let dir = temp_dir("formats");
    std::fs::write(dir.join("scene.toml"), GOOD_SCENE).unwrap();
    let render = |args: &[&str]| {
        let all = [&["render", "scene.toml", "--spp", "1", "-q"][..], args].concat();
        let out = embray(&all, &dir);
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        let names = written(&dir);
        for name in &names {
            std::fs::remove_file(dir.join(name)).unwrap();
        }
        names
    };
    assert_eq!(render(&[]), ["scene.exr", "scene.png"]);
    assert_eq!(render(&["-o", "a.exr"]), ["a.exr", "a.png"]);
    assert_eq!(render(&["--png", "only.png"]), ["only.png"]);
    std::fs::write(dir.join("scene.toml"), GOOD_SCENE).unwrap();
    let out = embray(&["render", "scene.toml", "--spp", "1", "-q", "-o", "view.png"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let png = image::open(dir.join("view.png")).unwrap();
    assert_eq!(
        image::ImageFormat::from_path(dir.join("view.png")).unwrap(),
        image::ImageFormat::Png
    );
    assert_eq!((png.width(), png.height()), (16, 12));
    let out = embray(&["render", "scene.toml", "--spp", "1", "-q", "-o", "view.JPG"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let bytes = std::fs::read(dir.join("view.JPG")).unwrap();
    assert_eq!(bytes[..3], [0xFF, 0xD8, 0xFF], "a JPEG's signature");
    let jpeg = image::load_from_memory_with_format(&bytes, image::ImageFormat::Jpeg).unwrap();
    // The JPEG is the PNG's pixels, give or take compression.
    let (a, b) = (png.to_rgb8(), jpeg.to_rgb8());
    let mean_difference =
        a.pixels().zip(b.pixels()).map(|(p, q)| p[1].abs_diff(q[1]) as f64).sum::<f64>()
            / (16.0 * 12.0);
    assert!(mean_difference < 4.0, "{mean_difference}");
    assert_eq!(written(&dir), ["view.JPG", "view.png"]);
}

#[test]
fn an_output_extension_that_names_no_format_is_refused() {
    let dir = temp_dir("bad-extension");
    std::fs::write(dir.join("scene.toml"), GOOD_SCENE).unwrap();
    let refuse = |args: &[&str], expected: &[&str]| {
        let out = embray(&[&["render", "scene.toml", "-q"][..], args].concat(), &dir);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
        for needle in expected {
            assert!(stderr.contains(needle), "{args:?}: message lacks '{needle}': {stderr}");
        }
        assert_eq!(written(&dir), Vec::<String>::new(), "{args:?}: files written");
    };
    refuse(&["-o", "out.tif"], &["-o 'out.tif'", "'.tif'", ".exr, .png, .jpg or .jpeg"]);
    refuse(&["-o", "out"], &["-o 'out' has no extension"]);
    refuse(&["-o", "out.png", "--png", "out2.png"], &["-o 'out.png' is the display image already"]);
    refuse(&["--png", "out.exr"], &["--png 'out.exr' names an EXR"]);
}

#[test]
fn render_without_a_scene_draws_the_default_cornell_box() {
    let dir = temp_dir("default");
    let out = embray(&["render", "--spp", "16", "--quiet", "-o", "cornell.exr"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let png = image::open(dir.join("cornell.png")).unwrap().to_rgb8();
    assert_eq!(png.dimensions(), (256, 256));
    // The left wall is red, the right wall green.
    let left = png.get_pixel(20, 128);
    let right = png.get_pixel(235, 128);
    assert!(
        left[0] > 2 * left[1] && right[1] as u32 * 2 > right[0] as u32 * 3,
        "{left:?} {right:?}"
    );
}

#[test]
fn missing_scene_is_a_clear_error() {
    assert_rejected("missing", None, &[], &[], &["scene.toml", "No such file"]);
}

#[test]
fn toml_syntax_error_names_the_line() {
    let broken = GOOD_SCENE.replace("vfov = 40.0", "vfov = = 40.0");
    assert_rejected("syntax", Some(&broken), &[], &[], &["scene.toml", "line 5"]);
}

#[test]
fn unknown_key_is_rejected() {
    let text = GOOD_SCENE.replace("vfov = 40.0", "vfov = 40.0\nfocal_lenght = 3.0");
    assert_rejected("unknown-key", Some(&text), &[], &[], &["scene.toml", "focal_lenght"]);
}

#[test]
fn nan_and_infinite_numbers_are_rejected() {
    let nan = GOOD_SCENE.replace("lookfrom = [0.0, 1.0, 4.0]", "lookfrom = [0.0, nan, 4.0]");
    assert_rejected("nan", Some(&nan), &[], &[], &["scene.toml", "lookfrom", "NaN"]);
    let inf = GOOD_SCENE.replace("radius = 1.0", "radius = inf");
    assert_rejected("inf", Some(&inf), &[], &[], &["scene.toml", "radius", "inf"]);
}

#[test]
fn zero_resolution_or_spp_is_rejected() {
    let zero_res = GOOD_SCENE.replace("resolution = [16, 12]", "resolution = [0, 12]");
    assert_rejected("zero-res", Some(&zero_res), &[], &[], &["scene.toml", "resolution"]);
    let zero_spp = format!("{GOOD_SCENE}\n[render]\nspp = 0\n");
    assert_rejected("zero-spp-file", Some(&zero_spp), &[], &[], &["scene.toml", "spp"]);
    assert_rejected("zero-spp-flag", Some(GOOD_SCENE), &[], &["--spp", "0"], &["--spp"]);
}

#[test]
fn missing_obj_is_rejected() {
    let text = format!(
        "{GOOD_SCENE}\n[[objects]]\ntype = \"mesh\"\nfile = \"nothere.obj\"\nmaterial = \"white\"\n"
    );
    assert_rejected("missing-obj", Some(&text), &[], &[], &["nothere.obj"]);
}

#[test]
fn obj_with_out_of_range_indices_is_rejected() {
    let text = format!(
        "{GOOD_SCENE}\n[[objects]]\ntype = \"mesh\"\nfile = \"bad.obj\"\nmaterial = \"white\"\n"
    );
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";
    assert_rejected("bad-obj", Some(&text), &[("bad.obj", obj)], &[], &["bad.obj"]);
}

#[test]
fn degenerate_camera_is_rejected() {
    let text = GOOD_SCENE.replace("lookat = [0.0, 0.0, 0.0]", "lookat = [0.0, 1.0, 4.0]");
    assert_rejected("camera", Some(&text), &[], &[], &["scene.toml", "lookfrom", "lookat"]);
}

#[test]
fn unwritable_output_is_an_error_not_a_panic() {
    let dir = temp_dir("unwritable");
    std::fs::write(dir.join("scene.toml"), GOOD_SCENE).unwrap();
    let out =
        embray(&["render", "scene.toml", "-o", "no/such/dir/x.exr", "--quiet", "--spp", "1"], &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && stderr.contains("x.exr") && !stderr.contains("panicked"),
        "{stderr}"
    );
}

/// A full disk or a closed pipe on standard output is an error with a message, not a panic;
/// an unwritable standard error changes nothing (the images are written, exit 0).
#[test]
fn unwritable_terminal_streams_are_errors_not_panics() {
    let dir = temp_dir("streams");
    let full = || std::fs::OpenOptions::new().write(true).open("/dev/full").expect("/dev/full");
    let out = Command::new(env!("CARGO_BIN_EXE_embray"))
        .arg("info")
        .current_dir(&dir)
        .stdout(full())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("cannot write to standard output"), "{stderr}");
    // The reader is gone before embray starts, so its first write fails whatever the timing.
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = Command::new(env!("CARGO_BIN_EXE_embray"))
        .args(["info"])
        .current_dir(&dir)
        .stdout(writer)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("cannot write to standard output"), "{stderr}");
    let out = Command::new(env!("CARGO_BIN_EXE_embray"))
        .args(["render", "--spp", "1", "-o", "x.exr"])
        .current_dir(&dir)
        .stderr(full())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert!(dir.join("x.exr").exists() && dir.join("x.png").exists());
}

/// `embray tonemap` maps a render's EXR to a PNG with the photographic operator; `render
/// --tonemap photographic` writes the same PNG; bad parameters and a missing or same-path
/// file are clear errors that write nothing.
#[test]
fn tonemap_maps_an_exr_like_render_does() {
    let dir = temp_dir("tonemap");
    std::fs::write(dir.join("scene.toml"), GOOD_SCENE).unwrap();
    let args = ["render", "scene.toml", "-o", "a.exr", "--tonemap", "photographic", "--key", "0.3"];
    let out = embray(&[&args[..], &["--quiet"]].concat(), &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let out = embray(&["tonemap", "a.exr", "-o", "b.png", "--key", "0.3"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (a, b) =
        (std::fs::read(dir.join("a.png")).unwrap(), std::fs::read(dir.join("b.png")).unwrap());
    assert_eq!(a, b, "render's PNG and tonemap's differ");
    for (args, needle) in [
        (&["tonemap", "a.exr", "-o", "c.png", "--key", "0"][..], "the key must be > 0"),
        (&["tonemap", "a.exr", "-o", "c.png", "--burn-out", "100"][..], "burn-out"),
        (&["tonemap", "nothing.exr", "-o", "c.png"][..], "nothing.exr"),
        (&["tonemap", "a.exr", "-o", "a.exr"][..], "a.exr"),
    ] {
        let out = embray(args, &dir);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && stderr.contains(needle), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert!(!dir.join("c.png").exists(), "{args:?} wrote c.png");
    }
    assert!(std::fs::metadata(dir.join("a.exr")).unwrap().len() > 0, "a.exr destroyed");
}

/// `embray compare` on two EXRs gives the linear figures: identical renders agree exactly,
/// renders with different seeds differ by a small RMSE; an EXR against a PNG, or a heat map
/// of EXRs, is refused with a clear message.
#[test]
fn compare_reads_two_exrs_linearly() {
    let dir = temp_dir("compare-exr");
    std::fs::write(dir.join("scene.toml"), GOOD_SCENE).unwrap();
    for (name, scene, seed) in [
        ("a", "scene.toml", Some("1")),
        ("b", "scene.toml", Some("1")),
        ("c", "scene.toml", Some("2")),
    ] {
        let output = format!("{name}.exr");
        let mut args = vec!["render", scene, "-o", &output, "--quiet"];
        args.extend(seed.map(|seed| ["--seed", seed]).iter().flatten());
        let out = embray(&args, &dir);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    }
    let same = embray(&["compare", "a.exr", "b.exr"], &dir);
    let text = String::from_utf8_lossy(&same.stdout);
    assert!(same.status.success(), "{}", String::from_utf8_lossy(&same.stderr));
    assert!(text.contains("16x12 linear") && text.contains("RMSE 0.000000,"), "{text}");
    assert!(text.contains("(largest difference 0.0000 %)"), "{text}");
    let other = embray(&["compare", "a.exr", "c.exr"], &dir);
    let text = String::from_utf8_lossy(&other.stdout);
    assert!(other.status.success() && !text.contains("RMSE 0.000000,"), "{text}");
    // An EXR whose header claims 100000² pixels is refused before anything is allocated.
    let mut huge = std::fs::read(dir.join("a.exr")).unwrap();
    for name in [&b"dataWindow\0box2i\0"[..], &b"displayWindow\0box2i\0"[..]] {
        let at = huge.windows(name.len()).position(|w| w == name).unwrap() + name.len() + 4;
        let corners = [0i32, 0, 99_999, 99_999].map(i32::to_le_bytes).concat();
        huge[at..at + 16].copy_from_slice(&corners);
    }
    std::fs::write(dir.join("huge.exr"), huge).unwrap();
    for (args, needle) in [
        (&["compare", "huge.exr", "a.exr"][..], "100000 × 100000 pixels"),
        (&["tonemap", "huge.exr", "-o", "h.png"][..], "100000 × 100000 pixels"),
        (&["compare", "a.exr", "a.png"][..], "compare an EXR with an EXR"),
        (&["compare", "a.exr", "b.exr", "--heatmap", "h.png"][..], "--heatmap is for 8-bit"),
        (&["compare", "a.exr", "missing.exr"][..], "missing.exr"),
    ] {
        let out = embray(args, &dir);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && stderr.contains(needle), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
    assert!(!dir.join("h.png").exists());
}

#[test]
fn a_black_image_is_said_not_silently_written() {
    let dir = temp_dir("black");
    // The quad light above the sphere emits along u × v = +y: away from it.
    let scene = "[camera]\nlookfrom = [0.0, 0.0, -5.0]\nlookat = [0.0, 0.0, 0.0]\nvfov = 40.0\n\
        resolution = [16, 16]\n[materials.white]\nalbedo = [0.8, 0.8, 0.8]\n[[objects]]\n\
        type = \"sphere\"\nmaterial = \"white\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\n\
        [[lights]]\ntype = \"quad\"\ncorner = [-1.0, 3.0, -1.0]\nu = [0.0, 0.0, 2.0]\n\
        v = [2.0, 0.0, 0.0]\nemission = [5.0, 5.0, 5.0]\n";
    std::fs::write(dir.join("away.toml"), scene).unwrap();
    let out = embray(&["render", "away.toml", "--spp", "2"], &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("warning: the image is black"), "{stderr}");
    let lit = scene.replace(
        "u = [0.0, 0.0, 2.0]\nv = [2.0, 0.0, 0.0]",
        "u = [2.0, 0.0, 0.0]\nv = [0.0, 0.0, 2.0]",
    );
    std::fs::write(dir.join("lit.toml"), lit).unwrap();
    let out = embray(&["render", "lit.toml", "--spp", "2"], &dir);
    assert!(!String::from_utf8_lossy(&out.stderr).contains("black"));
}
