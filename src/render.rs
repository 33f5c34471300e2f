//! One render from a scene description: convert to render space, build the backend, trace
//! tiles in parallel, gather film and counters.

use crate::accel::{self, Accel, AccelError, AccelOptions, BackendKind};
use crate::compile::{CompileError, EffectsMode, to_render_scene};
use crate::film::{Film, Tile, tiles};
use crate::integrator::{PathSample, Tracer};
use crate::ray::{Hit, Ray};
use crate::render_scene::RenderScene;
use crate::render_space::RenderSpace;
use crate::sampling::{SLOT_LENS, SLOT_TIME, SampleStream, SamplerKind};
use crate::scene::IntegratorKind;
use crate::scene::SceneDesc;
use crate::shading::spawn::SpawnMode;
use crate::stats::RenderStats;
use glam::{DVec3, Vec2, Vec3};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// Side of the square tiles rayon schedules, one task each (`par_iter` over the tiles,
/// buffers reused per worker). Measured on the Cornell box and the 1M-triangle sphere:
/// 8, 16, 32 and 64 cost the same CPU time within 1 %; 16 gives 256 tasks for a 256×256
/// image, plenty to balance two threads, so it stays.
const TILE_SIZE: u32 = 16;

/// Validated options of one render (command line, or tests).
#[derive(Clone, Debug)]
pub struct RenderOptions {
    pub spp: u32,
    pub max_depth: u32,
    pub seed: u64,
    /// Jitter samples inside their strata (off: stratum centres, for reproducible tests).
    /// A Whitted render at 1 spp always samples pixel centres, as the course does.
    pub jitter: bool,
    /// Worker threads; `None` uses every core.
    pub threads: Option<usize>,
    pub backend: BackendKind,
    pub render_space: RenderSpace,
    /// Moves the whole scene and camera (world space, f64) before rendering.
    pub offset: DVec3,
    pub count_traversal: bool,
    /// How the backend is built (its `count_traversal` is replaced by the one above).
    pub accel: AccelOptions,
    pub progress: bool,
    /// Shadow rays to emitters per shading point.
    pub light_samples: u32,
    pub effects_mode: EffectsMode,
    pub integrator: IntegratorKind,
    pub spawn: SpawnMode,
    pub sampler: SamplerKind,
}

impl RenderOptions {
    /// Options taking spp and depth from the scene's own settings.
    pub fn for_scene(scene: &SceneDesc) -> Self {
        RenderOptions {
            spp: scene.settings.spp,
            max_depth: scene.settings.max_depth,
            seed: 0,
            jitter: true,
            threads: None,
            backend: BackendKind::default_compiled(),
            render_space: RenderSpace::default(),
            offset: DVec3::ZERO,
            count_traversal: false,
            accel: AccelOptions::DEFAULT,
            progress: false,
            light_samples: scene.settings.light_samples,
            effects_mode: EffectsMode::Auto,
            integrator: scene.settings.integrator,
            spawn: SpawnMode::Robust,
            sampler: SamplerKind::default(),
        }
    }
}

impl RenderOptions {
    /// Whether sample positions are jittered: as asked, except that a Whitted render at one
    /// sample per pixel samples pixel centres (the course's convention).
    pub fn jitters(&self) -> bool {
        let centred = self.integrator == IntegratorKind::Whitted && self.spp == 1;
        self.jitter && !centred
    }
}

