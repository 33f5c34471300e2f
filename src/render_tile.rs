//! One tile of a render: the camera samples of its pixels for a range of sample indices,
//! traced one at a time or, with the path tracer, as a batch of the paths of one sample
//! index of every pixel of the tile.

use crate::film::Tile;
use crate::integrator::{PathSample, Tracer, Wavefront};
use crate::phase_times::{Phase, PhaseClock};
use crate::ray::Ray;
use crate::render_options::{PathBatching, RenderOptions};
use crate::render_scene::RenderScene;
use crate::sample_sums::PixelSums;
use crate::sampling::{self, PixelStreams, SLOT_LENS, SLOT_TIME, SampleStream};
use crate::stats::RenderStats;
use glam::{Vec2, Vec3};
use std::sync::{Mutex, TryLockError};

/// Side of the square tiles rayon schedules, one task each (`par_iter` over the tiles,
/// buffers reused per worker); the batched path tracer advances one sample index of a
/// tile's pixels together, so it is also the batch: 256 paths. 32 (1024 paths) was
/// measured and left out (alternated pairs, AVX-512 Xeon, same images bit for bit): small
/// scenes gain, as each bounce's last, partly empty block of lanes, Sobol draws and
/// packets is a smaller share (0.976× the wall time on the peers' Cornell box, 0.968× the
/// glass scene, 0.965× the city block, 0.989× the box on obvhs), but the 1M-triangle
/// sphere of `embray bench speed` lost 1–4 % of its samples a second on both backends (two
/// alternated runs each; presumably the larger batch's working set competing with the BVH
/// for the caches, not measured), and on the AVX2 EPYC batches of 1024 paths had cost the
/// Cornell box 1.015× its time. 24 and 48 were no better on the box than 32, and 64 worse
/// (1.059× 32's time). (With scalar paths, before the batches, 8 to 64 cost the same
/// within 1 %.)
pub const TILE_SIZE: u32 = 16;

/// What one tile's task gives: its pixels' sums (row-major) and its counters.
pub(crate) struct TileResult {
    pub tile: Tile,
    /// The tile's pixels, row-major.
    pub sums: Vec<PixelSums>,
    pub stats: RenderStats,
}

/// Most camera rays generated and intersected as one batch: one sample index of every pixel
/// of a tile.
pub const CAMERA_BATCH: usize = (TILE_SIZE * TILE_SIZE) as usize;

/// Buffers one worker reuses from tile to tile, so tracing a tile allocates only its result.
#[derive(Default)]
pub(crate) struct TileScratch {
    /// The batch's paths, and their random streams (made before their camera rays).
    wavefront: Wavefront,
    /// The batch's camera rays, and what they are made from.
    camera: CameraSamples,
    /// The tile's pixels (`Tile::pixels`): listed once per tile, not found from a sample's
    /// index by two integer divisions per camera ray.
    pixels: Vec<(u32, u32)>,
    /// What the random streams of each pixel's samples share, hashed once per tile.
    pixel_streams: Vec<PixelStreams>,
}

/// The camera samples of a batch, in order: each one's pixel-position draw, where in the
/// image it lies, its filter weight and its ray.
#[derive(Default)]
struct CameraSamples {
    positions: Vec<Vec2>,
    rasters: Vec<Vec2>,
    weights: Vec<f32>,
    rays: Vec<Ray>,
}

/// One `TileScratch` per worker of the rayon pool, kept for a whole render: rayon's
/// `for_each_init` would make one per job (one per tile when each tile is a job), whose
/// buffers would grow afresh every time.
pub(crate) struct WorkerScratches(Vec<Mutex<TileScratch>>);

impl WorkerScratches {
    /// One per thread of the current pool.
    pub fn for_pool() -> Self {
        WorkerScratches((0..rayon::current_num_threads()).map(|_| Mutex::default()).collect())
    }

    /// `f` of the calling worker's scratch; of a fresh one outside the pool, or where the
    /// worker's is in use (a tile taken while in another, should rayon nest them).
    pub fn with<R>(&self, f: impl FnOnce(&mut TileScratch) -> R) -> R {
        let own = rayon::current_thread_index().and_then(|i| self.0.get(i));
        let held = own.and_then(|scratch| match scratch.try_lock() {
            Ok(held) => Some(held),
            Err(TryLockError::Poisoned(poisoned)) => Some(poisoned.into_inner()),
            Err(TryLockError::WouldBlock) => None,
        });
        match held {
            Some(mut held) => f(&mut held),
            None => f(&mut TileScratch::default()),
        }
    }
}

