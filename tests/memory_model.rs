//! The memory estimate renders are checked against covers what they really hold. A file of
//! its own: it measures child processes, and nothing else may run beside them.

mod common;

use common::*;
use embray::choice::Choice;

/// The worker threads of the renders measured and of their estimates, on any machine.
const THREADS: &str = "2";

/// Runs `embray` with `args` in `dir` and returns its peak resident memory in bytes, read
/// from the kernel when the child is reaped (`wait4`), so that only that process counts.
// Reaped by `wait4` itself (which `Child::wait` cannot do and still report the usage).
#[allow(clippy::zombie_processes)]
fn child_peak_bytes(args: &[&str], dir: &std::path::Path) -> u64 {
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_embray"))
        .args(args)
        .current_dir(dir)
        .env("RAYON_NUM_THREADS", THREADS)
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

/// The memory estimate `embray info s.toml` prints for `backend`, in bytes.
fn info_estimate(dir: &std::path::Path, backend: &str) -> u64 {
    let threads = [("RAYON_NUM_THREADS", THREADS)];
    let out = common::command::embray_with_env(&["info", "s.toml"], dir, &threads);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    let line = text.lines().find(|l| l.starts_with("memory estimate:")).expect("an estimate");
    let at = line.find(&format!(" MiB on {backend}")).expect("the backend's estimate");
    let number = line[..at].rsplit([' ', ':']).next().unwrap();
    (number.parse::<f64>().unwrap() * 1048576.0) as u64
}

/// A small scene around `objects` (64² pixels unless `resolution` says otherwise).
fn scene(resolution: u32, materials: &str, objects: &str) -> String {
    format!(
        "[camera]\nlookfrom = [0.0, 2.0, 6.0]\nlookat = [0.0, 0.0, 0.0]\nvfov = 40.0\n\
         resolution = [{resolution}, {resolution}]\n\n[render]\nspp = 1\nmax_depth = 3\n\n\
         [materials.white]\nalbedo = [0.7, 0.7, 0.7]\n{materials}\n[[lights]]\ntype = \"point\"\n\
         position = [0.0, 4.0, 4.0]\nintensity = [40.0, 40.0, 40.0]\n{objects}"
    )
}

fn floor(material: &str) -> String {
    format!(
        "\n[[objects]]\ntype = \"quad\"\nmaterial = \"{material}\"\ncorner = [-2.0, 0.0, -2.0]\n\
         u = [4.0, 0.0, 0.0]\nv = [0.0, 0.0, 4.0]\n"
    )
}

/// A binary PLY square of 2·side² triangles.
fn ply_grid(path: &std::path::Path, side: u32) {
    let mut bytes = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\n\
         property float y\nproperty float z\nelement face {}\n\
         property list uchar int vertex_indices\nend_header\n",
        (side + 1) * (side + 1),
        2 * side * side
    )
    .into_bytes();
    for j in 0..=side {
        for i in 0..=side {
            for c in [i as f32 / side as f32, 0.0, j as f32 / side as f32] {
                bytes.extend(c.to_le_bytes());
            }
        }
    }
    for j in 0..side {
        for i in 0..side {
            let a = j * (side + 1) + i;
            for tri in [[a, a + 1, a + side + 1], [a + 1, a + side + 2, a + side + 1]] {
                bytes.push(3);
                tri.iter().for_each(|v| bytes.extend(v.to_le_bytes()));
            }
        }
    }
    std::fs::write(path, bytes).unwrap();
}

/// A binary PLY of `triangles` separate triangles, each vertex with a normal and texture
/// coordinates (as exporters write hard-edged or uv-seamed models).
fn ply_soup(path: &std::path::Path, triangles: u32) {
    let mut bytes = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\n\
         property float y\nproperty float z\nproperty float nx\nproperty float ny\n\
         property float nz\nproperty float u\nproperty float v\nelement face {triangles}\n\
         property list uchar int vertex_indices\nend_header\n",
        3 * triangles
    )
    .into_bytes();
    for t in 0..triangles {
        let (x, z) = ((t % 1000) as f32 * 1e-3, (t / 1000) as f32 * 1e-3);
        for (dx, dz) in [(0.0, 0.0), (1e-3, 0.0), (0.0, 1e-3)] {
            for c in [x + dx, 0.0, z + dz, 0.0, 1.0, 0.0, x, z] {
                bytes.extend(c.to_le_bytes());
            }
        }
    }
    for t in 0..triangles {
        bytes.push(3);
        [3 * t, 3 * t + 1, 3 * t + 2].iter().for_each(|v| bytes.extend(v.to_le_bytes()));
    }
    std::fs::write(path, bytes).unwrap();
}