#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Compile(#[from] CompileError),
    #[error(transparent)]
    Accel(#[from] AccelError),
    #[error(transparent)]
    Limit(#[from] crate::limits::LimitError),
    #[error("{what} is {value}, but must be at most {max}")]
    Option { what: &'static str, value: u64, max: u64 },
    #[error("could not start {threads} worker threads: {source}")]
    Threads { threads: usize, source: rayon::ThreadPoolBuildError },
}

#[derive(Debug)]
pub struct RenderOutput {
    pub film: Film,
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
    crate::limits::check_coordinates(&desc, options.render_space)?;
    Ok(to_render_scene(&desc, options.render_space, options.effects_mode)?)
}

/// Renders `desc` from start to finish.
pub fn render(desc: &SceneDesc, options: &RenderOptions) -> Result<RenderOutput, RenderError> {
    check_options(options)?;
    let samples =
        u64::from(desc.camera.width) * u64::from(desc.camera.height) * u64::from(options.spp);
    if samples > crate::limits::MAX_SAMPLES {
        let max = crate::limits::MAX_SAMPLES;
        return Err(RenderError::Option { what: "pixels × spp", value: samples, max });
    }
    crate::limits::check_memory(desc)?;
    let run = || -> Result<RenderOutput, RenderError> {
        let scene = prepare_scene(desc, options)?;
        let build_start = Instant::now();
        let accel_options =
            AccelOptions { count_traversal: options.count_traversal, ..options.accel };
        let accel = accel::build(options.backend, &scene, &accel_options)?;
        let build_time = build_start.elapsed();
        let render_start = Instant::now();
        let (film, stats) = render_film(&scene, accel.as_ref(), options);
        Ok(RenderOutput {
            film,
            stats,
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
    color: Vec<Vec3>,
    depth: Vec<f32>,
    normal: Vec<Vec3>,
    stats: RenderStats,
}

/// How many camera rays are generated and intersected as one batch: a run of a tile's
/// samples, which may end inside a pixel.
pub const CAMERA_BATCH: usize = 1024;

/// Buffers one worker reuses from tile to tile, so tracing a tile allocates only its result.
#[derive(Default)]
struct TileScratch {
    rays: Vec<Ray>,
    streams: Vec<SampleStream>,
    hits: Vec<Option<Hit>>,
}

/// The camera ray of sample `s` of pixel (`x`, `y`) and the random stream its path goes on
/// with.
fn camera_sample(
    scene: &RenderScene,
    options: &RenderOptions,
    (x, y): (u32, u32),
    s: u32,
    spp: u32,
) -> (Ray, SampleStream) {
    let camera = &scene.camera;
    let pixel = y as u64 * camera.width as u64 + x as u64;
    let mut stream = SampleStream::new(options.sampler, options.seed, pixel, s as u64);
    let in_pixel = stream.pixel_position(s, spp, options.jitters());
    let raster = Vec2::new(x as f32, y as f32) + in_pixel;
    let effects = &scene.effects;
    let lens = effects.depth_of_field.then(|| stream.reserved_2d(SLOT_LENS));
    let mut ray = camera.generate_ray(raster, lens);
    if effects.motion_blur {
        ray.time = stream.reserved_1d(SLOT_TIME);
    }
    (ray, stream)
}

/// The samples of one pixel, summed in sample order.
#[derive(Default)]
struct PixelSum {
    color: DVec3,
    depth_sum: f64,
    depth_count: u32,
    normal: DVec3,
}

impl PixelSum {
    fn add(&mut self, sample: &PathSample) {
        self.color += sample.radiance.as_dvec3();
        if let Some(d) = sample.depth {
            self.depth_sum += d as f64;
            self.depth_count += 1;
        }
        if let Some(nrm) = sample.normal {
            self.normal += nrm.as_dvec3();
        }
    }
}

impl TileResult {
    /// Appends the pixel's colour, depth and normal.
    fn push(&mut self, sum: PixelSum, spp: u32) {
        self.color.push((sum.color / spp as f64).as_vec3());
        self.depth.push(if sum.depth_count > 0 {
            (sum.depth_sum / sum.depth_count as f64) as f32
        } else {
            f32::INFINITY
        });
        self.normal.push(sum.normal.normalize_or_zero().as_vec3());
    }
}

/// Renders one tile. With the path tracer on a backend that traces batches faster
/// (`Accel::prefers_batches`: Embree packets), the camera rays of a chunk of pixels are
/// generated first (same order, same random numbers as one at a time), intersected as one
/// batch (`Accel::intersect_batch`, whose hits equal single-ray ones but for ties between
/// coincident surfaces, see `BatchMode`), and each path then continues from its first hit:
/// the image is the same as tracing sample by sample.
fn render_tile(
    tracer: &Tracer,
    tile: Tile,
    options: &RenderOptions,
    scratch: &mut TileScratch,
) -> TileResult {
    let scene = tracer.scene();
    let n = ((tile.x1 - tile.x0) * (tile.y1 - tile.y0)) as usize;
    let mut result = TileResult {
        tile,
        color: Vec::with_capacity(n),
        depth: Vec::with_capacity(n),
        normal: Vec::with_capacity(n),
        stats: RenderStats::default(),
    };
    let spp = options.spp.max(1);
    let batched = match tracer {
        Tracer::Path(path) if path.accel().prefers_batches() => Some(path),
        _ => None,
    };
    let Some(path) = batched else {
        for y in tile.y0..tile.y1 {
            for x in tile.x0..tile.x1 {
                let mut sum = PixelSum::default();
                for s in 0..spp {
                    let (ray, mut stream) = camera_sample(scene, options, (x, y), s, spp);
                    sum.add(&tracer.trace(ray, &mut stream, &mut result.stats));
                }
                result.push(sum, spp);
            }
        }
        return result;
    };
    // The tile's samples as one stream, pixel by pixel and sample by sample, cut into
    // batches of `CAMERA_BATCH`: memory stays bounded whatever the spp (a pixel's samples
    // may span batches; its sum carries over).
    let width = (tile.x1 - tile.x0) as usize;
    let spp_n = spp as usize;
    let total = n * spp_n;
    let mut sum = PixelSum::default();
    let mut first = 0;
    while first < total {
        let last = (first + CAMERA_BATCH).min(total);
        let pixel = |i: usize| (tile.x0 + (i % width) as u32, tile.y0 + (i / width) as u32);
        scratch.rays.clear();
        scratch.streams.clear();
        for g in first..last {
            let (ray, stream) =
                camera_sample(scene, options, pixel(g / spp_n), (g % spp_n) as u32, spp);
            scratch.rays.push(ray);
            scratch.streams.push(stream);
        }
        scratch.hits.clear();
        scratch.hits.resize(scratch.rays.len(), None);
        path.accel().intersect_batch(&scratch.rays, &mut scratch.hits, &mut result.stats.traversal);
        let samples = scratch.rays.iter().zip(&scratch.hits).zip(&mut scratch.streams);
        for (k, ((ray, hit), stream)) in samples.enumerate() {
            sum.add(&path.trace(*ray, Some(*hit), stream, &mut result.stats));
            if (first + k + 1) % spp_n == 0 {
                result.push(std::mem::take(&mut sum), spp);
            }
        }
        first = last;
    }
    result
}

/// Traces every pixel of `scene` with `accel`. Each pixel is computed by one task from
/// counter-based random numbers, so the image is bit-identical for any thread count.
pub fn render_film(
    scene: &RenderScene,
    accel: &dyn Accel,
    options: &RenderOptions,
) -> (Film, RenderStats) {
    let tracer = Tracer::new(
        options.integrator,
        scene,
        accel,
        options.max_depth,
        options.light_samples,
        options.spawn,
    );
    let camera = &scene.camera;
    let all_tiles = tiles(camera.width, camera.height, TILE_SIZE);
    let progress = if options.progress {
        let bar = ProgressBar::with_draw_target(
            Some(all_tiles.len() as u64),
            ProgressDrawTarget::stderr(),
        );
        if let Ok(style) =
            ProgressStyle::with_template("{bar:40} {percent:>3}% {elapsed}<{eta} {msg}")
        {
            bar.set_style(style);
        }
        bar
    } else {
        ProgressBar::hidden()
    };
    let results: Vec<TileResult> = all_tiles
        .par_iter()
        .map_init(TileScratch::default, |scratch, &tile| {
            let r = render_tile(&tracer, tile, options, scratch);
            progress.inc(1);
            r
        })
        .collect();
    progress.finish_and_clear();
    let mut film = Film::new(camera.width, camera.height);
    let mut stats = RenderStats::default();
    for r in results {
        let mut i = 0;
        for y in r.tile.y0..r.tile.y1 {
            for x in r.tile.x0..r.tile.x1 {
                let idx = film.index(x, y);
                film.color[idx] = r.color[i];
                film.depth[idx] = r.depth[i];
                film.normal[idx] = r.normal[i];
                i += 1;
            }
        }
        stats += r.stats;
    }
    (film, stats)
}
