//! Renders one scene for every (backend, render space, offset) and measures each.

use super::median;
use crate::accel::BackendKind;
use crate::choice::Choice;
use crate::image_error::{ImageError, image_error};
use crate::render::{RenderError, RenderOptions, render};
use crate::render_space::RenderSpace;
use crate::scene::SceneDesc;
use crate::stats::RenderStats;
use glam::DVec3;

/// One measured configuration.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Measurement {
    pub scene: String,
    pub backend: &'static str,
    pub render_space: &'static str,
    /// Distance of the scene from the origin (the same offset on every axis).
    pub offset: f64,
    /// Median render time over the runs, seconds (BVH build excluded).
    pub render_seconds: f64,
    /// Median BVH build time, seconds.
    pub build_seconds: f64,
    pub mrays_per_second: f64,
    pub stats: RenderStats,
    /// Which traversal counters the backend could observe.
    pub observes: crate::accel::Observes,
    /// Of the native (not counting) render, against the reference render (first backend,
    /// `cameraworld`, offset 0).
    pub error: ImageError,
}

/// What to measure.
#[derive(Clone, Debug)]
pub struct Grid {
    pub backends: Vec<BackendKind>,
    pub spaces: Vec<RenderSpace>,
    pub offsets: Vec<f64>,
    /// Timed repetitions per configuration (the median is reported).
    pub runs: usize,
}

/// Runs the grid; `on_progress` is called after each configuration.
pub fn measure(
    scene_name: &str,
    scene: &SceneDesc,
    base: &RenderOptions,
    grid: &Grid,
    mut on_progress: impl FnMut(&Measurement),
) -> Result<Vec<Measurement>, RenderError> {
    let mut reference_options = base.clone();
    reference_options.backend = grid.backends[0];
    reference_options.render_space = RenderSpace::Cameraworld;
    reference_options.offset = DVec3::ZERO;
    reference_options.count_traversal = false;
    let reference = render(scene, &reference_options)?.film;
    let mut rows = Vec::new();
    for &offset in &grid.offsets {
        for &space in &grid.spaces {
            for &backend in &grid.backends {
                let mut options = base.clone();
                options.backend = backend;
                options.render_space = space;
                options.offset = DVec3::splat(offset);
                // Counters come from a separate run so that counting never slows the timed ones.
                let mut counting = options.clone();
                counting.count_traversal = true;
                let counted = render(scene, &counting)?;
                options.count_traversal = false;
                let (mut times, mut builds) = (Vec::new(), Vec::new());
                let mut native = None;
                for _ in 0..grid.runs.max(1) {
                    let out = render(scene, &options)?;
                    times.push(out.render_time.as_secs_f64());
                    builds.push(out.build_time.as_secs_f64());
                    native = Some(out.film);
                }
                // The image error is the native run's: in counting mode Embree traces our
                // triangle test (user geometry), not its own kernel.
                let native = native.expect("at least one timed run");
                let render_seconds = median(times);
                let row = Measurement {
                    scene: scene_name.to_string(),
                    backend: backend.name(),
                    render_space: space.name(),
                    offset,
                    render_seconds,
                    build_seconds: median(builds),
                    mrays_per_second: counted.stats.total_rays() as f64 / render_seconds / 1e6,
                    stats: counted.stats,
                    observes: counted.observes,
                    error: image_error(&native, &reference),
                };
                on_progress(&row);
                rows.push(row);
            }
        }
    }
    Ok(rows)
}
