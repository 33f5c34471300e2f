//! `embray bench speed`: throughput of each backend on scenes from a dozen to a million
//! triangles — BVH build time per build quality, primary and diffuse-bounce rays per second
//! (Embree also against a bare `rtcIntersect1` loop), whole-render samples per second on 1
//! and 2 threads, and memory. Ray throughput is measured on one thread, so the ratios to
//! the raw loop are per core.

use super::median;
use crate::accel::{Accel, AccelError, AccelOptions, BackendKind, BuildQuality, Coherence, build};
use crate::choice::Choice;
use crate::ray::{Hit, Ray};
use crate::render::{CAMERA_BATCH, RenderError, RenderOptions, prepare_scene, render_film};
use crate::render_scene::RenderScene;
use crate::sampling::{cosine_hemisphere, hash4, to_unit_f32};
use crate::scene::SceneDesc;
use crate::shading::surface::interaction;
use crate::stats::TraversalCounters;
use glam::{Mat3, Vec2, Vec3};
use std::time::Instant;

#[derive(Clone, Debug, serde::Serialize)]
pub struct SpeedRow {
    pub scene: String,
    pub triangles: usize,
    pub backend: &'static str,
    /// Build time with `BuildQuality` low, medium and high.
    pub build_ms: [f64; 3],
    /// Camera rays one at a time (`Accel::intersect`), 1 thread.
    pub primary_mrays: f64,
    /// Camera rays in the renderer's batches (`Accel::intersect_batch`), 1 thread.
    pub primary_batch_mrays: f64,
    /// The same camera rays through a bare `rtcIntersect1` loop (Embree rows only).
    pub raw_embree_mrays: Option<f64>,
    /// Cosine-distributed bounce rays from the camera rays' hits, 1 thread.
    pub diffuse_mrays: f64,
    /// Whole-render samples (camera paths) per second with 1 and 2 threads.
    pub samples_per_s_1t: f64,
    pub samples_per_s_2t: f64,
    /// Memory of the acceleration structure, MiB, counted by each backend the same way:
    /// every byte it allocated for the structure (obvhs: nodes, leaf blocks and ids;
    /// Embree: what its device memory monitor reported).
    pub accel_mib: f64,
}

