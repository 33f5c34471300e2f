//! The process's surroundings: closed or full standard streams, and signals while output
//! files are being written.

use crate::harness::{Run, Scratch, scene};
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
