//! The memory estimate renders are checked against covers what they really hold. A file of
//! its own: it measures child processes, and nothing else may run beside them.

mod common;

use common::*;
use embray::choice::Choice;

/// Runs `embray` with `args` in `dir` and returns its peak resident memory in bytes, read
/// from the kernel when the child is reaped (`wait4`), so that only that process counts.
// Reaped by `wait4` itself (which `Child::wait` cannot do and still report the usage).
#[allow(clippy::zombie_processes)]
fn child_peak_bytes(args: &[&str], dir: &std::path::Path) -> u64 {
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_embray"))
        .args(args)
        .current_dir(dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("embray starts");
    let mut status = 0;
    // SAFETY: an all-zero `rusage` is a valid value for `wait4` to fill in.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: the pid is our own child, not yet waited for; both pointers are valid.
    let pid = unsafe { libc::wait4(child.id() as libc::pid_t, &mut status, 0, &mut usage) };
    assert_eq!(pid, child.id() as libc::pid_t, "wait4");
    assert!(libc::WIFEXITED(status) && libc::WEXITSTATUS(status) == 0, "embray {args:?} failed");
    usage.ru_maxrss as u64 * 1024 // kilobytes on Linux
}

/// The memory estimate against what a render really holds: `embray render` of the Cornell
/// box at a few sizes, on each backend, its peak resident memory read from the kernel. The
/// estimate must cover the peak (a render it accepts fits) and stay within 1.5 times it (a
/// render it refuses would not have fitted with much to spare).
#[test]
fn the_memory_estimate_covers_the_measured_peak_within_half_again() {
    let dir = common::command::temp_dir("memory-model");
    let cornell = std::fs::read_to_string(repo_path("scenes/cornell.toml")).unwrap();
    for backend in backends() {
        for size in [512u32, 1024] {
            let text: Vec<String> = cornell
                .lines()
                .map(|l| match l.starts_with("resolution") {
                    true => format!("resolution = [{size}, {size}]"),
                    false => l.to_owned(),
                })
                .collect();
            let name = format!("c{size}.toml");
            std::fs::write(dir.join(&name), text.join("\n")).unwrap();
            let scene = embray::scene::load(&dir.join(&name)).unwrap();
            let (estimate, _, _) = embray::scene::budget::memory_needed(&scene);
            let args = ["render", &name, "--spp", "1", "-q", "--backend", backend.name()];
            let peak = child_peak_bytes(&args, &dir);
            let ratio = estimate as f64 / peak as f64;
            println!(
                "{}: {size}² peak {:.1} MiB, estimate {:.1} MiB ({ratio:.2}×)",
                backend.name(),
                peak as f64 / 1048576.0,
                estimate as f64 / 1048576.0
            );
            assert!(estimate >= peak, "{} {size}²: estimate under the peak", backend.name());
            assert!(ratio <= 1.5, "{} {size}²: estimate {ratio:.2}× the peak", backend.name());
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