#[derive(Debug, thiserror::Error)]
pub enum SpeedError {
    #[error(transparent)]
    Render(#[from] RenderError),
    #[error(transparent)]
    Accel(#[from] AccelError),
}

/// One camera ray through every pixel centre.
pub fn primary_rays(scene: &RenderScene) -> Vec<Ray> {
    let camera = &scene.camera;
    (0..camera.height)
        .flat_map(|y| (0..camera.width).map(move |x| (x, y)))
        .map(|(x, y)| camera.generate_ray(Vec2::new(x as f32 + 0.5, y as f32 + 0.5), None))
        .collect()
}

/// Cosine-distributed bounce rays leaving the primary hits.
pub fn diffuse_rays(scene: &RenderScene, accel: &dyn Accel, primary: &[Ray]) -> Vec<Ray> {
    let mut counters = TraversalCounters::default();
    primary
        .iter()
        .enumerate()
        .filter_map(|(i, ray)| {
            let hit = accel.intersect(ray, &mut counters)?;
            let si = interaction(scene, ray, &hit);
            let u = Vec2::new(
                to_unit_f32(hash4(9, i as u64, 0, 0)),
                to_unit_f32(hash4(9, i as u64, 0, 1)),
            );
            let n = si.shading_normal;
            let t = if n.x.abs() < 0.9 { Vec3::X } else { Vec3::Y };
            let b1 = n.cross(t).normalize();
            let frame = Mat3::from_cols(b1, n.cross(b1), n);
            Some(si.surface.spawn_ray(frame * cosine_hemisphere(u), 0.0))
        })
        .collect()
}

/// Rays per second of `trace` over `rays` (median of `runs`), on the calling thread.
fn rays_per_second(rays: &[Ray], runs: usize, mut trace: impl FnMut(&[Ray]) -> usize) -> f64 {
    let times: Vec<f64> = (0..runs.max(1))
        .map(|_| {
            let start = Instant::now();
            std::hint::black_box(trace(rays));
            start.elapsed().as_secs_f64()
        })
        .collect();
    rays.len() as f64 / median(times)
}

/// Closest-hit rays per second over `rays`, one at a time on the calling thread.
pub fn throughput(accel: &dyn Accel, rays: &[Ray], runs: usize) -> f64 {
    rays_per_second(rays, runs, |rays| {
        let mut counters = TraversalCounters::default();
        rays.iter().filter(|r| accel.intersect(r, &mut counters).is_some()).count()
    })
}

/// As [`throughput`], in batches of the renderer's size through `Accel::intersect_batch`.
pub fn batch_throughput(accel: &dyn Accel, rays: &[Ray], runs: usize) -> f64 {
    let mut hits = vec![None; CAMERA_BATCH];
    rays_per_second(rays, runs, |rays| {
        let mut counters = TraversalCounters::default();
        rays.chunks(CAMERA_BATCH)
            .map(|chunk| {
                let hits = &mut hits[..chunk.len()];
                accel.intersect_batch(chunk, hits, Coherence::Coherent, &mut counters);
                hits.iter().filter(|h| h.is_some()).count()
            })
            .sum()
    })
}

/// The bare `rtcIntersect1` loop over `rays`, in rays per second; `None` without Embree.
fn raw_embree_throughput(scene: &RenderScene, rays: &[Ray], runs: usize) -> Option<f64> {
    let raw = crate::accel::raw_embree_loop(scene)?;
    Some(rays_per_second(rays, runs, |rays| raw(rays)))
}

/// Hits of `rays` one by one (for comparing batched paths against).
pub fn single_hits(accel: &dyn Accel, rays: &[Ray]) -> Vec<Option<Hit>> {
    let mut counters = TraversalCounters::default();
    rays.iter().map(|r| accel.intersect(r, &mut counters)).collect()
}

fn triangles(scene: &RenderScene) -> usize {
    scene
        .instances
        .iter()
        .map(|i| match &scene.prototypes[i.prototype as usize].geometry {
            crate::render_scene::Geometry::Triangles(m) => m.indices.len(),
            crate::render_scene::Geometry::Sphere(_) => 0,
            crate::render_scene::Geometry::SdfGrid(_) => 0,
        })
        .sum()
}

/// Measures one scene on one backend (see [`measure_scene`]).
pub fn measure(
    name: &str,
    desc: &SceneDesc,
    backend: BackendKind,
    spp: u32,
    runs: usize,
    render_quality: BuildQuality,
) -> Result<SpeedRow, SpeedError> {
    let mut rows = measure_scene(name, desc, &[backend], spp, runs, render_quality)?;
    Ok(rows.remove(0))
}

/// Measures one scene on each of `backends`: builds at every quality, ray throughput on one
/// thread, then whole renders on 1 and 2 threads with the backends' runs alternated, so a
/// change in the machine's speed during the measurement shifts all backends alike and
/// their ratio stays meaningful.
pub fn measure_scene(
    name: &str,
    desc: &SceneDesc,
    backends: &[BackendKind],
    spp: u32,
    runs: usize,
    render_quality: BuildQuality,
) -> Result<Vec<SpeedRow>, SpeedError> {
    let mut options = RenderOptions::for_scene(desc);
    options.spp = spp;
    let scene = prepare_scene(desc, &options)?;
    let mut rows = Vec::new();
    let mut accels = Vec::new();
    for &backend in backends {
        let (row, accel) = measure_rays(name, &scene, backend, runs, render_quality)?;
        rows.push(row);
        accels.push(accel);
    }
    let samples = scene.camera.width as f64 * scene.camera.height as f64 * spp as f64;
    for (slot, threads) in [1usize, 2].into_iter().enumerate() {
        let pool =
            rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("thread pool");
        let mut times = vec![Vec::new(); accels.len()];
        for _ in 0..runs.max(1) {
            for (accel, times) in accels.iter().zip(&mut times) {
                pool.install(|| {
                    let start = Instant::now();
                    std::hint::black_box(render_film(&scene, accel.as_ref(), &options));
                    times.push(start.elapsed().as_secs_f64());
                });
            }
        }
        for (row, times) in rows.iter_mut().zip(times) {
            let rate = samples / median(times);
            match slot {
                0 => row.samples_per_s_1t = rate,
                _ => row.samples_per_s_2t = rate,
            }
        }
    }
    Ok(rows)
}

/// Build times, memory and ray throughput of one backend (its row without the render
/// rates), and the backend built with `render_quality` to render with.
fn measure_rays(
    name: &str,
    scene: &RenderScene,
    backend: BackendKind,
    runs: usize,
    render_quality: BuildQuality,
) -> Result<(SpeedRow, Box<dyn Accel>), SpeedError> {
    let mut build_ms = [0.0; 3];
    let mut accel = None;
    let qualities = [BuildQuality::Low, BuildQuality::Medium, BuildQuality::High];
    for (slot, build_quality) in qualities.into_iter().enumerate() {
        let accel_options = AccelOptions { build_quality, ..AccelOptions::default() };
        let mut builds = Vec::new();
        for _ in 0..runs.max(1) {
            drop(accel.take());
            let start = Instant::now();
            accel = Some(build(backend, scene, &accel_options)?);
            builds.push(start.elapsed().as_secs_f64());
        }
        build_ms[slot] = median(builds) * 1e3;
    }
    drop(accel);
    // Memory of the BVH the rays and renders use.
    let render_options = AccelOptions { build_quality: render_quality, ..AccelOptions::default() };
    let accel = build(backend, scene, &render_options)?;
    let accel_mib = accel.memory_bytes().unwrap_or(0) as f64 / (1 << 20) as f64;
    let one_thread = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("thread pool");
    let primary = primary_rays(scene);
    let diffuse = diffuse_rays(scene, accel.as_ref(), &primary);
    let (primary_mrays, primary_batch_mrays, raw_embree_mrays, diffuse_mrays) =
        one_thread.install(|| {
            let raw = match backend {
                BackendKind::Embree => raw_embree_throughput(scene, &primary, runs),
                BackendKind::Obvhs => None,
            };
            (
                throughput(accel.as_ref(), &primary, runs) / 1e6,
                batch_throughput(accel.as_ref(), &primary, runs) / 1e6,
                raw.map(|r| r / 1e6),
                if diffuse.is_empty() {
                    0.0
                } else {
                    throughput(accel.as_ref(), &diffuse, runs) / 1e6
                },
            )
        });
    let row = SpeedRow {
        scene: name.to_string(),
        triangles: triangles(scene),
        backend: backend.name(),
        build_ms,
        primary_mrays,
        primary_batch_mrays,
        raw_embree_mrays,
        diffuse_mrays,
        samples_per_s_1t: 0.0,
        samples_per_s_2t: 0.0,
        accel_mib,
    };
    Ok((row, accel))
}

/// The rows as a Markdown table, then the ratios between the backends per scene.
pub fn markdown(rows: &[SpeedRow]) -> String {
    let mut out = String::from(
        "| scene | triangles | backend | build ms low / medium / high | primary Mrays/s | batched | raw rtcIntersect1 | diffuse Mrays/s | samples/s 1 thread | samples/s 2 threads | scaling | accel MiB |\n\
         |---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for r in rows {
        let raw = match r.raw_embree_mrays {
            Some(raw) => format!("{raw:.2} (ours {:.2}×)", r.primary_mrays / raw.max(1e-9)),
            None => "–".to_string(),
        };
        out += &format!(
            "| {} | {} | {} | {:.1} / {:.1} / {:.1} | {:.2} | {:.2} | {} | {:.2} | {:.0} | {:.0} | {:.2}× | {:.1} |\n",
            r.scene,
            r.triangles,
            r.backend,
            r.build_ms[0],
            r.build_ms[1],
            r.build_ms[2],
            r.primary_mrays,
            r.primary_batch_mrays,
            raw,
            r.diffuse_mrays,
            r.samples_per_s_1t,
            r.samples_per_s_2t,
            r.samples_per_s_2t / r.samples_per_s_1t.max(1e-9),
            r.accel_mib
        );
    }
    let pairs: Vec<(&SpeedRow, &SpeedRow)> = rows
        .iter()
        .filter(|r| r.backend == "embree")
        .filter_map(|e| {
            rows.iter().find(|o| o.backend == "obvhs" && o.scene == e.scene).map(|o| (e, o))
        })
        .collect();
    if !pairs.is_empty() {
        out += "\nobvhs render time ÷ Embree render time (1 thread / 2 threads):";
        for (embree, obvhs) in pairs {
            out += &format!(
                " {} {:.2}× / {:.2}×;",
                embree.scene,
                embree.samples_per_s_1t / obvhs.samples_per_s_1t.max(1e-9),
                embree.samples_per_s_2t / obvhs.samples_per_s_2t.max(1e-9),
            );
        }
        out.pop();
        out += "\n";
    }
    out
}
