//! The command line: clap arguments, one thin file per command. The only place that knows
//! clap; the library is driven through its own option types.

mod bench;
mod choices;
mod compare;
mod console;
mod convert;
mod info;
mod merge;
mod preview;
mod render;
mod render_args;
mod render_outputs;
mod render_part;
mod slurm;
mod slurm_render_args;
mod tonemap;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use embray::scene::SceneDesc;
use std::path::{Path, PathBuf};

pub use bench::BenchCommand;
pub use compare::CompareArgs;
pub use convert::ConvertArgs;
pub use merge::MergeArgs;
pub use render_args::RenderArgs;
pub use tonemap::TonemapArgs;

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
    Render(Box<RenderArgs>),
    /// Measure renders over backends, render spaces and offsets.
    #[command(subcommand)]
    Bench(BenchCommand),
    /// Print what a scene contains (for a CENG795 .xml file: each camera's scene).
    Info {
        /// Scene file (.toml, or .xml for the CENG795 or Mitsuba 3 format); the built-in
        /// Cornell box if omitted.
        scene: Option<PathBuf>,
        /// A Mitsuba scene's parameter (its `<default>`, `$name`), as Mitsuba's `-D`.
        #[arg(short = 'D', long = "define", value_name = "NAME=VALUE", value_parser = render_args::parse_define)]
        defines: Vec<(String, String)>,
    },
    /// Convert a CENG795 or Mitsuba 3 .xml scene to the native TOML format. Meshes are written as OBJ
    /// files into OUT_meshes/ beside it. A file with several cameras gives one TOML per
    /// camera, OUT_<image name>.toml, sharing the meshes.
    Convert(ConvertArgs),
    /// Compare two images. 8-bit images (PNG, JPEG): mean absolute error (in 1/255 units),
    /// the fraction of pixels with some channel off by more than the tolerance, and
    /// optionally a heat map of the per-pixel largest channel difference. Two EXRs: each
    /// channel's mean, RMSE, relative MSE and the largest difference.
    Compare(CompareArgs),
    /// Tone-map a linear EXR to PNG with the photographic operator (Reinhard et al. 2002, as
    /// the CENG795 course specifies it), without rendering.
    Tonemap(TonemapArgs),
    /// Join the part files of a split render (`embray render --part I/N`) into its EXR (and
    /// PNG): bit-identical to rendering it whole. Refuses parts of other renders, and missing
    /// or duplicated parts.
    Merge(MergeArgs),
    /// Render a scene on a Slurm cluster: one array job of N parts and a merge that waits for
    /// it (`embray slurm SCENE --parts N --out DIR [-- RENDER OPTIONS]`); `embray slurm
    /// status DIR` and `embray slurm resume DIR` pick up a job folder later.
    Slurm(slurm::SlurmArgs),
}

/// Runs the command `cli` names.
pub fn run(cli: Cli) -> Result<()> {
    // Checked before any work, whatever the command: a bad value is a mistake to report
    // once, not a setting each part of a cluster job silently drops.
    embray::limits::memory_budget()?;
    embray::render_passes::progress_interval()?;
    match cli.command {
        Command::Render(args) => render::run(&args),
        Command::Bench(command) => bench::run(command),
        Command::Info { scene, defines } => info::run(scene.as_deref(), &defines),
        Command::Convert(args) => convert::run(&args),
        Command::Compare(args) => compare::run(&args),
        Command::Tonemap(args) => tonemap::run(&args),
        Command::Merge(args) => merge::run(&args),
        Command::Slurm(args) => slurm::run(&args),
    }
}

/// Loads the named scene, or the built-in default. For a CENG795 .xml file with several
/// cameras, the first camera's scene.
pub fn load_scene(path: Option<&Path>, defines: &[(String, String)]) -> Result<SceneDesc> {
    Ok(match path {
        Some(path) if embray::scene::ceng795::is_ceng795_path(path) => {
            embray::scene::xml::load(path, defines)?.swap_remove(0).scene
        }
        _ if !defines.is_empty() => {
            let (path, kind) = match path {
                Some(path) => (path, "a TOML scene"),
                None => (Path::new("the built-in scene"), "the built-in Cornell box"),
            };
            return Err(embray::scene::xml::not_a_parameter(path, &defines[0], kind).into());
        }
        Some(path) => embray::scene::load(path)?,
        None => embray::scene::load(&embray::bundled::default_scene())
            .context("the built-in default scene failed to load")?,
    })
}

/// The `--lut` file, read and recorded as an input of the run (no output may overwrite it).
pub fn read_lut(
    path: Option<&Path>,
    plan: &mut embray::output::OutputPlan,
) -> Result<Option<embray::output::Lut3d>> {
    let Some(path) = path else {
        return Ok(None);
    };
    plan.input("the LUT", path);
    Ok(Some(embray::output::Lut3d::read(path)?))
}
