//! One render from a scene description: convert to render space, build the backend, trace
//! tiles in parallel, gather film and counters.

use crate::accel::{self, Accel, AccelError, AccelOptions};
use crate::compile::{CompileError, to_render_scene};
use crate::distributed::{Part, PartError};
use crate::film::{Film, Tile, tiles};
use crate::integrator::{PathSample, Tracer};
use crate::ray::{Hit, Ray};
use crate::render_passes::{Passes, Progress, add_tile, pass_ranges};
use crate::render_scene::RenderScene;
use crate::sample_sums::{FilmSums, PixelSums};
use crate::sampling::{SLOT_LENS, SLOT_TIME, SampleStream};
use crate::scene::SceneDesc;
use crate::stats::RenderStats;
use glam::{DVec3, Vec2, Vec3};
use rayon::prelude::*;
use std::sync::{Mutex, PoisonError};
use std::time::{Duration, Instant};

/// Side of the square tiles rayon schedules, one task each (`par_iter` over the tiles,
/// buffers reused per worker). Measured on the Cornell box and the 1M-triangle sphere:
/// 8, 16, 32 and 64 cost the same CPU time within 1 %; 16 gives 256 tasks for a 256×256
/// image, plenty to balance two threads, so it stays.
pub const TILE_SIZE: u32 = 16;

pub use crate::render_options::RenderOptions;

/// What a render calls after each pass with the sums so far and the samples per pixel done.
pub type OnPass<'a> = dyn FnMut(&FilmSums, u32) + Send + 'a;

