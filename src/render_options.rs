//! The options of one render, validated: samples, depth, seed, backend, render space, and
//! the switches that compare methods (sampler, spawning, lobe energy, effects).

use crate::accel::{AccelOptions, BackendKind};
use crate::compile::EffectsMode;
use crate::render_space::RenderSpace;
use crate::sampling::SamplerKind;
use crate::scene::{IntegratorKind, SceneDesc};
use crate::shading::spawn::SpawnMode;
use glam::DVec3;

/// How the path tracer advances its paths. Both give the same image bit for bit (each
/// path's arithmetic and random numbers are the same; the batched queries return the
/// single-ray answers), so the scalar one is the reference the batched one is tested
/// against.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PathBatching {
    /// The paths of one sample index of a tile's pixels together, a bounce at a time: their
    /// rays traced as packets (Embree `rtcIntersect8/16`, `rtcOccluded8/16`).
    #[default]
    Batched,
    /// One path at a time, one ray at a time.
    Scalar,
    /// As `Scalar`, with every BSDF through the general code, plain Lambertian ones
    /// included: the reference the vectorised Lambertian lanes are checked against.
    Reference,
}

crate::choice::named_choices!(PathBatching, "path batching", {
    Batched => "batched",
    Scalar => "scalar",
    Reference => "reference",
});

/// Validated options of one render (command line, or tests).
#[derive(Clone, Debug)]
pub struct RenderOptions {
    pub spp: u32,
    pub max_depth: u32,
    /// The interaction (from 1) from which Russian roulette may end a path.
    pub rr_depth: u32,
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
    /// How the path tracer advances its paths (the image is the same either way).
    pub paths: PathBatching,
    pub spawn: SpawnMode,
    pub sampler: SamplerKind,
    /// How the path tracer combines a material's lobes (conserving, or the course's
    /// additive model).
    pub energy: crate::shading::bsdf::Energy,
    /// Each sample's radiance is scaled down to at most this in every channel (a firefly
    /// clamp: biased, darker where light is concentrated, but quiet at low spp).
    pub clamp: Option<f32>,
    /// Camera hits record their albedo (for the `albedo` AOV; off, it is not computed and
    /// sums to zero).
    pub first_hit_albedo: bool,
    /// Renders only these pixels of the image (a preview window): the tiles that meet it
    /// are traced as in the whole render, so its pixels are the whole render's, bit for bit.
    pub crop: Option<crate::film::Tile>,
    /// Stops a progressive render early (a signal, a time limit) with the passes done.
    pub stop: Option<crate::render_stop::Stop>,
    /// Times the batched path tracer's phases (`RenderStats::phases`); the image is the same.
    pub time_phases: bool,
}

impl RenderOptions {
    /// Options taking spp and depth from the scene's own settings.
    pub fn for_scene(scene: &SceneDesc) -> Self {
        RenderOptions {
            spp: scene.settings.spp,
            max_depth: scene.settings.max_depth,
            rr_depth: scene.settings.rr_depth,
            seed: scene.settings.seed,
            jitter: scene.settings.jitter,
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
            paths: PathBatching::default(),
            spawn: SpawnMode::Robust,
            sampler: SamplerKind::default(),
            energy: Default::default(),
            clamp: None,
            first_hit_albedo: false,
            crop: None,
            stop: None,
            time_phases: false,
        }
    }
}

impl RenderOptions {
    /// The worker threads the render runs on: as asked, else (as rayon takes 0 too) one
    /// per core.
    pub fn worker_threads(&self) -> usize {
        self.threads.filter(|&n| n > 0).unwrap_or_else(rayon::current_num_threads)
    }

    /// Whether sample positions are jittered: as asked, except that a Whitted render at one
    /// sample per pixel samples pixel centres (the course's convention).
    pub fn jitters(&self) -> bool {
        let centred = self.integrator == IntegratorKind::Whitted && self.spp == 1;
        self.jitter && !centred
    }
}
