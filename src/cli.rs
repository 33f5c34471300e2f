//! Command-line arguments (clap) and their validation into library options.

use anyhow::{Context, Result, bail};
use clap::{Args, Parser, Subcommand};
use embray::accel::BackendKind;
use embray::output::ToneMap;
use embray::render::RenderOptions;
use embray::render_space::RenderSpace;
use embray::scene::SceneDesc;
use glam::DVec3;
use std::path::{Path, PathBuf};

/// The scene rendered when none is named: a Cornell box.
pub const DEFAULT_SCENE: &str = include_str!("../scenes/cornell.toml");
pub const DEFAULT_SCENE_NAME: &str = "scenes/cornell.toml (built in)";

#[derive(Parser, Debug)]
#[command(
    name = "embray",
    version,
    about = "Ray tracer on Embree (FFI) or obvhs, rendering in camera-relative space"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render a scene to EXR (with depth and normal AOVs) and PNG.
    Render(RenderArgs),
    /// Measure renders over backends, render spaces and offsets.
    #[command(subcommand)]
    Bench(BenchCommand),
    /// Print what a scene contains (for a CENG795 .xml file: each camera's scene).
    Info {
        /// Scene file (.toml, or .xml for the CENG795 format); the built-in Cornell box if
        /// omitted.
        scene: Option<PathBuf>,
    },
    /// Convert a CENG795 .xml scene to the native TOML format. Meshes are written as OBJ
    /// files into OUT_meshes/ beside it. A file with several cameras gives one TOML per
    /// camera, OUT_<image name>.toml, sharing the meshes.
    Convert(ConvertArgs),
    /// Compare two images: mean absolute error (in 1/255 units), the fraction of pixels with
    /// some channel off by more than the tolerance, and optionally a heat map of the
    /// per-pixel largest channel difference.
    Compare(CompareArgs),
}

#[derive(Args, Debug)]
pub struct ConvertArgs {
    /// The CENG795 scene (.xml).
    pub input: PathBuf,
    /// The TOML file to write.
    #[arg(short, long)]
    pub output: PathBuf,
}

#[derive(Args, Debug)]
pub struct CompareArgs {
    /// First image (e.g. the render).
    pub a: PathBuf,
    /// Second image (e.g. the reference).
    pub b: PathBuf,
    /// Write a heat map of the per-pixel largest channel difference (PNG): black where
    /// equal, blue up to the tolerance, red to yellow beyond it.
    #[arg(long)]
    pub heatmap: Option<PathBuf>,
    /// Per-channel tolerance in 1/255 steps.
    #[arg(long, default_value_t = embray::compare::DEFAULT_TOLERANCE)]
    pub tolerance: u8,
}

/// `--tonemap`: a curve, or `auto` (the scene's integrator decides).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum TonemapArg {
    /// clamp255 for Whitted (CENG795) scenes, aces otherwise.
    #[default]
    Auto,
    /// Clamp to [0, 1], sRGB encoded.
    None,
    /// x / (1 + x) per channel, sRGB encoded.
    Reinhard,
    /// Narkowicz's ACES fit, sRGB encoded.
    Aces,
    /// Values in 0–255 units clamped and rounded, no curve, no sRGB (the CENG795 output).
    #[value(name = "clamp255")]
    Clamp255,
}

impl TonemapArg {
    /// The curve for a scene rendered with `integrator`.
    pub fn resolve(self, integrator: embray::scene::IntegratorKind) -> ToneMap {
        match self {
            TonemapArg::Auto => match integrator {
                embray::scene::IntegratorKind::Whitted => ToneMap::Clamp255,
                embray::scene::IntegratorKind::Path => ToneMap::Aces,
            },
            TonemapArg::None => ToneMap::None,
            TonemapArg::Reinhard => ToneMap::Reinhard,
            TonemapArg::Aces => ToneMap::Aces,
            TonemapArg::Clamp255 => ToneMap::Clamp255,
        }
    }
}

#[derive(Subcommand, Debug)]
pub enum BenchCommand {
    /// Render space × backend (× offset) on one scene: time, counters and image error against
    /// the cameraworld render at offset 0. Default scene: scenes/city_block.toml.
    Spaces(BenchArgs),
    /// The accuracy/time report: every bundled precision scene (or the named ones) × render
    /// space × backend × offset, written as Markdown, CSV, charts and an image strip.
    Accuracy(AccuracyArgs),
    /// Throughput of each backend on scenes from a dozen to a million triangles: build time,
    /// primary and diffuse Mrays/s, samples/s on 1 and 2 threads, memory.
    Speed(SpeedArgs),
    /// What motion-blur and lens support cost a static scene: normal vs all effects forced.
    Effects(EffectsArgs),
}

