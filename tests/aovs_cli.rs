//! AOVs in the EXR (`--aovs`): values against a scene whose answers are known (a plane's
//! albedo, normal and depth, an emitter's zero variance, coverage), the channel names, and a
//! split render's merge carrying the same AOVs byte for byte.

mod common;

use common::command::{embray, temp_dir};
use std::collections::HashMap;

/// A camera at the origin looking down −z at a grey-brown plane 2 units away that fills the
/// left half of the view, lit by a point light; an emitting quad in the top right, nothing
/// in the bottom right.
const SCENE: &str = r#"
[camera]
lookfrom = [0.0, 0.0, 0.0]
lookat = [0.0, 0.0, -1.0]
vfov = 60.0
resolution = [16, 16]

[materials.plane]
albedo = [0.5, 0.25, 0.125]

[materials.lamp]
albedo = [0.0, 0.0, 0.0]
emission = [3.0, 3.0, 3.0]

[[objects]]
type = "quad"
material = "plane"
corner = [-10.0, -10.0, -2.0]
u = [10.0, 0.0, 0.0]
v = [0.0, 20.0, 0.0]

[[objects]]
type = "quad"
material = "lamp"
corner = [0.0, 0.0, -2.0]
u = [10.0, 0.0, 0.0]
v = [0.0, 10.0, 0.0]

[[lights]]
type = "point"
position = [-1.0, 0.0, 0.0]
intensity = [2.0, 2.0, 2.0]
"#;

/// Every channel of the EXR at `path`, by name.
fn channels(path: &std::path::Path) -> HashMap<String, Vec<f32>> {
    let image = exr::prelude::read_all_flat_layers_from_file(path).unwrap();
    let layer = &image.layer_data[0];
    layer
        .channel_data
        .list
        .iter()
        .map(|c| (c.name.to_string(), c.sample_data.values_as_f32().collect()))
        .collect()
}

