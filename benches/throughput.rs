//! Ray throughput and BVH builds per backend, on one thread (`cargo bench --bench throughput`;
//! a filter such as `cargo bench --bench throughput -- primary/sphere_1m` runs a subset).
//!
//! For each scene (the procedural displaced sphere at about 12, 100k and 1M triangles, and
//! `scenes/cornell.toml`), on 256×256 camera rays through the pixel centres and on the
//! cosine-distributed bounces leaving their hits:
//!
//! - `raw_embree`: a bare `rtcIntersect1` loop (`EmbreeAccel::raw_intersect_loop`), the
//!   baseline the backend's wrapper is measured against;
//! - `embree`: `Accel::intersect` one ray at a time (what the integrator calls);
//! - `embree_batch`: `Accel::intersect_batch` on chunks of `CAMERA_BATCH` rays (what the
//!   renderer does with a tile's camera rays; Embree packets);
//! - `obvhs`, `obvhs_batch`: the same two calls on the pure-Rust backend.
//!
//! `build/{scene}` times building each backend, Embree at each `BuildQuality`.
//!
//! Sample sizes and measurement times are small so the whole run takes a few minutes on two
//! cores; the machines this runs on are noisy, so compare within a run.

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use embray::accel::{Accel, AccelOptions, BackendKind, BatchMode, BuildQuality, Coherence, build};
use embray::bench::{procedural, speed};
use embray::choice::Choice;
use embray::ray::{Hit, Ray};
use embray::render::{RenderOptions, prepare_scene};
use embray::render_scene::RenderScene;
use embray::scene::SceneDesc;
use embray::stats::TraversalCounters;
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

/// Rays per `intersect_batch` call, as the renderer's camera batches.
const BATCH: usize = embray::render::CAMERA_BATCH;

fn scenes() -> Vec<(&'static str, SceneDesc)> {
    let sphere = |n| procedural::displaced_sphere_scene(n, 256, 256);
    let cornell_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cornell.toml");
    let mut cornell = embray::scene::load(&cornell_path).expect("scenes/cornell.toml loads");
    cornell.camera.width = 256;
    cornell.camera.height = 256;
    vec![
        ("sphere_tiny", sphere(12)),
        ("cornell", cornell),
        ("sphere_100k", sphere(100_000)),
        ("sphere_1m", sphere(1_000_000)),
    ]
}

fn render_scene(desc: &SceneDesc) -> RenderScene {
    prepare_scene(desc, &RenderOptions::for_scene(desc)).expect("scene converts")
}

fn hits_one_by_one(accel: &dyn Accel, rays: &[Ray]) -> usize {
    let mut counters = TraversalCounters::default();
    rays.iter().filter(|r| accel.intersect(r, &mut counters).is_some()).count()
}

fn hits_batched(accel: &dyn Accel, rays: &[Ray], hits: &mut [Option<Hit>]) -> usize {
    let mut counters = TraversalCounters::default();
    for (rays, hits) in rays.chunks(BATCH).zip(hits.chunks_mut(BATCH)) {
        accel.intersect_batch(rays, hits, Coherence::Coherent, &mut counters);
    }
    hits.iter().filter(|h| h.is_some()).count()
}

fn throughput(c: &mut Criterion) {
    // One thread: the backends' own speed, not the machine's load across cores. (Embree
    // traces on the calling thread; only its builds use TBB workers.)
    for (name, desc) in scenes() {
        let scene = render_scene(&desc);
        let accels: Vec<(BackendKind, Box<dyn Accel>)> = BackendKind::compiled()
            .into_iter()
            .map(|kind| (kind, build(kind, &scene, &AccelOptions::default()).expect("builds")))
            .collect();
        let primary = speed::primary_rays(&scene);
        let diffuse = speed::diffuse_rays(&scene, accels[0].1.as_ref(), &primary);
        #[cfg(feature = "embree")]
        let raw = embray::accel::embree::EmbreeAccel::build(&scene, &AccelOptions::default())
            .expect("Embree builds");
        for (kind, rays) in [("primary", &primary), ("diffuse", &diffuse)] {
            if rays.is_empty() {
                continue;
            }
            let mut group = c.benchmark_group(format!("{kind}/{name}"));
            group.throughput(Throughput::Elements(rays.len() as u64));
            #[cfg(feature = "embree")]
            group.bench_function("raw_embree", |b| {
                b.iter(|| raw.raw_intersect_loop(black_box(rays)))
            });
            let mut hits = vec![None; rays.len()];
            for (backend, accel) in &accels {
                let accel = accel.as_ref();
                group.bench_function(backend.name(), |b| {
                    b.iter(|| hits_one_by_one(accel, black_box(rays)))
                });
                group.bench_function(format!("{}_batch", backend.name()), |b| {
                    b.iter(|| hits_batched(accel, black_box(rays), &mut hits))
                });
            }
            group.finish();
        }
        let mut group = c.benchmark_group(format!("build/{name}"));
        let mut configs = vec![(BackendKind::Obvhs, BuildQuality::Medium)];
        if cfg!(feature = "embree") {
            for quality in [BuildQuality::Low, BuildQuality::Medium, BuildQuality::High] {
                configs.push((BackendKind::Embree, quality));
            }
        }
        for (backend, quality) in configs {
            if !BackendKind::compiled().contains(&backend) {
                continue;
            }
            let options = AccelOptions { build_quality: quality, ..AccelOptions::default() };
            let id = format!("{}_{quality:?}", backend.name()).to_lowercase();
            group.bench_function(id, |b| {
                b.iter_batched(
                    || (),
                    |()| build(backend, &scene, &options).expect("builds"),
                    BatchSize::PerIteration,
                )
            });
        }
        group.finish();
    }
}

/// Embree's batch modes and build qualities on the camera rays of the large scenes.
fn embree_options(c: &mut Criterion) {
    if !BackendKind::compiled().contains(&BackendKind::Embree) {
        return;
    }
    for (name, desc) in scenes().into_iter().filter(|(n, _)| *n != "sphere_tiny") {
        let scene = render_scene(&desc);
        let primary = speed::primary_rays(&scene);
        let mut group = c.benchmark_group(format!("embree_options/{name}"));
        group.throughput(Throughput::Elements(primary.len() as u64));
        let mut hits = vec![None; primary.len()];
        for quality in [BuildQuality::Low, BuildQuality::Medium, BuildQuality::High] {
            for (compact, batch) in [
                (false, BatchMode::Single),
                (false, BatchMode::Packets8),
                (false, BatchMode::Packets16),
                (true, BatchMode::Packets8),
            ] {
                let options = AccelOptions {
                    build_quality: quality,
                    compact,
                    batch,
                    ..AccelOptions::default()
                };
                let accel = build(BackendKind::Embree, &scene, &options).expect("builds");
                let id = format!("{quality:?}{}_{batch:?}", if compact { "_compact" } else { "" });
                group.bench_function(id.to_lowercase(), |b| {
                    b.iter(|| hits_batched(accel.as_ref(), black_box(&primary), &mut hits))
                });
            }
        }
        group.finish();
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(1200));
    targets = throughput, embree_options
}
criterion_main!(benches);
