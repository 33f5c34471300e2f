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
