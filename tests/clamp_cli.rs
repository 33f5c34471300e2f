//! `--clamp L`: no sample brings more than L in any channel, so a box-filtered pixel never
//! exceeds L; without it the same render has brighter pixels; nonsense limits are refused.

mod common;

use common::command::{GOOD_SCENE, embray, temp_dir};

fn brightest(path: &std::path::Path) -> f32 {
    let film = embray::bench::convergence::read_reference(path).unwrap();
    film.color.iter().map(|c| c.max_element()).fold(0.0, f32::max)
}

#[test]
fn a_clamp_bounds_every_pixel_and_nonsense_is_refused() {
    let dir = temp_dir("clamp");
    std::fs::write(dir.join("scene.toml"), GOOD_SCENE).unwrap();
    let render = |extra: &[&str], out: &str| {
        let mut args = vec!["render", "scene.toml", "-q", "--spp", "4", "-o", out];
        args.extend(extra);
        embray(&args, &dir)
    };
    assert!(render(&[], "free.exr").status.success());
    let free = brightest(&dir.join("free.exr"));
    let limit = 0.5 * free;
    let clamped = render(&["--clamp", &limit.to_string()], "clamped.exr");
    assert!(clamped.status.success(), "{}", String::from_utf8_lossy(&clamped.stderr));
    let bright = brightest(&dir.join("clamped.exr"));
    assert!(bright <= limit * (1.0 + 1e-6) && bright > 0.0, "{bright} vs {limit} (free {free})");
    for bad in ["0", "-1", "inf", "NaN"] {
        let out = render(&["--clamp", bad], "bad.exr");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{bad}: {stderr}");
        assert!(stderr.contains("--clamp is"), "{bad}: {stderr}");
    }
}

/// A sample beyond what a pixel's exact sums hold (2⁵⁰) is added as that largest value, and
/// an image whose brightest pixel is below the sums' exact range (2⁻³²) has lost precision:
/// both are said, not left silent; `--clamp` keeps the first from happening.
#[test]
fn radiance_beyond_the_exact_sums_is_warned_about() {
    let dir = temp_dir("clamp-range");
    let scene = |emission: &str| {
        format!(
            "[camera]\nlookfrom = [0.0, 0.0, 3.0]\nlookat = [0.0, 0.0, 0.0]\nvfov = 40.0\n\
             resolution = [4, 4]\n[render]\nspp = 2\n[materials.light]\nalbedo = [0.0, 0.0, 0.0]\n\
             emission = [{emission}, {emission}, {emission}]\n[[objects]]\ntype = \"sphere\"\n\
             material = \"light\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\n"
        )
    };
    let warnings = |emission: &str, extra: &[&str]| {
        std::fs::write(dir.join("s.toml"), scene(emission)).unwrap();
        let mut args = vec!["render", "s.toml", "-o", "s.exr"];
        args.extend(extra);
        let out = embray(&args, &dir);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8_lossy(&out.stderr)
            .lines()
            .filter(|l| l.contains("warning"))
            .map(str::to_owned)
            .collect::<Vec<_>>()
    };
    let bright = warnings("1e20", &[]);
    assert!(bright.iter().any(|w| w.contains("samples were brighter than 1.126e15")), "{bright:?}");
    assert!(brightest(&dir.join("s.exr")) <= 1.126e15 * 1.001);
    assert_eq!(warnings("1e20", &["--clamp", "1e10"]), Vec::<String>::new());
    assert_eq!(warnings("1", &[]), Vec::<String>::new());
    let dim = warnings("1e-12", &[]);
    assert!(dim.iter().any(|w| w.contains("the brightest pixel is 1.000e-12")), "{dim:?}");
}
