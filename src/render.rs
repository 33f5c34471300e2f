//! One render from a scene description: convert to render space, build the backend, trace
//! tiles in parallel, gather film and counters.

use crate::accel::{self, Accel, AccelError, AccelOptions};
use crate::compile::{CompileError, to_render_scene};
use crate::distributed::{Part, PartError};
use crate::film::{Film, tiles};
use crate::integrator::Tracer;
use crate::render_passes::{Passes, Progress, add_tile, pass_ranges};
use crate::render_scene::RenderScene;
pub use crate::render_tile::{CAMERA_BATCH, TILE_SIZE};
use crate::render_tile::{WorkerScratches, render_tile};
use crate::sample_sums::FilmSums;
use crate::scene::SceneDesc;
use crate::stats::RenderStats;
use glam::DVec3;
use rayon::prelude::*;
use std::sync::{Mutex, PoisonError};
use std::time::{Duration, Instant};

pub use crate::render_options::RenderOptions;

/// What a render calls after each pass with the sums so far and the samples per pixel done.
pub type OnPass<'a> = dyn FnMut(&FilmSums, u32) + Send + 'a;

#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// `file` names the scene (empty for one built in code, which names none).
    #[error("{}{error}", in_file(file))]
    Compile { file: std::path::PathBuf, error: CompileError },
    #[error(transparent)]
    Accel(#[from] AccelError),
    #[error(transparent)]
    Limit(#[from] crate::scene::budget::LimitError),
    #[error("{what} is {value}, but must be at most {max}")]
    Option { what: &'static str, value: u64, max: u64 },
    #[error(transparent)]
    Part(#[from] PartError),
    #[error("could not start {threads} worker threads: {error}")]
    Threads { threads: usize, error: rayon::ThreadPoolBuildError },
}

#[derive(Debug)]
pub struct RenderOutput {
    pub film: Film,
    /// Samples per pixel rendered: all of them unless `stopped`.
    pub spp_done: u32,
    pub stopped: Option<crate::render_stop::StopReason>,
    pub stats: RenderStats,
    pub backend: &'static str,
    /// Which of `stats.traversal` the backend filled in.
    pub observes: crate::accel::Observes,
    pub build_time: Duration,
    pub render_time: Duration,
    /// What the scene does that is likely a mistake (`unlit_emitters`).
    pub warnings: Vec<String>,
}

/// The render-space scene for `desc` under `options` (offset applied first, in world space).
pub fn prepare_scene(
    desc: &SceneDesc,
    options: &RenderOptions,
) -> Result<RenderScene, RenderError> {
    let mut desc = desc.clone();
    if options.offset != DVec3::ZERO {
        desc.translate(options.offset);
    }
    // Checked here, before either backend sees the scene, so both refuse the same scenes.
    crate::scene::budget::check_coordinates(&desc, options.render_space)?;
    to_render_scene(&desc, options.render_space, options.effects_mode)
        .map_err(|error| RenderError::Compile { file: desc.source.clone(), error })
}

/// "FILE: ", the prefix of an error in the scene file `file`, if it has a name.
fn in_file(file: &std::path::Path) -> String {
    match file.as_os_str().is_empty() {
        true => String::new(),
        false => format!("{}: ", file.display()),
    }
}

/// Renders `desc` from start to finish (or until `options.stop`).
pub fn render(desc: &SceneDesc, options: &RenderOptions) -> Result<RenderOutput, RenderError> {
    render_with(desc, options, &mut |_, _| {})
}

/// As [`render`], handing every pass's sums so far to `on_pass` (for checkpoints).
pub fn render_with(
    desc: &SceneDesc,
    options: &RenderOptions,
    on_pass: &mut OnPass<'_>,
) -> Result<RenderOutput, RenderError> {
    let part = render_part_with(desc, options, Part::WHOLE, on_pass)?;
    let film = match options.crop {
        Some(window) => part.sums.resolve().cropped(window),
        None => part.sums.resolve(),
    };
    let mut warnings = part.warnings;
    let brightest = film.color.iter().fold(0.0f32, |b, c| b.max(c.abs().max_element()));
    if brightest > 0.0 && brightest < crate::sample_sums::SMALLEST_EXACT {
        warnings.push(format!(
            "the brightest pixel is {brightest:.3e}, below {:.3e}, under which a pixel's exact \
             sums truncate each sample: the image has lost precision (scale the lights up)",
            crate::sample_sums::SMALLEST_EXACT
        ));
    }
    Ok(RenderOutput {
        spp_done: part.spp_done,
        stopped: part.stopped,
        film,
        stats: part.stats,
        backend: part.backend,
        observes: part.observes,
        build_time: part.build_time,
        render_time: part.render_time,
        warnings,
    })
}

/// What rendering one part gave: its sample sums, before they are resolved into an image.
#[derive(Debug)]
pub struct PartOutput {
    pub sums: FilmSums,
    pub spp_done: u32,
    pub stopped: Option<crate::render_stop::StopReason>,
    pub stats: RenderStats,
    pub backend: &'static str,
    pub observes: crate::accel::Observes,
    pub build_time: Duration,
    pub render_time: Duration,
    pub warnings: Vec<String>,
}

/// Renders `part` of `desc` (all of it for `Part::WHOLE`).
pub fn render_part(
    desc: &SceneDesc,
    options: &RenderOptions,
    part: Part,
) -> Result<PartOutput, RenderError> {
    render_part_with(desc, options, part, &mut |_, _| {})
}

/// As [`render_part`], handing every pass to `on_pass` (see [`render_passes`]).
pub fn render_part_with(
    desc: &SceneDesc,
    options: &RenderOptions,
    part: Part,
    on_pass: &mut OnPass<'_>,
) -> Result<PartOutput, RenderError> {
    check_options(options)?;
    // Saturating: a product past u64 is past the limit too, and must not wrap under it.
    let samples = u64::from(desc.camera.width)
        .saturating_mul(u64::from(desc.camera.height))
        .saturating_mul(u64::from(options.spp));
    if samples > crate::limits::MAX_SAMPLES {
        let max = crate::limits::MAX_SAMPLES;
        return Err(RenderError::Option { what: "pixels × spp", value: samples, max });
    }
    part.check((desc.camera.width, desc.camera.height), TILE_SIZE, options.spp.max(1))?;
    let triangle = options.backend.bytes_per_triangle();
    crate::scene::budget::check_memory(desc, triangle, options.worker_threads())?;
    let mut run = move || -> Result<PartOutput, RenderError> {
        let scene = prepare_scene(desc, options)?;
        let warnings = crate::unlit_emitters::emitters_facing_away(&scene);
        let build_start = Instant::now();
        let accel_options =
            AccelOptions { count_traversal: options.count_traversal, ..options.accel };
        let accel = accel::build(options.backend, &scene, &accel_options)?;
        let build_time = build_start.elapsed();
        let render_start = Instant::now();
        let passes = render_passes(&scene, accel.as_ref(), options, part, on_pass);
        let mut warnings = warnings;
        if let clamped @ 1.. = passes.stats.clamped_samples {
            warnings.push(format!(
                "{clamped} samples were brighter than {:.3e}, the most a pixel's exact sums \
                 hold for one sample, and were added as that (lights that bright are beyond \
                 what the film represents: scale them down, or give --clamp)",
                crate::sample_sums::LARGEST_SAMPLE
            ));
        }
        Ok(PartOutput {
            sums: passes.sums,
            stats: passes.stats,
            spp_done: passes.spp_done,
            stopped: passes.stopped,
            backend: accel.name(),
            observes: accel.observes(),
            build_time,
            render_time: render_start.elapsed(),
            warnings,
        })
    };
    match options.threads {
        Some(threads) => rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|error| RenderError::Threads { threads, error })?
            .install(run),
        None => run(),
    }
}

/// Counts beyond the documented limits (`crate::limits`) are refused, whoever built the
/// options.
fn check_options(options: &RenderOptions) -> Result<(), RenderError> {
    use crate::limits::{MAX_DEPTH, MAX_LIGHT_SAMPLES, MAX_SPP, MAX_THREADS};
    let checks = [
        ("spp", u64::from(options.spp), u64::from(MAX_SPP)),
        ("max_depth", u64::from(options.max_depth), u64::from(MAX_DEPTH)),
        ("light_samples", u64::from(options.light_samples), u64::from(MAX_LIGHT_SAMPLES)),
        ("the thread count", options.threads.unwrap_or(1) as u64, MAX_THREADS as u64),
    ];
    for (what, value, max) in checks {
        if value > max {
            return Err(RenderError::Option { what, value, max });
        }
    }
    Ok(())
}

/// Traces every pixel of `scene` with `accel` (see [`render_sums`]).
pub fn render_film(
    scene: &RenderScene,
    accel: &dyn Accel,
    options: &RenderOptions,
) -> (Film, RenderStats) {
    let (sums, stats) = render_sums(scene, accel, options, Part::WHOLE);
    (sums.resolve(), stats)
}

/// Traces `part` of `scene` with `accel`: the sums of its samples of its pixels (zero
/// elsewhere). Each tile is computed by one task from counter-based random numbers and
/// summed exactly (`sample_sums`), so the sums are bit-identical for any thread count and
/// any split.
pub fn render_sums(
    scene: &RenderScene,
    accel: &dyn Accel,
    options: &RenderOptions,
    part: Part,
) -> (FilmSums, RenderStats) {
    let passes = render_passes(scene, accel, options, part, &mut |_, _| {});
    (passes.sums, passes.stats)
}

/// As [`render_sums`], in passes over the whole part (`render_passes::pass_ranges`), each
/// handed to `on_pass` with the samples per pixel done so far; stops before its last pass
/// when `options.stop` asks (no new tile is started; the tiles done keep their samples).
pub fn render_passes(
    scene: &RenderScene,
    accel: &dyn Accel,
    options: &RenderOptions,
    part: Part,
    on_pass: &mut OnPass<'_>,
) -> Passes {
    let tracer = Tracer::new(scene, accel, options);
    let camera = &scene.camera;
    let mut all_tiles = part.tiles(&tiles(camera.width, camera.height, TILE_SIZE));
    if let Some(window) = options.crop {
        all_tiles.retain(|t| t.meets(&window));
    }
    let passes = pass_ranges(part.samples(options.spp.max(1)));
    let spp_total = passes.iter().map(|r| r.len() as u32).sum();
    let units = (all_tiles.len() * passes.len()) as u64;
    let progress = Progress::new(options.progress, units, spp_total);
    let stop = || options.stop.as_ref().and_then(|s| s.requested());
    // From here a first signal stops the render with the passes done; before (reading the
    // scene, its tables, the acceleration structure) there is nothing to keep, and it quits
    // at once.
    if let Some(stop) = &options.stop {
        stop.watch();
    }
    let mut done = Passes {
        sums: FilmSums::new(camera.width, camera.height),
        stats: RenderStats::default(),
        spp_done: 0,
        stopped: None,
    };
    let scratches = WorkerScratches::for_pool();
    for samples in passes {
        // Each tile is added to the film as it ends (exact sums: in any order), so no copy
        // of the image's sums is held per pass. A stop leaves the tiles of the pass not yet
        // done: they keep one pass fewer (every pixel is the mean of its own samples).
        let film = Mutex::new((
            std::mem::replace(&mut done.sums, FilmSums::new(0, 0)),
            RenderStats::default(),
            0usize,
        ));
        // One tile per rayon job: with longer runs of tiles, rayon splits a range only
        // when another thread steals it, and a thread that ran out of work waited for the
        // other's run to end at each pass's end.
        all_tiles.par_iter().with_max_len(1).for_each(|&tile| {
            if stop().is_some() {
                return;
            }
            let traced = scratches
                .with(|scratch| render_tile(&tracer, tile, samples.clone(), options, scratch));
            let Some(r) = traced else {
                return;
            };
            progress.tile_done(r.stats.total_rays());
            let mut film = film.lock().unwrap_or_else(PoisonError::into_inner);
            add_tile(&mut film.0, r.tile, &r.sums);
            film.1 += r.stats;
            film.2 += 1;
        });
        let (sums, stats, tiles_done) = film.into_inner().unwrap_or_else(PoisonError::into_inner);
        done.sums = sums;
        done.stats += stats;
        if let Some(reason) = stop().filter(|_| tiles_done < all_tiles.len()) {
            done.stopped = Some(reason);
            break;
        }
        done.spp_done += samples.len() as u32;
        on_pass(&done.sums, done.spp_done);
        if let Some(reason) = stop().filter(|_| done.spp_done < spp_total) {
            done.stopped = Some(reason);
            break;
        }
    }
    progress.finish();
    done
}
