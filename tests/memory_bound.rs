//! Memory a render needs does not grow with the samples per pixel. This file holds one test
//! so that its process's peak memory is that render's alone.

mod common;

use common::*;
use embray::choice::Choice;

/// Peak resident memory of this process so far (Linux `VmHWM`), in MiB.
fn peak_mib() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").expect("/proc/self/status");
    let line = status.lines().find(|l| l.starts_with("VmHWM:")).expect("a VmHWM line");
    let kib: f64 = line.split_whitespace().nth(1).and_then(|n| n.parse().ok()).expect("kB");
    kib / 1024.0
}

#[test]
fn a_million_samples_of_one_pixel_stay_under_50_mb() {
    let scene = cornell(1, 1);
    for backend in backends() {
        let out = render_ok(&scene, &options(&scene, backend, 1_000_000));
        let peak = peak_mib();
        println!(
            "{}: 1×1 at 1e6 spp, {} camera rays; peak resident memory so far {peak:.1} MiB",
            backend.name(),
            out.stats.camera.rays
        );
        assert_eq!(out.stats.camera.rays, 1_000_000);
        assert!(peak < 50.0, "{}: peak {peak:.1} MiB", backend.name());
    }
}
