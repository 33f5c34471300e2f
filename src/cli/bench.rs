//! `embray bench`: the measurements (render spaces, accuracy, speed, effects' cost).

use super::choices::choice;
use super::console::{note, out};
use super::load_scene;
use anyhow::{Result, bail};
use clap::{Args, Subcommand};
use embray::accel::{BackendKind, BuildQuality};
use embray::bundled;
use embray::output::{OutputPlan, OutputSet, Target};
use embray::render_space::RenderSpace;
use embray::sampling::SamplerKind;
use embray::shading::spawn::SpawnMode;
use std::path::PathBuf;

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
    /// What a ray query costs per ray kind (camera, bounce, shadow) on each backend, one at a
    /// time and in each Embree batch mode, on one thread: how the path tracer's batches are
    /// traced is chosen by it. Default scene: the built-in Cornell box.
    Queries(QueriesArgs),
    /// What motion-blur and lens support cost a static scene: normal vs all effects forced.
    Effects(EffectsArgs),
    /// Error against a reference EXR at each spp, render time and MSE × seconds (the
    /// time-to-equal-error figure), as Markdown (and CSV).
    Convergence(ConvergenceArgs),
}

#[derive(Args, Debug)]
pub struct ConvergenceArgs {
    /// Scene file (.toml, or .xml: its first camera).
    pub scene: PathBuf,
    /// Reference image (linear EXR with R, G, B channels, the scene's resolution), e.g. a
    /// high-spp render of embray or of another renderer.
    #[arg(long)]
    pub reference: PathBuf,
    /// Samples per pixel to measure, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "4,16,64,256")]
    pub spps: Vec<u32>,
    #[arg(long, value_parser = choice::<BackendKind>())]
    pub backend: Option<BackendKind>,
    #[arg(long, value_parser = choice::<SamplerKind>(), default_value_t = SamplerKind::Sobol)]
    pub sampler: SamplerKind,
    #[arg(long)]
    pub threads: Option<usize>,
    /// The seed of the random numbers (default: the scene's, else 0).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Also print the spp at which the RMSE would reach this value (MSE ∝ 1/spp).
    #[arg(long)]
    pub target_rmse: Option<f64>,
    /// Also write the table as CSV.
    #[arg(long)]
    pub csv: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct QueriesArgs {
    /// Scene file; the built-in Cornell box if omitted.
    pub scene: Option<PathBuf>,
    /// Timed runs per measurement (the median is reported).
    #[arg(long, default_value_t = 5)]
    pub runs: usize,
    /// Trace the scene's view at WIDTHxHEIGHT (one camera ray per pixel) instead of its own
    /// size.
    #[arg(long, value_name = "WxH")]
    pub resolution: Option<String>,
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
    #[arg(long, value_parser = choice::<BuildQuality>(), default_value_t = BuildQuality::Medium)]
    pub build_quality: BuildQuality,
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
    #[arg(long, value_delimiter = ',', value_parser = SpawnMode::parse,
          default_value = "robust,epsilon=1e-4,epsilon=1e-2")]
    pub spawn: Vec<SpawnMode>,
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

/// `--runs` and `--threads` within 1..=their limits (a run count of 0 has no median).
fn check_counts(runs: usize, threads: Option<usize>) -> Result<()> {
    use embray::limits::{MAX_RUNS, MAX_THREADS};
    let max_runs = MAX_RUNS as usize;
    anyhow::ensure!(
        (1..=max_runs).contains(&runs),
        "--runs is {runs}, but must be between 1 and {max_runs}"
    );
    if let Some(threads) = threads {
        anyhow::ensure!(
            (1..=MAX_THREADS).contains(&threads),
            "--threads is {threads}, but must be between 1 and {MAX_THREADS}"
        );
    }
    Ok(())
}

/// Writes a CSV report through the output module (checked, committed whole).
/// Checks a `--csv` path before it is written: it may overwrite no file this run has read
/// (scenes, meshes, a reference image). Called once those inputs are read, before the work.
fn plan_csv(path: &std::path::Path, named_inputs: &[(&str, &std::path::Path)]) -> Result<Target> {
    let mut plan = OutputPlan::new();
    for (what, input) in named_inputs {
        plan.input(what, input);
    }
    plan.inputs_read(&embray::input_file::files_read());
    Ok(plan.output("--csv", path, false)?)
}

fn write_csv(target: &Target, text: &str) -> Result<()> {
    let mut files = OutputSet::new();
    files.write(target, |w| w.write_all(text.as_bytes()))?;
    Ok(files.commit()?)
}