#[derive(Args, Debug)]
pub struct EffectsArgs {
    /// Scene file; the built-in Cornell box if omitted.
    pub scene: Option<PathBuf>,
    #[arg(long, default_value_t = 5)]
    pub runs: usize,
    #[arg(long, default_value_t = 16)]
    pub spp: u32,
}

#[derive(Args, Debug)]
pub struct SpeedArgs {
    /// Triangles in the largest (procedural) scene.
    #[arg(long, default_value_t = 1_000_000)]
    pub large: usize,
    /// Timed runs per measurement (the median is reported).
    #[arg(long, default_value_t = 3)]
    pub runs: usize,
    /// Samples per pixel of the whole-render measurement.
    #[arg(long, default_value_t = 4)]
    pub spp: u32,
    /// Longest image side.
    #[arg(long, default_value_t = 256)]
    pub size: u32,
    /// Build quality of the BVHs the rays and renders are measured on.
    #[arg(long, value_enum, default_value_t = embray::accel::BuildQuality::Medium)]
    pub build_quality: embray::accel::BuildQuality,
    /// Only these scenes (comma-separated: cornell, city_block, instances, large).
    #[arg(long, value_delimiter = ',')]
    pub only: Vec<String>,
}

#[derive(Args, Debug)]
pub struct AccuracyArgs {
    /// Scene files; the bundled Cornell box and scenes/precision/*.toml if omitted.
    pub scenes: Vec<PathBuf>,
    /// Distances from the origin, comma separated (applied on all three axes).
    #[arg(long, value_delimiter = ',', default_value = "0,1e3,1e5,1e6,1e7")]
    pub offsets: Vec<f64>,
    /// Timed runs per configuration (the median is reported).
    #[arg(long, default_value_t = 3)]
    pub runs: usize,
    #[arg(long, default_value_t = 4)]
    pub spp: u32,
    /// Longest image side; larger scenes are scaled down.
    #[arg(long, default_value_t = 64)]
    pub max_size: u32,
    #[arg(long)]
    pub threads: Option<usize>,
    /// Folder for report.md, report.csv, the charts and strip.png.
    #[arg(long, default_value = "accuracy-report")]
    pub out: PathBuf,
    /// Spawn methods compared on the grazing-plane and thin-wall scenes.
    #[arg(long, value_delimiter = ',', value_parser = embray::spawn::SpawnMode::parse,
          default_value = "robust,epsilon=1e-4,epsilon=1e-2")]
    pub spawn: Vec<embray::spawn::SpawnMode>,
}

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Scene file; scenes/city_block.toml if omitted.
    pub scene: Option<PathBuf>,
    /// Timed runs per configuration (the median is reported).
    #[arg(long, default_value_t = 3)]
    pub runs: usize,
    #[arg(long)]
    pub spp: Option<u32>,
    #[arg(long)]
    pub threads: Option<usize>,
    /// Offsets from the origin to test, comma separated (applied on all three axes).
    #[arg(long, value_delimiter = ',', default_value = "0")]
    pub offsets: Vec<f64>,
    /// Also write the table as CSV.
    #[arg(long)]
    pub csv: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Scene file: .toml (native) or .xml (CENG795, every camera rendered to its ImageName
    /// in --out-dir); the built-in Cornell box if omitted.
    pub scene: Option<PathBuf>,
    /// EXR output (linear RGB, Z, N.X/N.Y/N.Z) [default: render.exr; for a one-camera .xml
    /// scene: the ImageName with .exr in --out-dir].
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// PNG output (tone-mapped sRGB); defaults to the EXR path with a .png extension.
    #[arg(long)]
    pub png: Option<PathBuf>,
    /// Folder for the images of a CENG795 .xml scene: each camera's ImageName (PNG) and an
    /// EXR with the same stem. Not used with -o.
    #[arg(long, default_value = ".")]
    pub out_dir: PathBuf,
    /// Samples per pixel (default: the scene's, else 16).
    #[arg(long)]
    pub spp: Option<u32>,
    /// Maximum number of surface interactions per path (1 = direct light only).
    #[arg(long)]
    pub max_depth: Option<u32>,
    /// Worker threads (default: all cores). The image does not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Space the committed scene lives in.
    #[arg(long, value_enum, default_value_t = RenderSpace::Cameraworld)]
    pub render_space: RenderSpace,
    /// Move the whole scene and camera by X,Y,Z (e.g. 1e7,1e7,1e7) to test precision.
    #[arg(long, value_parser = parse_offset, allow_hyphen_values = true)]
    pub offset: Option<DVec3>,
    /// Put samples at stratum centres instead of jittering them.
    #[arg(long)]
    pub no_jitter: bool,
    /// Intersection backend.
    #[arg(long, value_enum)]
    pub backend: Option<BackendKind>,
    /// BVH build quality (both backends; medium was fastest overall when measured).
    #[arg(long, value_enum, default_value_t = embray::accel::BuildQuality::Medium)]
    pub build_quality: embray::accel::BuildQuality,
    /// Embree: build a compact BVH (less memory, slower traversal).
    #[arg(long)]
    pub compact: bool,
    /// Embree: how camera rays are traced — single rays, or packets of 8 or 16.
    #[arg(long, value_enum, default_value_t = embray::accel::BatchMode::Packets8)]
    pub batch: embray::accel::BatchMode,
    /// PNG tone curve.
    #[arg(long, value_enum, default_value_t = TonemapArg::Auto)]
    pub tonemap: TonemapArg,
    /// Exposure adjustment in stops, applied before tone mapping (PNG only).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub exposure: f32,
    /// Print ray and traversal counters as a table (counting node visits and primitive
    /// tests costs time; the summary's Mrays/s is then not representative).
    #[arg(long)]
    pub stats: bool,
    /// Write the counters as JSON to this file (implies counting, like --stats).
    #[arg(long)]
    pub stats_json: Option<PathBuf>,
    /// Shadow rays to area lights per shading point (default: the scene's, else 1).
    #[arg(long)]
    pub light_samples: Option<u32>,
    /// Sample every effect (time, lens) and build motion BVHs even where the scene needs
    /// none: measures what the effects machinery would cost a static scene.
    #[arg(long)]
    pub force_all_effects: bool,
    /// How rays leave surfaces: `robust` (error-bound offsets) or `epsilon=VALUE`.
    #[arg(long, value_parser = embray::spawn::SpawnMode::parse, default_value = "robust")]
    pub spawn: embray::spawn::SpawnMode,
    /// No progress bar or summary line.
    #[arg(short, long)]
    pub quiet: bool,
}