/// The random streams of pixel `(x, y)`'s samples.
fn pixel_streams(scene: &RenderScene, options: &RenderOptions, (x, y): (u32, u32)) -> PixelStreams {
    let pixel = y as u64 * scene.camera.width as u64 + x as u64;
    PixelStreams::new(options.sampler, options.seed, pixel)
}

/// The camera ray through `pixel` at `uniform` (the sample's position draw,
/// `SampleStream::pixel_position`) with the rest of its draws from `stream`, the scene's
/// backdrop behind it (if it has one), and the sample's filter weight.
#[inline(always)]
fn camera_ray(
    scene: &RenderScene,
    pixel: (u32, u32),
    uniform: Vec2,
    stream: &SampleStream,
) -> (Ray, Option<Vec3>, f32) {
    let (raster, weight) = raster_position(scene, pixel, uniform);
    let mut ray = scene.camera.generate_ray(raster, lens_sample(scene, stream));
    set_time(scene, &mut ray, stream);
    (ray, scene.backdrop_at(raster), weight)
}

/// Where in the image a sample of pixel (`x`, `y`) at `uniform` lies, and its filter weight.
#[inline(always)]
fn raster_position(scene: &RenderScene, (x, y): (u32, u32), uniform: Vec2) -> (Vec2, f32) {
    let (in_pixel, weight) = scene.pixel_filter.sample((x, y), uniform);
    (Vec2::new(x as f32, y as f32) + in_pixel, weight)
}

/// The lens draw, where the scene has depth of field.
#[inline(always)]
fn lens_sample(scene: &RenderScene, stream: &SampleStream) -> Option<Vec2> {
    scene.effects.depth_of_field.then(|| stream.reserved_2d(SLOT_LENS))
}

/// The ray's time, drawn from `stream` where the scene has motion blur.
#[inline(always)]
fn set_time(scene: &RenderScene, ray: &mut Ray, stream: &SampleStream) {
    if scene.effects.motion_blur {
        ray.time = stream.reserved_1d(SLOT_TIME);
    }
}

impl CameraSamples {
    /// The samples of a batch: one of each pixel of `pixels`, drawn from its stream in
    /// `streams` (`draw`: the sample index, the pixel's sample count and whether positions
    /// are jittered, as `sampling::pixel_positions` takes them). Each is `camera_ray`'s but
    /// for the backdrop, which the caller looks up from `rasters`; a pinhole camera's rays
    /// are computed together (`Camera::pinhole_rays`).
    fn make(
        &mut self,
        scene: &RenderScene,
        pixels: &[(u32, u32)],
        streams: &mut [SampleStream],
        draw: (u32, u32, bool),
    ) {
        let CameraSamples { positions, rasters, weights, rays } = self;
        sampling::pixel_positions(streams, draw, positions);
        rasters.clear();
        weights.clear();
        rays.clear();
        for (&pixel, &uniform) in pixels.iter().zip(positions.iter()) {
            let (raster, weight) = raster_position(scene, pixel, uniform);
            rasters.push(raster);
            weights.push(weight);
        }
        let camera = &scene.camera;
        if camera.is_pinhole() {
            camera.pinhole_rays(rasters, rays);
        } else {
            let generated = rasters.iter().zip(streams.iter());
            let ray = |(&raster, stream)| camera.generate_ray(raster, lens_sample(scene, stream));
            rays.extend(generated.map(ray));
        }
        for (ray, stream) in rays.iter_mut().zip(streams.iter()) {
            set_time(scene, ray, stream);
        }
    }
}

