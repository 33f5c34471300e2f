//! `embray bench queries`: what one ray query costs per ray kind and batch mode, the
//! measurement that picks how the batched path tracer calls each backend. On one thread:
//! camera rays through every pixel centre (closest hits, coherent batches), cosine bounces
//! from their hits (closest hits, incoherent batches), and the same bounces as occlusion
//! queries (shadow rays), each one at a time and in the renderer's batches of each mode;
//! on Embree with its robust triangle test (the default) and with its fast one.

use super::median;
use super::speed::{diffuse_rays, primary_rays};
use crate::accel::{Accel, AccelOptions, BackendKind, BatchMode, Coherence, Intersection, build};
use crate::choice::Choice;
use crate::ray::Ray;
use crate::render::{RenderError, RenderOptions, prepare_scene};
use crate::scene::SceneDesc;
use crate::stats::TraversalCounters;
use std::time::Instant;

/// Rays per batched call: a tile's paths, as the renderer batches them.
const BATCH: usize = crate::render::CAMERA_BATCH;

/// Nanoseconds per ray of one backend and batch mode, per query kind.
#[derive(Clone, Debug, serde::Serialize)]
pub struct QueryRow {
    pub backend: &'static str,
    /// `single` for one query per ray; else the batch mode's name; ` (fast)` after it for
    /// Embree's fast triangle test (`Intersection::Fast`).
    pub mode: String,
    pub camera_ns: f64,
    pub bounce_ns: f64,
    pub shadow_ns: f64,
}

/// Median nanoseconds per ray of `query` over `rays` in `runs` runs.
fn ns_per_ray(rays: &[Ray], runs: usize, mut query: impl FnMut(&[Ray])) -> f64 {
    let times = (0..runs.max(1)).map(|_| {
        let start = Instant::now();
        query(rays);
        start.elapsed().as_secs_f64()
    });
    median(times.collect()) * 1e9 / rays.len().max(1) as f64
}

/// The query costs on `desc` for every backend in `backends`: one row of single queries
/// each, and one per Embree batch mode, for each of Embree's triangle tests.
pub fn measure(
    desc: &SceneDesc,
    backends: &[BackendKind],
    runs: usize,
) -> Result<Vec<QueryRow>, RenderError> {
    let scene = prepare_scene(desc, &RenderOptions::for_scene(desc))?;
    let mut rows = Vec::new();
    for &backend in backends {
        let (modes, tests): (&[Option<BatchMode>], &[Intersection]) = match backend {
            BackendKind::Embree => {
                (&[None, Some(BatchMode::Packets8), Some(BatchMode::Packets16)], Intersection::ALL)
            }
            BackendKind::Obvhs => (&[None], &[Intersection::Robust]),
        };
        let builds = tests.iter().flat_map(|&test| modes.iter().map(move |&mode| (test, mode)));
        for (intersection, mode) in builds {
            let batch = mode.unwrap_or_default();
            let options = AccelOptions { batch, intersection, ..AccelOptions::DEFAULT };
            let accel = build(backend, &scene, &options)?;
            // The default test unnamed, as the rows before there was a choice.
            let test = if intersection == AccelOptions::DEFAULT.intersection {
                String::new()
            } else {
                format!(" ({})", intersection.name())
            };
            let camera = primary_rays(&scene);
            let bounces = diffuse_rays(&scene, accel.as_ref(), &camera);
            let row = match mode {
                None => QueryRow {
                    backend: backend.name(),
                    mode: format!("single{test}"),
                    camera_ns: ns_per_ray(&camera, runs, |r| one_by_one(accel.as_ref(), r)),
                    bounce_ns: ns_per_ray(&bounces, runs, |r| one_by_one(accel.as_ref(), r)),
                    shadow_ns: ns_per_ray(&bounces, runs, |r| occluded(accel.as_ref(), r)),
                },
                Some(mode) => {
                    let accel = accel.as_ref();
                    let coherent = |r: &[Ray]| batched(accel, r, Coherence::Coherent);
                    let incoherent = |r: &[Ray]| batched(accel, r, Coherence::Incoherent);
                    QueryRow {
                        backend: backend.name(),
                        mode: format!("{}{test}", mode.name()),
                        camera_ns: ns_per_ray(&camera, runs, coherent),
                        bounce_ns: ns_per_ray(&bounces, runs, incoherent),
                        shadow_ns: ns_per_ray(&bounces, runs, |r| occluded_batched(accel, r)),
                    }
                }
            };
            rows.push(row);
        }
    }
    Ok(rows)
}

fn one_by_one(accel: &dyn Accel, rays: &[Ray]) {
    let mut counters = TraversalCounters::default();
    for ray in rays {
        std::hint::black_box(accel.intersect(ray, &mut counters));
    }
}

fn occluded(accel: &dyn Accel, rays: &[Ray]) {
    let mut counters = TraversalCounters::default();
    for ray in rays {
        std::hint::black_box(accel.occluded(ray, &mut counters));
    }
}

fn batched(accel: &dyn Accel, rays: &[Ray], coherence: Coherence) {
    let mut counters = TraversalCounters::default();
    let mut hits = vec![None; BATCH];
    for chunk in rays.chunks(BATCH) {
        let hits = &mut hits[..chunk.len()];
        accel.intersect_batch(chunk, hits, coherence, &mut counters);
        std::hint::black_box(hits);
    }
}

fn occluded_batched(accel: &dyn Accel, rays: &[Ray]) {
    let mut counters = TraversalCounters::default();
    let mut blocked = vec![false; BATCH];
    for chunk in rays.chunks(BATCH) {
        let blocked = &mut blocked[..chunk.len()];
        accel.occluded_batch(chunk, blocked, &mut counters);
        std::hint::black_box(blocked);
    }
}

/// The rows as a Markdown table.
pub fn markdown(rows: &[QueryRow]) -> String {
    let mut out = String::from(
        "| backend | queries | camera ns/ray (coherent) | bounce ns/ray (incoherent) | shadow ns/ray |\n\
         |---|---|---:|---:|---:|\n",
    );
    for r in rows {
        out += &format!(
            "| {} | {} | {:.1} | {:.1} | {:.1} |\n",
            r.backend, r.mode, r.camera_ns, r.bounce_ns, r.shadow_ns
        );
    }
    out
}