/// The memory estimate against what a render really holds: `embray render` of scenes
/// where one count dominates (materials, lights, pixels, mesh triangles, object placements,
/// texture texels, an EXR environment map's texels), on each backend, its peak resident memory read from
/// the kernel. The estimate must cover the peak (a render it accepts fits) and stay within
/// 1.5 times it (a render it refuses would not have fitted with much to spare).
/// `scripts/memory_model.py` measures the costs per unit these cases check.
#[test]
fn the_memory_estimate_covers_the_measured_peak_within_half_again() {
    let dir = common::command::temp_dir("memory-model");
    ply_grid(&dir.join("grid.ply"), 700);
    ply_soup(&dir.join("soup.ply"), 300_000);
    let noise = image::RgbImage::from_fn(2048, 2048, |x, y| {
        let h = (x.wrapping_mul(2654435761) ^ y.wrapping_mul(40503)).wrapping_mul(2246822519);
        image::Rgb([h as u8, (h >> 8) as u8, (h >> 16) as u8])
    });
    noise.save(dir.join("noise.png")).unwrap();
    drop(noise);
    // An EXR radiance map as renderers write them (R, G, B and more channels).
    std::fs::write(dir.join("m.toml"), scene(1024, "", &floor("white"))).unwrap();
    let out =
        common::command::embray(&["render", "m.toml", "--spp", "1", "-q", "-o", "map.exr"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let materials: String =
        (0..100_000).map(|i| format!("[materials.m{i}]\nalbedo = [0.5, 0.5, 0.5]\n")).collect();
    let lights: String = (0..32_000)
        .map(|i| {
            format!(
                "\n[[lights]]\ntype = \"point\"\nposition = [{}, 4.0, 4.0]\n\
                 intensity = [0.01, 0.01, 0.01]\n",
                i as f64 * 1e-3
            )
        })
        .collect();
    let cases = [
        ("materials 100k", scene(64, &materials, &floor("white"))),
        ("lights 32k", scene(64, "", &(floor("white") + &lights))),
        ("pixels 512²", scene(512, "", &floor("white"))),
        ("pixels 1024²", scene(1024, "", &floor("white"))),
        (
            "triangles 980k",
            scene(
                64,
                "",
                "\n[[objects]]\ntype = \"mesh\"\nmaterial = \"white\"\nfile = \"grid.ply\"\n",
            ),
        ),
        (
            "triangle soup 300k with normals and uvs",
            scene(
                64,
                "",
                "\n[[objects]]\ntype = \"mesh\"\nmaterial = \"white\"\nfile = \"soup.ply\"\n",
            ),
        ),
        (
            "placements 216k",
            scene(
                64,
                "",
                "\n[[objects]]\ntype = \"box\"\nmaterial = \"white\"\nmin = [0.0, 0.0, 0.0]\n\
                 max = [0.01, 0.01, 0.01]\nrepeat = { count = [60, 60, 60], spacing = [0.02, 0.02, 0.02] }\n",
            ),
        ),
        (
            "texels 2048²",
            scene(
                64,
                "\n[materials.tex]\ntexture = { type = \"image\", file = \"noise.png\" }\n",
                &floor("tex"),
            ),
        ),
        (
            "EXR environment map 1024²",
            scene(
                64,
                "",
                &(floor("white") + "\n[[lights]]\ntype = \"environment\"\nfile = \"map.exr\"\n"),
            ),
        ),
        (
            "environment map 2048²",
            scene(
                64,
                "",
                &(floor("white") + "\n[[lights]]\ntype = \"environment\"\nfile = \"noise.png\"\n"),
            ),
        ),
    ];
    for backend in backends() {
        for (name, text) in &cases {
            std::fs::write(dir.join("s.toml"), text).unwrap();
            // The estimate as `embray info` prints it: the scene is never loaded here, as a
            // child's peak as the kernel reports it includes the memory of the process it
            // was forked from (before `exec`), and freed memory may stay resident.
            let estimate = info_estimate(&dir, backend.name());
            let args = ["render", "s.toml", "--spp", "1", "-q", "--backend", backend.name()];
            let peak = child_peak_bytes(&args, &dir);
            let ratio = estimate as f64 / peak as f64;
            println!(
                "{} {name}: peak {:.1} MiB, estimate {:.1} MiB ({ratio:.2}×)",
                backend.name(),
                peak as f64 / 1048576.0,
                estimate as f64 / 1048576.0
            );
            assert!(estimate >= peak, "{} {name}: estimate under the peak", backend.name());
            assert!(ratio <= 1.5, "{} {name}: estimate {ratio:.2}× the peak", backend.name());
        }
    }
}
