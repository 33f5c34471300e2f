//! The process's surroundings: closed or full standard streams, signals while output
//! files are being written, a time limit that leaves cameras unrendered, and a render too
//! long to run at all.

use crate::harness::{Run, Scratch, refused_in, scene, xml_scene};
use std::process::Stdio;
use std::time::{Duration, Instant};

#[test]
fn info_into_a_full_disk_is_an_error_not_a_panic() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    let full = std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap();
    let output = scratch.command(&["info", "s.toml"]).stdout(full).output().unwrap();
    let run = Run::from(output);
    run.assert_no_panic();
    assert_eq!(run.code, Some(1));
    run.assert_says(&["cannot write to standard output"]);
}

#[test]
fn info_into_a_closed_pipe_is_an_error_not_a_panic() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    // The pipe's reader is gone before the child starts (as with `| true` once `true` has
    // exited), so its first write fails whatever the timing.
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let child = scratch
        .command(&["info", "s.toml"])
        .stdout(Stdio::from(writer))
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let run = Run::from(child.wait_with_output().unwrap());
    run.assert_no_panic();
    assert_eq!(run.code, Some(1), "{}", run.stderr);
}

#[test]
fn render_with_a_full_stderr_still_writes_its_images() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    let full = std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap();
    let output = scratch.command(&["render", "s.toml"]).stderr(full).output().unwrap();
    assert_eq!(output.status.code(), Some(0));
    assert!(scratch.path("s.exr").is_file() && scratch.path("s.png").is_file());
}

/// Starts a render whose PNG goes to a FIFO nobody reads: committing blocks on opening it
/// while the EXR waits under its temporary name. Returns once that file exists.
fn render_blocked_in_commit(scratch: &Scratch) -> std::process::Child {
    scratch.write("s.toml", scene(""));
    scratch.write("out.exr", "earlier exr");
    let fifo = scratch.path("pipe.png");
    assert!(std::process::Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let child = scratch
        .command(&["render", "s.toml", "-o", "out.exr", "--png", "pipe.png", "-q"])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !has_temp_file(scratch) {
        assert!(start.elapsed() < Duration::from_secs(60), "no temporary file appeared");
        std::thread::sleep(Duration::from_millis(20));
    }
    child
}

fn has_temp_file(scratch: &Scratch) -> bool {
    scratch.snapshot().keys().any(|p| p.to_string_lossy().ends_with(".tmp"))
}

fn interrupted_during_commit(signal: &str, code: i32) {
    let scratch = Scratch::new();
    let mut child = render_blocked_in_commit(&scratch);
    let pid = child.id().to_string();
    let kill = || {
        let status = std::process::Command::new("kill").args([signal, &pid]).status();
        assert!(status.unwrap().success());
    };
    kill();
    // The temporary EXR appears while the render still takes a first signal as a request
    // to stop and write its images (`Stop::watch`): a signal that lands before the commit
    // starts is followed by the commit blocking on the FIFO, which a second signal ends.
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(5) {
            kill();
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let run = Run::from(child.wait_with_output().unwrap());
    run.assert_no_panic();
    assert_eq!(run.code, Some(code), "{}", run.stderr);
    assert!(!has_temp_file(&scratch), "the temporary EXR was left behind");
    assert_eq!(std::fs::read_to_string(scratch.path("out.exr")).unwrap(), "earlier exr");
}

#[test]
fn sigterm_while_writing_removes_the_temporary_files() {
    interrupted_during_commit("-TERM", 143);
}

#[test]
fn sigint_while_writing_removes_the_temporary_files() {
    interrupted_during_commit("-INT", 130);
}

/// `xml_scene` with `names` as cameras, the first one given `first` (XML in its element).
fn cameras_scene(names: &[&str], first: &str) -> String {
    let resolution = "<ImageResolution>8 8</ImageResolution>";
    xml_scene(names, "").replacen(resolution, &format!("{resolution}{first}"), 1)
}

#[test]
fn a_time_limit_in_the_first_camera_names_the_cameras_it_skipped() {
    let scratch = Scratch::new();
    // 2²⁰ samples a pixel over 32² pixels: the limit stops the first camera after its
    // first passes (of 1 spp each), however fast the machine.
    let first = "<NumSamples>1048576</NumSamples>";
    let xml = cameras_scene(&["a.png", "b.png", "c.png"], first).replacen(
        "<ImageResolution>8 8<",
        "<ImageResolution>32 32<",
        1,
    );
    scratch.write("s.xml", xml);
    std::fs::create_dir(scratch.path("out")).unwrap();
    let args = ["render", "s.xml", "--out-dir", "out", "--time-limit", "1", "-q"];
    let run = Run::from(scratch.command(&args).output().unwrap());
    run.assert_no_panic();
    // README (Progressive renders): a time limit writes what it has and exits 0.
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    run.assert_says(&[
        "warning: --time-limit reached in camera 1 of 3 ('a.png')",
        "the later cameras were skipped and their files not written",
        "camera 2 of 3 ('b.png') (out/b.exr, out/b.png), camera 3 of 3 ('c.png')",
    ]);
    assert!(scratch.path("out/a.png").exists() && !scratch.path("out/b.png").exists());
}

#[test]
fn too_many_samples_are_refused_naming_the_file_the_camera_and_the_field() {
    let scratch = Scratch::new();
    // The second camera: 512² pixels at 2²⁰ spp, 2³⁸ samples (at most 2³⁶ are taken).
    let small = "<ImageResolution>8 8</ImageResolution>";
    let xml = cameras_scene(&["b.png", "a.png"], "");
    let at = xml.rfind(small).unwrap();
    let big = "<ImageResolution>512 512</ImageResolution><NumSamples>1048576</NumSamples>";
    let xml = format!("{}{big}{}", &xml[..at], &xml[at + small.len()..]);
    scratch.write("s.xml", xml);
    std::fs::create_dir(scratch.path("out")).unwrap();
    refused_in(
        &scratch,
        &["render", "s.xml", "--out-dir", "out"],
        &["'s.xml', camera 2 of 2 ('a.png'): pixels × spp is 274877906944", "NumSamples"],
    );
    scratch.write("s.toml", scene(""));
    refused_in(
        &scratch,
        &["render", "s.toml", "--spp", "1048576", "--resolution", "512x512"],
        &["'s.toml': pixels × spp is 274877906944 (512x512 pixels × 1048576 spp, from --spp)"],
    );
}