fn parse_offset(text: &str) -> Result<DVec3, String> {
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() != 3 {
        return Err(format!("expected X,Y,Z, got '{text}'"));
    }
    let mut v = [0.0; 3];
    for (slot, part) in v.iter_mut().zip(&parts) {
        let value: f64 = part.trim().parse().map_err(|_| format!("'{part}' is not a number"))?;
        if !value.is_finite() {
            return Err(format!("'{part}' is not finite"));
        }
        *slot = value;
    }
    Ok(DVec3::from_array(v))
}

/// Loads the named scene, or the built-in default. For a CENG795 .xml file with several
/// cameras, the first camera's scene.
pub fn load_scene(path: Option<&Path>) -> Result<SceneDesc> {
    Ok(match path {
        Some(path) if embray::scene::ceng795::is_ceng795_path(path) => {
            embray::scene::ceng795::load(path)?.swap_remove(0).scene
        }
        Some(path) => embray::scene::load(path)?,
        None => embray::scene::load_str(DEFAULT_SCENE, Path::new(DEFAULT_SCENE_NAME))
            .context("the built-in default scene failed to load")?,
    })
}

impl RenderArgs {
    /// The EXR path (`-o`, default render.exr).
    pub fn output_path(&self) -> PathBuf {
        self.output.clone().unwrap_or_else(|| PathBuf::from("render.exr"))
    }

    pub fn png_path(&self) -> PathBuf {
        self.png.clone().unwrap_or_else(|| self.output_path().with_extension("png"))
    }

    pub fn to_options(&self, scene: &SceneDesc) -> Result<RenderOptions> {
        let mut options = RenderOptions::for_scene(scene);
        if let Some(spp) = self.spp {
            if spp == 0 {
                bail!("--spp must be at least 1");
            }
            options.spp = spp;
        }
        if let Some(depth) = self.max_depth {
            options.max_depth = depth;
        }
        if let Some(threads) = self.threads {
            if threads == 0 {
                bail!("--threads must be at least 1");
            }
            options.threads = Some(threads);
        }
        if !self.exposure.is_finite() {
            bail!("--exposure must be a finite number");
        }
        options.seed = self.seed;
        // The course samples pixel centres at one sample per pixel: so does a Whitted scene.
        let centred =
            scene.settings.integrator == embray::scene::IntegratorKind::Whitted && options.spp == 1;
        options.jitter = !self.no_jitter && !centred;
        options.render_space = self.render_space;
        options.offset = self.offset.unwrap_or(DVec3::ZERO);
        if let Some(backend) = self.backend {
            options.backend = backend;
        }
        options.count_traversal = self.stats || self.stats_json.is_some();
        options.accel.build_quality = self.build_quality;
        options.accel.compact = self.compact;
        options.accel.batch = self.batch;
        if let Some(n) = self.light_samples {
            if n == 0 {
                bail!("--light-samples must be at least 1");
            }
            options.light_samples = n;
        }
        options.spawn = self.spawn;
        if self.force_all_effects {
            options.effects_mode = embray::render_space::EffectsMode::ForceAll;
        }
        options.progress = !self.quiet;
        Ok(options)
    }
}