#[test]
fn aovs_have_the_values_of_a_known_scene() {
    let dir = temp_dir("aovs");
    std::fs::write(dir.join("s.toml"), SCENE).unwrap();
    let args = [
        "render",
        "s.toml",
        "--spp",
        "16",
        "-q",
        "--aovs",
        "depth,normal,albedo,variance,alpha",
        "-o",
        "a.exr",
    ];
    let out = embray(&args, &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let c = channels(&dir.join("a.exr"));
    let mut names: Vec<&str> = c.keys().map(String::as_str).collect();
    names.sort();
    assert_eq!(
        names,
        [
            "A",
            "B",
            "G",
            "N.X",
            "N.Y",
            "N.Z",
            "R",
            "Z",
            "albedo.B",
            "albedo.G",
            "albedo.R",
            "variance.B",
            "variance.G",
            "variance.R"
        ]
    );
    let at = |x: usize, y: usize| y * 16 + x;
    // The plane (left half, away from its edge): its albedo, its normal, depth 2 / cos θ.
    let plane = at(3, 8);
    assert_eq!(
        [c["albedo.R"][plane], c["albedo.G"][plane], c["albedo.B"][plane]],
        [0.5, 0.25, 0.125]
    );
    assert_eq!([c["N.X"][plane], c["N.Y"][plane], c["N.Z"][plane]], [0.0, 0.0, 1.0]);
    assert_eq!(c["A"][plane], 1.0);
    let cos = 1.0 / (1.0 + (5.0f32 / 16.0 * 2.0 * (30f32).to_radians().tan()).powi(2)).sqrt();
    assert!((c["Z"][plane] - 2.0 / cos).abs() < 0.05, "depth {}", c["Z"][plane]);
    // The emitter (top right): 3 from every sample, so no variance at all.
    let lamp = at(12, 3);
    assert_eq!(c["R"][lamp], 3.0);
    assert_eq!(c["variance.R"][lamp], 0.0);
    // The plane under the point light: each sample at another point of the pixel, of
    // another brightness.
    assert!(c["variance.G"][plane] > 0.0);
    // Nothing there (bottom right): no coverage, depth 0 (finite), no albedo.
    let empty = at(12, 12);
    assert_eq!((c["A"][empty], c["Z"][empty], c["albedo.R"][empty]), (0.0, 0.0, 0.0));
    // By default: R, G, B, Z and N as always; `none`: the beauty alone.
    let out = embray(&["render", "s.toml", "--spp", "1", "-q", "-o", "d.exr"], &dir);
    assert!(out.status.success());
    assert_eq!(channels(&dir.join("d.exr")).len(), 7);
    let out =
        embray(&["render", "s.toml", "--spp", "1", "-q", "--aovs", "none", "-o", "n.exr"], &dir);
    assert!(out.status.success());
    assert_eq!(channels(&dir.join("n.exr")).len(), 3);
}

#[test]
fn a_merged_split_render_has_the_same_aovs_byte_for_byte() {
    let dir = temp_dir("aovs-merge");
    std::fs::write(dir.join("s.toml"), SCENE).unwrap();
    let aovs = ["--aovs", "albedo,variance,alpha", "--spp", "6", "-q"];
    let run = |extra: &[&str]| {
        let mut args = vec!["render", "s.toml"];
        args.extend(aovs);
        args.extend(extra);
        let out = embray(&args, &dir);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    };
    run(&["-o", "whole.exr"]);
    run(&["--part", "0/2", "--split", "samples", "-o", "p0.exr"]);
    run(&["--part", "1/2", "--split", "samples", "-o", "p1.exr"]);
    let out = embray(&["merge", "p0.exr", "p1.exr", "-o", "merged.exr", "-q"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (whole, merged) = (
        std::fs::read(dir.join("whole.exr")).unwrap(),
        std::fs::read(dir.join("merged.exr")).unwrap(),
    );
    assert!(whole == merged, "the merged EXR differs from the whole render");
    assert!(channels(&dir.join("merged.exr")).contains_key("variance.R"));
}

#[test]
fn an_unknown_aov_is_refused() {
    let dir = temp_dir("aovs-refused");
    std::fs::write(dir.join("s.toml"), SCENE).unwrap();
    let out = embray(&["render", "s.toml", "--aovs", "albedo,motion"], &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("'motion' is not an AOV; the AOVs are depth, normal, albedo"),
        "{stderr}"
    );
}

/// The relative mean squared error of an EXR's RGB against a reference's, (x − r)² / (r² +
/// 0.01) per channel: an error measure the lamp's bright pixels do not swamp.
fn relative_mse(image: &std::path::Path, reference: &std::path::Path) -> f64 {
    let read = |p: &std::path::Path| embray::exr_rgb::read(&std::fs::read(p).unwrap()).unwrap().2;
    let (image, reference) = (read(image), read(reference));
    assert_eq!(image.len(), reference.len());
    let per_channel = image.iter().zip(&reference).flat_map(|(x, r)| {
        (0..3).map(move |c| ((x[c] - r[c]) as f64).powi(2) / ((r[c] as f64).powi(2) + 0.01))
    });
    per_channel.sum::<f64>() / (3 * image.len()) as f64
}

#[test]
#[cfg_attr(
    not(feature = "denoise"),
    ignore = "denoising is not built in: OIDN_DIR=$(bash scripts/oidn-runtime.sh) cargo test --features denoise"
)]
fn denoising_brings_a_noisy_render_closer_to_the_reference() {
    let dir = temp_dir("denoise");
    let cornell = common::repo_path("scenes/cornell.toml");
    let cornell = cornell.to_str().unwrap();
    let render = |spp: &str, out: &str, extra: &[&str]| {
        let mut args = vec!["render", cornell, "--resolution", "64x64", "--spp", spp, "-o", out];
        args.extend(extra);
        let result = embray(&args, &dir);
        assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
        String::from_utf8_lossy(&result.stderr).into_owned()
    };
    render("512", "reference.exr", &["-q"]);
    let said = render("4", "noisy.exr", &["--denoise"]);
    assert!(said.contains("noisy.denoised.exr") && said.contains("denoised in"), "{said}");
    assert!(dir.join("noisy.denoised.png").is_file());
    let noisy = relative_mse(&dir.join("noisy.exr"), &dir.join("reference.exr"));
    let denoised = relative_mse(&dir.join("noisy.denoised.exr"), &dir.join("reference.exr"));
    println!("relative MSE against 512 spp: noisy {noisy:.4}, denoised {denoised:.4}");
    assert!(denoised < 0.25 * noisy, "noisy {noisy}, denoised {denoised}");
    // A render that fits in 2 GB but whose denoising would not (2000² pixels: about 1.2 GB
    // to render, 2 GB more to denoise) is refused before anything is rendered.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_embray"))
        .args(["render", cornell, "--resolution", "2000x2000", "--denoise", "-o", "big.exr"])
        .env("EMBRAY_MAX_MEMORY", "2000000000")
        .current_dir(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("denoising") && stderr.contains("MiB available"), "{stderr}");
    assert!(!dir.join("big.exr").exists() && !dir.join("big.denoised.exr").exists());
}

#[test]
#[cfg(not(feature = "denoise"))]
fn denoise_without_the_denoiser_is_refused_before_rendering() {
    let dir = temp_dir("no-denoise");
    let cornell = common::repo_path("scenes/cornell.toml");
    let out = embray(&["render", cornell.to_str().unwrap(), "--denoise", "-o", "x.exr"], &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("not built into") && stderr.contains("--features denoise"), "{stderr}");
    assert!(!dir.join("x.exr").exists() && !dir.join("x.denoised.exr").exists());
}

/// A Mitsuba scene's `aov` integrator chooses the EXR's AOVs (its nested integrator renders
/// the image; an AOV embray does not write is named in a warning); `--aovs` overrides it.
#[test]
fn a_mitsuba_aov_integrator_chooses_the_aovs() {
    let dir = temp_dir("aovs-mitsuba");
    let scene = r#"<scene version="3.0.0">
    <integrator type="aov">
        <string name="aovs" value="dd.y:depth, alb:albedo, nn:sh_normal, pp:position"/>
        <integrator type="path"><integer name="max_depth" value="3"/></integrator>
    </integrator>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
    </sensor>
    <shape type="sphere"><point name="center" x="0" y="0" z="4"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.6, 0.9"/></bsdf></shape>
    <emitter type="constant"/>
</scene>"#;
    std::fs::write(dir.join("s.xml"), scene).unwrap();
    let out = embray(&["render", "s.xml", "--spp", "4", "-o", "a.exr"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("the AOVs position are not written"), "{stderr}");
    let c = channels(&dir.join("a.exr"));
    let mut names: Vec<&str> = c.keys().map(String::as_str).collect();
    names.sort();
    assert_eq!(
        names,
        ["B", "G", "N.X", "N.Y", "N.Z", "R", "Z", "albedo.B", "albedo.G", "albedo.R"]
    );
    let centre = 4 * 8 + 4;
    assert_eq!(
        [c["albedo.R"][centre], c["albedo.G"][centre], c["albedo.B"][centre]],
        [0.3, 0.6, 0.9]
    );
    let out =
        embray(&["render", "s.xml", "--spp", "1", "-q", "--aovs", "none", "-o", "b.exr"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let mut names: Vec<String> = channels(&dir.join("b.exr")).into_keys().collect();
    names.sort();
    assert_eq!(names, ["B", "G", "R"]);
}
