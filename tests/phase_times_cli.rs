//! `--time-phases`: the time spent in each phase of the batched path tracer, printed with the
//! ray counters; a timed render makes the same image, byte for byte, as an untimed one.

mod common;

use common::command::{GOOD_SCENE, embray, temp_dir};

/// The seconds `table` gives for `phase` ("closest hits      0.012     37.5 %").
fn phase_seconds(table: &str, phase: &str) -> f64 {
    let line = table.lines().find(|l| l.starts_with(phase)).unwrap_or_else(|| panic!("{table}"));
    line[phase.len()..].split_whitespace().next().unwrap().parse().unwrap()
}

/// The render time the summary line says ("render 0.123 s").
fn render_seconds(stderr: &str) -> f64 {
    let at = stderr.find("render ").expect("a summary line") + "render ".len();
    stderr[at..].split_whitespace().next().unwrap().parse().unwrap()
}

#[test]
fn phases_are_timed_within_the_render_time_and_change_no_pixel() {
    let dir = temp_dir("time-phases");
    std::fs::write(dir.join("s.toml"), GOOD_SCENE).unwrap();
    let common = ["render", "s.toml", "--spp", "16", "--threads", "2", "--resolution", "48x36"];
    let timed = embray(&[&common[..], &["-o", "timed.exr", "--time-phases"]].concat(), &dir);
    let stdout = String::from_utf8_lossy(&timed.stdout);
    let stderr = String::from_utf8_lossy(&timed.stderr);
    assert!(timed.status.success(), "{stderr}");
    let phases = [
        "camera rays",
        "closest hits",
        "Sobol draws",
        "shading",
        "vector lanes",
        "lane outcomes",
        "shadow rays",
        "accumulate",
    ];
    let seconds: Vec<f64> = phases.iter().map(|p| phase_seconds(&stdout, p)).collect();
    assert!(seconds.iter().all(|&s| s >= 0.0), "{stdout}");
    assert!(seconds[1] > 0.0 && seconds[3] > 0.0, "rays were traced and shaded: {stdout}");
    // Each of the two threads times disjoint spans of the render: their sum is within twice
    // its wall time, up to the printed figures' rounding (5 ms at most).
    let total: f64 = seconds.iter().sum();
    assert!(total <= 2.0 * render_seconds(&stderr) + 0.005, "{stdout}\n{stderr}");
    assert!(stdout.contains("camera ") && stdout.contains("shadow "), "the ray counters too");

    let plain = embray(&[&common[..], &["-o", "plain.exr"]].concat(), &dir);
    assert!(plain.status.success(), "{}", String::from_utf8_lossy(&plain.stderr));
    assert!(!String::from_utf8_lossy(&plain.stdout).contains("closest hits"), "untimed");
    let read = |name: &str| std::fs::read(dir.join(name)).unwrap();
    assert!(read("timed.exr") == read("plain.exr"), "timing changed the image");
}

#[test]
fn renders_without_phases_say_so_and_parts_print_their_own() {
    let dir = temp_dir("time-phases-none");
    std::fs::write(dir.join("s.toml"), GOOD_SCENE).unwrap();
    let scalar =
        embray(&["render", "s.toml", "--spp", "2", "--paths", "scalar", "--time-phases"], &dir);
    let stdout = String::from_utf8_lossy(&scalar.stdout);
    assert!(scalar.status.success(), "{}", String::from_utf8_lossy(&scalar.stderr));
    assert!(stdout.contains("not timed") && !stdout.contains("closest hits"), "{stdout}");

    // A part prints its counters and phases as a whole render does (`--stats` too).
    for flag in ["--time-phases", "--stats"] {
        let args = ["render", "s.toml", "--part", "1/2", "--split", "samples", "-o", "p.exr", flag];
        let part = embray(&args, &dir);
        let stdout = String::from_utf8_lossy(&part.stdout);
        assert!(part.status.success(), "{}", String::from_utf8_lossy(&part.stderr));
        assert!(stdout.contains("camera ") && stdout.contains("shadow "), "{flag}: {stdout}");
        assert_eq!(stdout.contains("closest hits"), flag == "--time-phases", "{flag}: {stdout}");
        assert!(dir.join("p.exr").exists(), "{flag}: the part is written");
    }
}