/// Renders the samples `samples` of every pixel of one tile. The path tracer (unless asked
/// for scalar paths) advances the paths of one sample index of every pixel of the tile
/// together, a bounce at a time (`Wavefront`: rays in packets, each path shaded as the
/// scalar integrator shades it, with the same random numbers), so the image is the scalar
/// one. A batch depends only on the tile and the sample index, never on the sample range,
/// so a render split into sample ranges traces the same packets as the whole one and
/// merges to the same image bit for bit.
pub(crate) fn render_tile(
    tracer: &Tracer,
    tile: Tile,
    samples: std::ops::Range<u32>,
    options: &RenderOptions,
    scratch: &mut TileScratch,
) -> Option<TileResult> {
    let scene = tracer.scene();
    scratch.pixels.clear();
    scratch.pixels.extend(tile.pixels());
    scratch.pixel_streams.clear();
    let streams_of = |&pixel: &(u32, u32)| pixel_streams(scene, options, pixel);
    scratch.pixel_streams.extend(scratch.pixels.iter().map(streams_of));
    let n = scratch.pixels.len();
    let mut result =
        TileResult { tile, sums: vec![PixelSums::default(); n], stats: RenderStats::default() };
    let spp = options.spp.max(1);
    let clamp = options.clamp;
    let add = |sums: &mut PixelSums, sample: &PathSample, weight: f32| {
        let radiance = match clamp {
            Some(limit) if sample.radiance.max_element() > limit => {
                sample.radiance * (limit / sample.radiance.max_element())
            }
            _ => sample.radiance,
        };
        // The box filter's weight is exactly 1, and x · 1 is x: its renders are unchanged.
        let radiance = radiance * weight;
        sums.add_sample(radiance, sample.depth, sample.normal, sample.albedo);
        // Whether the sums held it whole (a light of 10¹⁶ seen directly does not).
        u64::from(radiance.abs().max_element() > crate::sample_sums::LARGEST_SAMPLE)
    };
    let batched = match tracer {
        Tracer::Path(path) if options.paths == PathBatching::Batched => Some(path),
        _ => None,
    };
    // A stop ends the tile too (its pass is dropped), so that a long pass stops promptly.
    let stopped = || options.stop.as_ref().is_some_and(|s| s.requested().is_some());
    let Some(path) = batched else {
        let pixels = scratch.pixels.iter().zip(&scratch.pixel_streams);
        for (i, (sums, (&pixel, streams))) in result.sums.iter_mut().zip(pixels).enumerate() {
            if i % 16 == 0 && stopped() {
                return None;
            }
            for s in samples.clone() {
                let mut stream = streams.stream(s.into());
                let uniform = stream.pixel_position(s, spp, options.jitters());
                let (ray, backdrop, weight) = camera_ray(scene, pixel, uniform, &stream);
                let sample = tracer.trace(ray, backdrop, &mut stream, &mut result.stats);
                result.stats.clamped_samples += add(sums, &sample, weight);
            }
        }
        // A Whitted tree stops mid-sample on a stop: the tile's last samples may be cut.
        return (!stopped()).then_some(result);
    };
    let wavefront = &mut scratch.wavefront;
    let mut clock = PhaseClock::new(options.time_phases);
    for s in samples {
        if stopped() {
            return None;
        }
        let streams = wavefront.begin(scratch.pixel_streams.iter().map(|p| p.stream(s.into())));
        let draw = (s, spp, options.jitters());
        let camera = &mut scratch.camera;
        camera.make(scene, &scratch.pixels, streams, draw);
        let rays = camera.rays.iter().zip(&camera.rasters);
        wavefront
            .start_paths(rays.map(|(&ray, &raster)| path.start(ray, scene.backdrop_at(raster))));
        clock.lap(Phase::CameraRays, &mut result.stats.phases);
        wavefront.run(path, &mut result.stats, &mut clock);
        for ((sums, sample), weight) in
            result.sums.iter_mut().zip(wavefront.results()).zip(&scratch.camera.weights)
        {
            result.stats.clamped_samples += add(sums, sample, *weight);
        }
        clock.lap(Phase::Accumulate, &mut result.stats.phases);
    }
    Some(result)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A worker gets its own scratch back, as it left it; a call from outside the pool, or
    /// nested in the worker's own, gets a fresh one.
    #[test]
    fn a_worker_keeps_its_scratch_and_others_get_fresh_ones() {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().expect("a pool");
        let scratches = pool.install(WorkerScratches::for_pool);
        assert_eq!(scratches.with(|s| s.pixels.len()), 0, "outside the pool");
        pool.install(|| {
            scratches.with(|s| s.pixels.push((3, 4)));
            let nested = scratches.with(|s| (s.pixels.clone(), scratches.with(|t| t.pixels.len())));
            assert_eq!(nested, (vec![(3, 4)], 0));
        });
        assert_eq!(scratches.with(|s| s.pixels.len()), 0, "outside the pool again");
    }
}