/// Runs one bench command.
pub fn run(command: BenchCommand) -> Result<()> {
    match command {
        BenchCommand::Spaces(args) => bench_spaces(&args),
        BenchCommand::Accuracy(args) => bench_accuracy(&args),
        BenchCommand::Speed(args) => bench_speed(&args),
        BenchCommand::Queries(args) => bench_queries(&args),
        BenchCommand::Effects(args) => bench_effects(&args),
        BenchCommand::Convergence(args) => bench_convergence(&args),
    }
}

fn bench_queries(args: &QueriesArgs) -> Result<()> {
    use embray::bench::{memory, queries};
    check_counts(args.runs, None)?;
    let mut scene = load_scene(args.scene.as_deref(), &[])?;
    if let Some(text) = &args.resolution {
        super::preview::set_resolution(&mut scene, super::preview::parse_resolution(text)?);
    }
    memory::check_queries(&scene).map_err(anyhow::Error::msg)?;
    let rows = queries::measure(&scene, &embray::accel::BackendKind::compiled(), args.runs)?;
    out(queries::markdown(&rows))?;
    Ok(())
}

fn bench_effects(args: &EffectsArgs) -> Result<()> {
    use embray::bench::effects_cost;
    anyhow::ensure!(args.spp > 0, "--spp must be at least 1");
    check_counts(args.runs, None)?;
    let scene = load_scene(args.scene.as_deref(), &[])?;
    let mut base = embray::render::RenderOptions::for_scene(&scene);
    base.spp = args.spp;
    let rows =
        effects_cost::measure(&scene, &base, &embray::accel::BackendKind::compiled(), args.runs)?;
    out(effects_cost::markdown(&rows))?;
    Ok(())
}

fn bench_speed(args: &SpeedArgs) -> Result<()> {
    use embray::bench::{memory, procedural, speed};
    anyhow::ensure!(args.spp > 0, "--spp must be at least 1");
    anyhow::ensure!(args.size > 0, "--size must be at least 1");
    anyhow::ensure!(args.large > 0, "--large must be at least 1 (triangles)");
    check_counts(args.runs, None)?;
    const NAMES: [&str; 4] = ["cornell", "city_block", "instances", "large"];
    if let Some(unknown) = args.only.iter().find(|n| !NAMES.contains(&n.as_str())) {
        bail!("--only: unknown scene '{unknown}' (expected some of {})", NAMES.join(", "));
    }
    let wanted = |name: &str| args.only.is_empty() || args.only.iter().any(|n| n == name);
    let mut scenes = Vec::new();
    for name in NAMES[..3].iter().filter(|n| wanted(n)) {
        let path = bundled::path(&format!("scenes/{name}.toml"));
        scenes.push((name.to_string(), embray::scene::load(&path)?));
    }
    if wanted("large") {
        memory::check_large(args.large).map_err(anyhow::Error::msg)?;
        let large = format!("sphere_{}k", args.large / 1000);
        scenes.push((large, procedural::displaced_sphere_scene(args.large, 256, 256)));
    }
    let mut rows = Vec::new();
    let bar = indicatif::ProgressBar::new(scenes.len() as u64);
    for (name, mut scene) in scenes {
        let longest = scene.camera.width.max(scene.camera.height);
        if longest > args.size {
            let scale = args.size as f64 / longest as f64;
            scene.camera.width = ((scene.camera.width as f64 * scale) as u32).max(1);
            scene.camera.height = ((scene.camera.height as f64 * scale) as u32).max(1);
        }
        bar.set_message(name.clone());
        let backends = embray::accel::BackendKind::compiled();
        rows.extend(speed::measure_scene(
            &name,
            &scene,
            &backends,
            args.spp,
            args.runs,
            args.build_quality,
        )?);
        bar.inc(1);
    }
    bar.finish_and_clear();
    out(speed::markdown(&rows))?;
    Ok(())
}

fn bench_accuracy(args: &AccuracyArgs) -> Result<()> {
    use embray::bench::{accuracy, table};
    anyhow::ensure!(args.spp > 0, "--spp must be at least 1");
    anyhow::ensure!(args.max_size > 0, "--max-size must be at least 1");
    check_counts(args.runs, args.threads)?;
    anyhow::ensure!(!args.offsets.is_empty(), "--offsets needs at least one value");
    anyhow::ensure!(args.offsets.iter().all(|o| o.is_finite()), "--offsets must be finite numbers");
    let scenes =
        if args.scenes.is_empty() { accuracy::default_scenes() } else { args.scenes.clone() };
    let grazing = bundled::path("scenes/precision/grazing_plane.toml");
    let thin = bundled::path("scenes/precision/thin_walls.toml");
    let options = accuracy::AccuracyOptions {
        scenes,
        offsets: args.offsets.clone(),
        backends: embray::accel::BackendKind::compiled(),
        runs: args.runs,
        spp: args.spp,
        max_size: args.max_size,
        threads: args.threads,
        out_dir: args.out.clone(),
        spawn_scenes: Some((grazing, thin)),
        spawn_methods: args.spawn.clone(),
    };
    let total = options.scenes.len() * options.offsets.len() * 3 * options.backends.len();
    let bar = indicatif::ProgressBar::new(total as u64 + 1);
    let report = accuracy::run(&options, |message| {
        bar.set_message(message.to_string());
        bar.inc(1);
    })?;
    bar.finish_and_clear();
    out(table::markdown(&report.rows))?;
    if !report.spawn_rows.is_empty() {
        out(format!("\n{}", embray::bench::spawn_report::markdown(&report.spawn_rows)))?;
    }
    for warning in &report.warnings {
        note(format!("warning: {warning}"));
    }
    for file in &report.files {
        note(format!("wrote {}", file.display()));
    }
    Ok(())
}

