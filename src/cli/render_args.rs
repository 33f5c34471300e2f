//! `embray render`'s arguments and their validation into `RenderOptions`.

use super::choices::{LookArgs, TonemapArg, choice, tonemap};
use anyhow::{Result, bail};
use clap::Args;
use embray::accel::{AccelOptions, BackendKind, BatchMode, BuildQuality, Intersection};
use embray::compile::EffectsMode;
use embray::distributed::Split;
use embray::limits::{MAX_DEPTH, MAX_LIGHT_SAMPLES, MAX_SAMPLES, MAX_SPP, MAX_THREADS};
use embray::render::RenderOptions;
use embray::render_options::PathBatching;
use embray::render_space::RenderSpace;
use embray::sampling::SamplerKind;
use embray::scene::SceneDesc;
use embray::shading::bsdf::Energy;
use embray::shading::spawn::SpawnMode;
use glam::DVec3;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Scene file: .toml (native) or .xml (CENG795, every camera rendered to its ImageName
    /// in --out-dir); the built-in Cornell box if omitted.
    pub scene: Option<PathBuf>,
    /// A Mitsuba 3 scene's parameter (its `<default name=…>`, used as `$NAME`), as
    /// Mitsuba's own `-D`; repeatable.
    #[arg(short = 'D', long = "define", value_name = "NAME=VALUE", value_parser = parse_define)]
    pub defines: Vec<(String, String)>,
    /// Output image, its format by the extension: .exr (linear RGB, Z, N.X/N.Y/N.Z; the PNG
    /// is written beside it), or .png / .jpg / .jpeg (that display image only) [default: the
    /// scene's name with .exr and .png (cornell.exr); for a one-camera .xml scene: the
    /// ImageName with .exr in --out-dir].
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Display image (tone-mapped sRGB; .png, or .jpg/.jpeg for JPEG); defaults to the EXR
    /// path with a .png extension. Given without -o, only this image is written.
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
    /// The seed of the random numbers (default: the scene's, else 0).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Space the committed scene lives in.
    #[arg(long, value_parser = choice::<RenderSpace>(), default_value_t = RenderSpace::Cameraworld)]
    pub render_space: RenderSpace,
    /// Move the whole scene and camera by X,Y,Z (e.g. 1e7,1e7,1e7) to test precision.
    #[arg(long, value_parser = parse_offset, allow_hyphen_values = true)]
    pub offset: Option<DVec3>,
    /// Put samples at stratum centres instead of jittering them (default: the scene's, else
    /// jittered).
    #[arg(long)]
    pub no_jitter: bool,
    /// Intersection backend.
    #[arg(long, value_parser = choice::<BackendKind>())]
    pub backend: Option<BackendKind>,
    /// BVH build quality (both backends; medium was fastest overall when measured).
    #[arg(long, value_parser = choice::<BuildQuality>(), default_value_t = BuildQuality::Medium)]
    pub build_quality: BuildQuality,
    /// Embree: build a compact BVH (less memory, slower traversal).
    #[arg(long)]
    pub compact: bool,
    /// Embree: how batches of rays (the batched path tracer's) are traced — packets as wide
    /// as Embree's kernels here (16 with AVX-512, else 8), single rays, or packets of 8 or 16.
    #[arg(long, value_parser = choice::<BatchMode>(), default_value_t = BatchMode::Native)]
    pub batch: BatchMode,
    /// Embree: watertight triangle tests (robust), or Embree's fast ones, Mitsuba 3's
    /// setting (a ray through an edge that triangles share may slip between them; 13 %
    /// faster on the Cornell box, README: Speed).
    #[arg(long, value_parser = choice::<Intersection>(), default_value_t = AccelOptions::DEFAULT.intersection)]
    pub intersection: Intersection,
    /// How the path tracer advances its paths: batched (the paths of a tile's pixels
    /// together, a bounce at a time, rays traced in packets, plain Lambertian bounces
    /// computed in vector lanes), scalar (one path, one ray at a time) or reference (scalar,
    /// every BSDF through the general code). The image is the same every way.
    #[arg(long, value_parser = choice::<PathBatching>(), default_value_t = PathBatching::Batched)]
    pub paths: PathBatching,
    /// PNG tone curve.
    /// auto: photographic for a CENG795 camera with a <Tonemap>, clamp255 for other Whitted
    /// (CENG795) scenes, aces otherwise; none: clamp to [0, 1]; reinhard: x / (1 + x); aces:
    /// Narkowicz's ACES fit (all sRGB encoded); clamp255: values in 0–255 units clamped and
    /// truncated, no curve, no sRGB (the CENG795 output); photographic: Reinhard et al.'s
    /// global operator over the whole image (--key, --burn-out, --saturation, --gamma).
    #[arg(long, value_parser = tonemap(), default_value = "auto")]
    pub tonemap: TonemapArg,
    #[command(flatten)]
    pub look: LookArgs,
    /// Print ray and traversal counters as a table (counting node visits and primitive
    /// tests costs time; the summary's Mrays/s is then not representative).
    #[arg(long)]
    pub stats: bool,
    /// Write the counters as JSON to this file (implies counting, like --stats).
    #[arg(long)]
    pub stats_json: Option<PathBuf>,
    /// Print the ray counters and the time spent in each phase of the batched path tracer
    /// (camera rays, closest hits, Sobol draws, shading, vector lanes, lane outcomes, shadow
    /// rays, accumulate), summed over the threads: where a render's time goes. Unlike
    /// --stats it does not count traversal, so the render runs as it otherwise would.
    #[arg(long)]
    pub time_phases: bool,
    /// Shadow rays to area lights per shading point (default: the scene's, else 1).
    #[arg(long)]
    pub light_samples: Option<u32>,
    /// Sample every effect (time, lens) and build motion BVHs even where the scene needs
    /// none: measures what the effects machinery would cost a static scene.
    #[arg(long)]
    pub force_all_effects: bool,
    /// Random numbers: Owen-scrambled Sobol, stratified pixels with hashed dimensions, or
    /// all independent (for comparisons).
    #[arg(long, value_parser = choice::<SamplerKind>(), default_value_t = SamplerKind::Sobol)]
    pub sampler: SamplerKind,
    /// How the path tracer combines a material's lobes: `conserving` (no material reflects
    /// more than it receives) or `additive` (the CENG795 course's renderer: kd, mirror and
    /// the specular lobe added as they are, to reproduce its images).
    #[arg(long, value_parser = choice::<Energy>(), default_value_t = Energy::Conserving)]
    pub energy: Energy,
    /// Firefly clamp: scale each sample down so that no channel exceeds this radiance
    /// (biased: it darkens bright caustics and highlights; off by default).
    #[arg(long, allow_hyphen_values = true)]
    pub clamp: Option<f32>,
    /// The EXR's channels beside R, G, B: a comma list of depth (Z), normal (N.X/Y/Z),
    /// albedo (albedo.R/G/B), variance (variance.R/G/B, the samples' variance), alpha (A:
    /// the fraction of samples that hit something); `none` for the beauty alone.
    /// [default: the scene's (a Mitsuba `aov` integrator's), else depth,normal]
    #[arg(long, value_parser = |s: &str| embray::output::Aovs::parse(s))]
    pub aovs: Option<embray::output::Aovs>,
    /// Also write the beauty denoised by Intel Open Image Denoise, beside each image
    /// (NAME.denoised.exr, NAME.denoised.png), guided by the first hit's albedo and normal.
    /// Needs a build with `--features denoise` (README: Denoising).
    #[arg(long)]
    pub denoise: bool,
    /// Render at WIDTHxHEIGHT instead of the scene's size, with the same view (a preview).
    #[arg(long, value_name = "WxH")]
    pub resolution: Option<String>,
    /// Render only the pixels X0..X1, Y0..Y1 of the image (X1, Y1 excluded; after
    /// --resolution): the same pixels as the whole render gives, bit for bit.
    #[arg(long, value_name = "X0,Y0,X1,Y1")]
    pub crop: Option<String>,
    /// One camera of a multi-camera CENG795 file: its ImageName (with or without the
    /// extension) or its position from 1; -o and --part then work as for any scene.
    #[arg(long, value_name = "NAME|N")]
    pub camera: Option<String>,
    /// Stop after this many seconds (counted from the start of the command) and write the
    /// image of the samples done so far: renders go in passes over the whole image, and at
    /// the limit no new tile is started. Ctrl-C and SIGTERM stop the same way (a second one
    /// quits at once).
    #[arg(long, value_name = "SECONDS")]
    pub time_limit: Option<f64>,
    /// While rendering, write the image so far (every output, atomically replaced) after
    /// each pass that ends at least this many seconds after the last such write, to look
    /// at a long render while it runs.
    #[arg(long, value_name = "SECONDS")]
    pub checkpoint_every: Option<f64>,
    /// How rays leave surfaces: `robust` (error-bound offsets) or `epsilon=VALUE`.
    #[arg(long, value_parser = SpawnMode::parse, default_value = "robust")]
    pub spawn: SpawnMode,
    /// Render only part I of N (counting from 0) into a part file of exact sample sums
    /// (-o, default part-I-of-N.exr); `embray merge` joins the N parts into the image the
    /// whole render would give, bit for bit.
    #[arg(long, value_name = "I/N")]
    pub part: Option<String>,
    /// How --part divides the render: each part gets whole tiles (spread over the image), or
    /// a range of every pixel's samples.
    #[arg(long, value_parser = choice::<Split>(), default_value_t = Split::Tiles, requires = "part")]
    pub split: Split,
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

/// `NAME=VALUE` for `-D`.
pub(super) fn parse_define(text: &str) -> Result<(String, String), String> {
    match text.split_once('=') {
        Some((name, value)) if !name.is_empty() => Ok((name.to_owned(), value.to_owned())),
        _ => Err(format!("expected NAME=VALUE, got '{text}'")),
    }
}

impl RenderArgs {
    /// The display image's path: `--png`, else the EXR's (`-o`) with .png.
    pub fn png_path(&self) -> PathBuf {
        let exr = self.output.clone().unwrap_or_else(|| PathBuf::from("render.exr"));
        self.png.clone().unwrap_or_else(|| exr.with_extension("png"))
    }

    /// Why these options cannot render a part of a split render (`--part`, `embray slurm`),
    /// if they cannot: checked before the scene is loaded.
    pub fn part_flag_problem(&self) -> Option<String> {
        let images = [
            ("--png", self.png.is_some()),
            ("--stats-json", self.stats_json.is_some()),
            ("--lut", self.look.lut.is_some()),
        ];
        if let Some((flag, _)) = images.into_iter().find(|(_, given)| *given) {
            return Some(format!(
                "{flag} cannot be used with --part: a part holds sample sums, not an image; \
                 `embray merge` writes the image (and its PNG, graded with its own --lut) once \
                 every part is done"
            ));
        }
        if self.crop.is_some() {
            return Some(
                "--crop cannot be used with --part: --part splits the whole image (render the \
                 crop without --part)"
                    .to_owned(),
            );
        }
        let whole_only = [
            ("--time-limit", self.time_limit.is_some()),
            ("--checkpoint-every", self.checkpoint_every.is_some()),
            ("--denoise", self.denoise),
        ];
        let (flag, _) = whole_only.into_iter().find(|(_, given)| *given)?;
        Some(format!(
            "{flag} cannot be used with --part: a part file holds all of its samples of its share \
             of the whole image, or nothing (a part that did not finish is rendered again)"
        ))
    }

    /// Why `scene` (after `apply_preview`) cannot be rendered in parts, if it cannot: its own
    /// crop window (the parts split the whole image; merged, they were refused as damaged).
    pub fn part_scene_problem(scene: &SceneDesc) -> Option<String> {
        let crop = scene.settings.crop?;
        Some(format!(
            "'{}' asks for a crop window ({}, {}) to ({}, {}), and --part splits the whole image: \
             render the crop without --part (or all of the image in parts with --resolution, \
             which drops the crop)",
            scene.source.display(),
            crop.x0,
            crop.y0,
            crop.x1,
            crop.y1
        ))
    }

    /// `--resolution` applied to a loaded scene.
    pub fn apply_preview(&self, scene: &mut SceneDesc) -> Result<()> {
        if let Some(text) = &self.resolution {
            super::preview::set_resolution(scene, super::preview::parse_resolution(text)?);
        }
        Ok(())
    }

    /// The AOVs `scene`'s EXR carries: `--aovs`, else the scene's, else depth and normal.
    pub fn aovs_for(&self, scene: &SceneDesc) -> embray::output::Aovs {
        self.aovs.or(scene.settings.aovs).unwrap_or_default()
    }

    /// Refuses more camera samples than a render takes (`limits::MAX_SAMPLES`) before
    /// anything is built, naming the scene file, the camera (of a file of several) and
    /// where the spp came from.
    pub fn check_samples(&self, scene: &SceneDesc, spp: u32, camera: Option<&str>) -> Result<()> {
        let (width, height) = (scene.camera.width, scene.camera.height);
        let pixels = u64::from(width) * u64::from(height);
        let samples = pixels.saturating_mul(u64::from(spp));
        if samples <= MAX_SAMPLES {
            return Ok(());
        }
        let xml = scene.source.extension().is_some_and(|e| e.eq_ignore_ascii_case("xml"));
        let field = match (self.spp.is_some(), xml) {
            (true, _) => "--spp",
            (false, true) => "the scene's NumSamples (CENG795) or sample_count (Mitsuba)",
            (false, false) => "the scene's [render] spp",
        };
        let camera = camera.map(|c| format!(", {c}")).unwrap_or_default();
        bail!(
            "'{}'{camera}: pixels × spp is {samples} ({width}x{height} pixels × {spp} spp, \
             from {field}), but must be at most {MAX_SAMPLES} (2³⁶): lower the spp, or the size \
             with --resolution",
            scene.source.display()
        )
    }

    pub fn to_options(&self, scene: &SceneDesc) -> Result<RenderOptions> {
        let mut options = RenderOptions::for_scene(scene);
        if let Some(spp) = self.spp {
            if !(1..=MAX_SPP).contains(&spp) {
                bail!("--spp is {spp}, but must be between 1 and {MAX_SPP}");
            }
            options.spp = spp;
        }
        if let Some(depth) = self.max_depth {
            if depth > MAX_DEPTH {
                bail!("--max-depth is {depth}, but must be at most {MAX_DEPTH}");
            }
            options.max_depth = depth;
        }
        if let Some(threads) = self.threads {
            if !(1..=MAX_THREADS).contains(&threads) {
                bail!("--threads is {threads}, but must be between 1 and {MAX_THREADS}");
            }
            options.threads = Some(threads);
        }
        self.look.check()?;
        if let Some(seed) = self.seed {
            options.seed = seed;
        }
        if self.no_jitter {
            options.jitter = false;
        }
        options.render_space = self.render_space;
        options.offset = self.offset.unwrap_or(DVec3::ZERO);
        if let Some(backend) = self.backend {
            options.backend = backend;
        }
        options.count_traversal = self.stats || self.stats_json.is_some();
        options.time_phases = self.time_phases;
        options.accel.build_quality = self.build_quality;
        options.accel.compact = self.compact;
        options.accel.batch = self.batch;
        options.accel.intersection = self.intersection;
        options.paths = self.paths;
        if let Some(n) = self.light_samples {
            if !(1..=MAX_LIGHT_SAMPLES).contains(&n) {
                bail!("--light-samples is {n}, but must be between 1 and {MAX_LIGHT_SAMPLES}");
            }
            options.light_samples = n;
        }
        options.spawn = self.spawn;
        options.sampler = self.sampler;
        options.energy = self.energy;
        if let Some(limit) = self.clamp {
            if !(limit.is_finite() && limit > 0.0) {
                bail!("--clamp is {limit}, but must be a finite radiance > 0");
            }
            options.clamp = Some(limit);
        }
        if self.force_all_effects {
            options.effects_mode = EffectsMode::ForceAll;
        }
        for (flag, value) in
            [("--time-limit", self.time_limit), ("--checkpoint-every", self.checkpoint_every)]
        {
            if let Some(seconds) = value.filter(|s| !(s.is_finite() && *s > 0.0 && *s < 1e9)) {
                let seconds = embray::excerpt::short_number(seconds.to_string());
                bail!("{flag} is {seconds}, but must be a number of seconds > 0 and below 1e9");
            }
        }
        options.crop = match &self.crop {
            Some(text) => {
                Some(super::preview::parse_crop(text, (scene.camera.width, scene.camera.height))?)
            }
            None => scene.settings.crop,
        };
        options.first_hit_albedo = self.aovs_for(scene).albedo || self.denoise;
        options.progress = !self.quiet;
        Ok(options)
    }
}