#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Compile(#[from] CompileError),
    #[error(transparent)]
    Accel(#[from] AccelError),
    #[error(transparent)]
    Limit(#[from] crate::scene::budget::LimitError),
    #[error("{what} is {value}, but must be at most {max}")]
    Option { what: &'static str, value: u64, max: u64 },
    #[error(transparent)]
    Part(#[from] PartError),
    #[error("could not start {threads} worker threads: {source}")]
    Threads { threads: usize, source: rayon::ThreadPoolBuildError },
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
    Ok(to_render_scene(&desc, options.render_space, options.effects_mode)?)
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
    Ok(RenderOutput {
        spp_done: part.spp_done,
        stopped: part.stopped,
        film: match options.crop {
            Some(window) => part.sums.resolve().cropped(window),
            None => part.sums.resolve(),
        },
        stats: part.stats,
        backend: part.backend,
        observes: part.observes,
        build_time: part.build_time,
        render_time: part.render_time,
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
    crate::scene::budget::check_memory(desc, options.backend.bytes_per_triangle())?;
    let mut run = move || -> Result<PartOutput, RenderError> {
        let scene = prepare_scene(desc, options)?;
        let build_start = Instant::now();
        let accel_options =
            AccelOptions { count_traversal: options.count_traversal, ..options.accel };
        let accel = accel::build(options.backend, &scene, &accel_options)?;
        let build_time = build_start.elapsed();
        let render_start = Instant::now();
        let passes = render_passes(&scene, accel.as_ref(), options, part, on_pass);
        Ok(PartOutput {
            sums: passes.sums,
            stats: passes.stats,
            spp_done: passes.spp_done,
            stopped: passes.stopped,
            backend: accel.name(),
            observes: accel.observes(),
            build_time,
            render_time: render_start.elapsed(),
        })
    };
    match options.threads {
        Some(threads) => rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|source| RenderError::Threads { threads, source })?
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

struct TileResult {
    tile: Tile,
    /// The tile's pixels, row-major.
    sums: Vec<PixelSums>,
    stats: RenderStats,
}

/// Most camera rays generated and intersected as one batch: one sample index of every pixel
/// of a tile.
pub const CAMERA_BATCH: usize = (TILE_SIZE * TILE_SIZE) as usize;

/// Buffers one worker reuses from tile to tile, so tracing a tile allocates only its result.
#[derive(Default)]
struct TileScratch {
    rays: Vec<Ray>,
    streams: Vec<SampleStream>,
    hits: Vec<Option<Hit>>,
    backdrops: Vec<Option<Vec3>>,
    weights: Vec<f32>,
}

/// The camera ray of sample `s` of pixel (`x`, `y`), the random stream its path goes on
/// with, the scene's backdrop behind it (if it has one), and the sample's filter weight.
fn camera_sample(
    scene: &RenderScene,
    options: &RenderOptions,
    (x, y): (u32, u32),
    s: u32,
    spp: u32,
) -> (Ray, SampleStream, Option<Vec3>, f32) {
    let camera = &scene.camera;
    let pixel = y as u64 * camera.width as u64 + x as u64;
    let mut stream = SampleStream::new(options.sampler, options.seed, pixel, s as u64);
    let uniform = stream.pixel_position(s, spp, options.jitters());
    let (in_pixel, weight) = scene.pixel_filter.sample((x, y), uniform);
    let raster = Vec2::new(x as f32, y as f32) + in_pixel;
    let effects = &scene.effects;
    let lens = effects.depth_of_field.then(|| stream.reserved_2d(SLOT_LENS));
    let mut ray = camera.generate_ray(raster, lens);
    if effects.motion_blur {
        ray.time = stream.reserved_1d(SLOT_TIME);
    }
    (ray, stream, scene.backdrop_at(raster), weight)
}

/// Renders the samples `samples` of every pixel of one tile. With the path tracer on a
/// backend that traces batches faster (`Accel::prefers_batches`: Embree packets), the camera
/// rays of one sample index of every pixel of the tile are generated first (the same random
/// numbers as one at a time), intersected as one batch (`Accel::intersect_batch`, whose hits
/// equal single-ray ones but for ties between coincident surfaces, see `BatchMode`), and each
/// path then continues from its first hit. A batch depends only on the tile and the sample
/// index, never on the sample range, so a render split into sample ranges traces the same
/// packets as the whole one and merges to the same image bit for bit.
fn render_tile(
    tracer: &Tracer,
    tile: Tile,
    samples: std::ops::Range<u32>,
    options: &RenderOptions,
    scratch: &mut TileScratch,
) -> Option<TileResult> {
    let scene = tracer.scene();
    let width = (tile.x1 - tile.x0) as usize;
    let n = width * (tile.y1 - tile.y0) as usize;
    let mut result =
        TileResult { tile, sums: vec![PixelSums::default(); n], stats: RenderStats::default() };
    let spp = options.spp.max(1);
    let pixel = |i: usize| (tile.x0 + (i % width) as u32, tile.y0 + (i / width) as u32);
    let clamp = options.clamp;
    let add = |sums: &mut PixelSums, sample: PathSample, weight: f32| {
        let radiance = match clamp {
            Some(limit) if sample.radiance.max_element() > limit => {
                sample.radiance * (limit / sample.radiance.max_element())
            }
            _ => sample.radiance,
        };
        // The box filter's weight is exactly 1, and x · 1 is x: its renders are unchanged.
        sums.add_sample(radiance * weight, sample.depth, sample.normal, sample.albedo)
    };
    let batched = match tracer {
        Tracer::Path(path) if path.accel().prefers_batches() => Some(path),
        _ => None,
    };
    // A stop ends the tile too (its pass is dropped), so that a long pass stops promptly.
    let stopped = || options.stop.as_ref().is_some_and(|s| s.requested().is_some());
    let Some(path) = batched else {
        for (i, sums) in result.sums.iter_mut().enumerate() {
            if i % 16 == 0 && stopped() {
                return None;
            }
            for s in samples.clone() {
                let (ray, mut stream, backdrop, weight) =
                    camera_sample(scene, options, pixel(i), s, spp);
                add(sums, tracer.trace(ray, backdrop, &mut stream, &mut result.stats), weight);
            }
        }
        return Some(result);
    };
    for s in samples {
        if stopped() {
            return None;
        }
        scratch.rays.clear();
        scratch.streams.clear();
        scratch.backdrops.clear();
        scratch.weights.clear();
        for i in 0..n {
            let (ray, stream, backdrop, weight) = camera_sample(scene, options, pixel(i), s, spp);
            scratch.rays.push(ray);
            scratch.streams.push(stream);
            scratch.backdrops.push(backdrop);
            scratch.weights.push(weight);
        }
        scratch.hits.clear();
        scratch.hits.resize(n, None);
        path.accel().intersect_batch(&scratch.rays, &mut scratch.hits, &mut result.stats.traversal);
        let traced = scratch.rays.iter().zip(&scratch.hits).zip(&mut scratch.streams);
        for (((sums, ((ray, hit), stream)), backdrop), weight) in
            result.sums.iter_mut().zip(traced).zip(&scratch.backdrops).zip(&scratch.weights)
        {
            let sample = path.trace(*ray, Some(*hit), *backdrop, stream, &mut result.stats);
            add(sums, sample, *weight);
        }
    }
    Some(result)
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
    let tracer = Tracer::new(
        options.integrator,
        scene,
        accel,
        options.max_depth,
        options.light_samples,
        options.spawn,
        options.energy,
    );
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
    let mut done = Passes {
        sums: FilmSums::new(camera.width, camera.height),
        stats: RenderStats::default(),
        spp_done: 0,
        stopped: None,
    };
    for samples in passes {
        // Each tile is added to the film as it ends (exact sums: in any order), so no copy
        // of the image's sums is held per pass. A stop leaves the tiles of the pass not yet
        // done: they keep one pass fewer (every pixel is the mean of its own samples).
        let film = Mutex::new((
            std::mem::replace(&mut done.sums, FilmSums::new(0, 0)),
            RenderStats::default(),
            0usize,
        ));
        all_tiles.par_iter().for_each_init(TileScratch::default, |scratch, &tile| {
            if stop().is_some() {
                return;
            }
            let Some(r) = render_tile(&tracer, tile, samples.clone(), options, scratch) else {
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