fn bench_spaces(args: &BenchArgs) -> Result<()> {
    use embray::bench::{grid, table};
    let path = args.scene.clone().unwrap_or_else(|| bundled::path("scenes/city_block.toml"));
    let scene = load_scene(Some(&path), &[])?;
    check_counts(args.runs, args.threads)?;
    let mut options = embray::render::RenderOptions::for_scene(&scene);
    if let Some(spp) = args.spp {
        anyhow::ensure!(spp > 0, "--spp must be at least 1");
        options.spp = spp;
    }
    options.threads = args.threads;
    anyhow::ensure!(args.offsets.iter().all(|o| o.is_finite()), "--offsets must be finite numbers");
    let backends = embray::accel::BackendKind::compiled();
    let spaces = vec![RenderSpace::World, RenderSpace::Camera, RenderSpace::Cameraworld];
    let grid = grid::Grid { backends, spaces, offsets: args.offsets.clone(), runs: args.runs };
    let total = (grid.backends.len() * grid.spaces.len() * grid.offsets.len()) as u64;
    let bar = indicatif::ProgressBar::new(total);
    let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let rows = grid::measure(&name, &scene, &options, &grid, |row| {
        bar.set_message(format!("{} {} {:e}", row.backend, row.render_space, row.offset));
        bar.inc(1);
    })?;
    bar.finish_and_clear();
    out(table::markdown(&rows))?;
    if let Some(csv) = &args.csv {
        write_csv(&plan_csv(csv, &[])?, &table::csv(&rows))?;
    }
    Ok(())
}

/// The sentence `--target-rmse` prints; numbers too large or too small to read as plain
/// digits (a target of 1e-30 needs ~1e58 spp) are written in scientific notation.
fn spp_needed_line(target: f64, spp: f64) -> String {
    let target =
        if (1e-4..1e9).contains(&target) { format!("{target}") } else { format!("{target:e}") };
    let spp = if spp < 1e9 { format!("{spp:.0}") } else { format!("{spp:.2e}") };
    format!("RMSE {target} needs about {spp} spp\n")
}

fn bench_convergence(args: &ConvergenceArgs) -> Result<()> {
    use embray::bench::convergence;
    anyhow::ensure!(!args.spps.is_empty(), "--spps needs at least one value");
    anyhow::ensure!(args.spps.iter().all(|&s| s > 0), "--spps values must be at least 1");
    check_counts(1, args.threads)?;
    if let Some(t) = args.target_rmse {
        anyhow::ensure!(t.is_finite() && t > 0.0, "--target-rmse must be a positive number");
    }
    let scene = load_scene(Some(&args.scene), &[])?;
    let reference = convergence::read_reference(&args.reference)?;
    let inputs = [("the scene", args.scene.as_path()), ("the reference", args.reference.as_path())];
    let csv = args.csv.as_deref().map(|csv| plan_csv(csv, &inputs)).transpose()?;
    let mut options = embray::render::RenderOptions::for_scene(&scene);
    if let Some(seed) = args.seed {
        options.seed = seed;
    }
    options.sampler = args.sampler;
    options.threads = args.threads;
    if let Some(backend) = args.backend {
        options.backend = backend;
    }
    let rows = convergence::measure(&scene, &options, &reference, &args.spps, &args.reference)?;
    out(convergence::markdown(&rows))?;
    let needed = args.target_rmse.and_then(|t| Some((t, convergence::spp_for_rmse(&rows, t)?)));
    if let Some((target, spp)) = needed {
        out(spp_needed_line(target, spp))?;
    }
    if let Some(csv) = &csv {
        write_csv(csv, &convergence::csv(&rows))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::spp_needed_line;

    #[test]
    fn spp_needed_reads_as_plain_digits_unless_extreme() {
        assert_eq!(spp_needed_line(0.005, 1234.4), "RMSE 0.005 needs about 1234 spp\n");
        assert_eq!(spp_needed_line(1e-30, 3.39e58), "RMSE 1e-30 needs about 3.39e58 spp\n");
    }
}
