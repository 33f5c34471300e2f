//! Progressive renders: Ctrl-C, SIGTERM and `--time-limit` write a complete image of the
//! passes done (the spp reached said on the console), `--checkpoint-every` writes the image
//! while rendering, progress lines go into pipes, and a render that runs to its end is the
//! same, byte for byte, with or without these.

mod common;

use common::command::{GOOD_SCENE, embray, temp_dir};
use std::process::{Command, Stdio};
use std::time::Duration;

/// Starts `embray render s.toml --spp 1000000 -o out.exr` in `dir`, lets it render for a
/// while, sends `signal`, and returns the exit code and standard error.
fn interrupted(dir: &std::path::Path, signal: i32) -> (Option<i32>, String) {
    interrupted_after(dir, signal, Duration::from_millis(1500))
}

/// `interrupted`, the signal sent after `wait`.
fn interrupted_after(dir: &std::path::Path, signal: i32, wait: Duration) -> (Option<i32>, String) {
    let child = Command::new(env!("CARGO_BIN_EXE_embray"))
        .args(["render", "s.toml", "--spp", "1000000", "-o", "out.exr"])
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Passes of 1, 1, 2, 4, … spp of 192 pixels: many are done within a second.
    std::thread::sleep(wait);
    // SAFETY: the pid is our own child, still running (it renders a million spp).
    assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, signal) }, 0);
    let out = child.wait_with_output().unwrap();
    (out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// The spp the summary line says were done ("… @ 37 of 1000000 spp, …").
fn spp_done(stderr: &str) -> u32 {
    let at = stderr.find(" of 1000000 spp").expect("the spp reached is said");
    stderr[..at].rsplit(' ').next().unwrap().parse().unwrap()
}

/// The `embray` text attribute of the EXR at `path` (how the image was made).
fn embray_attribute(path: &std::path::Path) -> String {
    let meta = exr::meta::MetaData::read_from_file(path, false).unwrap();
    let value = meta.headers[0].own_attributes.other.get(&exr::prelude::Text::from("embray"));
    match value {
        Some(exr::meta::attribute::AttributeValue::Text(text)) => text.to_string(),
        other => panic!("no embray attribute: {other:?}"),
    }
}

#[test]
fn ctrl_c_and_sigterm_write_the_passes_done() {
    for (signal, name, code) in [(libc::SIGINT, "Ctrl-C", 130), (libc::SIGTERM, "SIGTERM", 143)] {
        let dir = temp_dir(&format!("interrupt-{signal}"));
        std::fs::write(dir.join("s.toml"), GOOD_SCENE).unwrap();
        let (exit, stderr) = interrupted(&dir, signal);
        assert_eq!(exit, Some(code), "{stderr}");
        assert!(stderr.contains(&format!("interrupted ({name})")), "{stderr}");
        let done = spp_done(&stderr);
        assert!((2..1_000_000).contains(&done), "{stderr}");
        // An image of the passes done: the sphere lit, no NaN.
        let film = embray::bench::convergence::read_reference(&dir.join("out.exr")).unwrap();
        assert!(film.color.iter().all(|c| c.is_finite()));
        assert!(film.color.iter().any(|c| c.max_element() > 0.1));
        assert!(dir.join("out.png").exists());
        // The EXR says how far it got, and why it stopped.
        let said = embray_attribute(&dir.join("out.exr"));
        for line in [
            format!("spp: {done}\n"),
            "spp_requested: 1000000\n".into(),
            format!("stopped: interrupted ({name})\n"),
        ] {
            assert!(said.contains(&line), "{line:?} not in {said}");
        }
    }
}

#[test]
fn a_time_limit_writes_the_passes_done_and_succeeds() {
    let dir = temp_dir("time-limit");
    std::fs::write(dir.join("s.toml"), GOOD_SCENE).unwrap();
    let args = [
        "render",
        "s.toml",
        "--spp",
        "1000000",
        "--time-limit",
        "1.5",
        "--checkpoint-every",
        "0.3",
        "-o",
        "out.exr",
    ];
    let out = embray(&args, &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("--time-limit reached"), "{stderr}");
    assert!(stderr.contains("checkpoint: "), "checkpoints while rendering: {stderr}");
    assert!(spp_done(&stderr) >= 2, "{stderr}");
    embray::bench::convergence::read_reference(&dir.join("out.exr")).unwrap();
}

/// Passes add exact sums: a render that runs to the end is the image it was before passes,
/// limits and checkpoints or not.
#[test]
fn a_render_that_ends_is_the_same_with_a_limit_and_checkpoints() {
    let dir = temp_dir("progressive-same");
    std::fs::write(dir.join("s.toml"), GOOD_SCENE).unwrap();
    let plain = ["render", "s.toml", "--spp", "40", "-q", "-o", "a.exr"];
    assert!(embray(&plain, &dir).status.success());
    let limited = [
        "render",
        "s.toml",
        "--spp",
        "40",
        "-q",
        "-o",
        "b.exr",
        "--time-limit",
        "1000",
        "--checkpoint-every",
        "1000",
    ];
    assert!(embray(&limited, &dir).status.success());
    assert_eq!(
        std::fs::read(dir.join("a.exr")).unwrap(),
        std::fs::read(dir.join("b.exr")).unwrap()
    );
}

#[test]
fn progress_lines_go_into_a_pipe() {
    let dir = temp_dir("progress-pipe");
    std::fs::write(dir.join("s.toml"), GOOD_SCENE).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_embray"))
        .args(["render", "s.toml", "--spp", "64", "-o", "out.exr"])
        .env("EMBRAY_PROGRESS_SECONDS", "0")
        .current_dir(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let line = stderr.lines().find(|l| l.starts_with("rendering:")).expect("a progress line");
    for part in [" % (about ", " of 64 spp), ", " M rays/s, ", " s left"] {
        assert!(line.contains(part), "{line}");
    }
}

#[test]
fn limits_and_checkpoints_are_refused_for_parts_and_bad_values() {
    let dir = temp_dir("progressive-refused");
    std::fs::write(dir.join("s.toml"), GOOD_SCENE).unwrap();
    let cases: [(&[&str], &str); 3] = [
        (&["--part", "0/2", "--time-limit", "5"], "--time-limit cannot be used with --part"),
        (&["--time-limit", "0"], "--time-limit is 0, but must be a number of seconds > 0"),
        (&["--checkpoint-every", "nan"], "--checkpoint-every is NaN"),
    ];
    common::command::assert_render_refusals(&dir, &cases);
}

/// A signal before the first tile (here while 2,000 rough plastics' coating tables are
/// integrated: 15 ms each on one core) quits at once, with 128 + its number: there is no
/// image to keep yet. (It used to wait for the tables and the acceleration structure, then
/// stop with nothing to write.)
#[test]
fn a_signal_while_the_scene_is_prepared_quits_at_once() {
    let dir = temp_dir("interrupt-preparing");
    let mut scene = GOOD_SCENE.to_owned();
    for i in 0..2000 {
        let roughness = 0.1 + i as f64 * 1e-5;
        let z = 2.0 + i as f64 * 1e-4;
        scene += &format!(
            "[materials.p{i}]\ntype = \"plastic\"\nroughness = {roughness}\n\
             [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, {z}]\nradius = 0.01\n\
             material = \"p{i}\"\n"
        );
    }
    std::fs::write(dir.join("s.toml"), scene).unwrap();
    let started = std::time::Instant::now();
    let (exit, stderr) = interrupted_after(&dir, libc::SIGINT, Duration::from_millis(300));
    let took = started.elapsed();
    assert_eq!(exit, Some(130), "{stderr}");
    assert!(!stderr.contains("stopping:"), "{stderr}");
    assert!(!dir.join("out.exr").exists() && !dir.join("out.png").exists());
    // The tables alone take 15 s of one core's time.
    assert!(took < Duration::from_secs(5), "quit after {took:?}: {stderr}");
}
