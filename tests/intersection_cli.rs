//! `--intersection robust|fast`: reported in `--stats-json`, robust by default; Embree's
//! fast triangle test renders the image the robust one does up to rounding; other names are
//! refused with the choices listed.

mod common;

use common::command::{GOOD_SCENE, embray, temp_dir};

#[test]
fn fast_intersection_is_reported_and_renders_the_same_image_up_to_rounding() {
    let dir = temp_dir("intersection");
    std::fs::write(dir.join("scene.toml"), GOOD_SCENE).unwrap();
    let render = |extra: &[&str], name: &str| {
        let (exr, json) = (format!("{name}.exr"), format!("{name}.json"));
        let mut args = vec!["render", "scene.toml", "-q", "--spp", "4", "-o", &exr];
        args.extend(["--stats-json", &json]);
        args.extend(extra);
        let out = embray(&args, &dir);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let stats: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join(&json)).unwrap()).unwrap();
        let film = embray::bench::convergence::read_reference(&dir.join(&exr)).unwrap();
        (film.color, stats)
    };
    let (robust, robust_stats) = render(&[], "robust");
    let (fast, fast_stats) = render(&["--intersection", "fast"], "fast");
    assert_eq!(robust_stats["intersection"], "robust");
    assert_eq!(fast_stats["intersection"], "fast");
    // Same seed, same paths: a pixel can differ only where a hit point rounds otherwise and
    // a path goes another way from there, so the means agree far inside the noise.
    let mean =
        |pixels: &[glam::Vec3]| pixels.iter().copied().sum::<glam::Vec3>() / pixels.len() as f32;
    let (a, b) = (mean(&robust), mean(&fast));
    assert!(a.min_element() > 0.0, "a lit image: {a}");
    assert!(((b - a).abs() / a).max_element() < 1e-3, "robust {a} vs fast {b}");
    let out = embray(&["render", "scene.toml", "--intersection", "exact"], &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && stderr.contains("robust, fast"), "{stderr}");
}
