//! `embray compare`: two images' difference in 1/255 steps, and optionally a heat map.

use anyhow::Result;
use clap::Args;
use embray::compare::{compare_images, read_rgb};
use embray::output::{OutputPlan, OutputSet, encode_rgb8};
use std::path::PathBuf;

use super::console::{note, out};

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

pub fn run(args: &CompareArgs) -> Result<()> {
    // The heat map may overwrite neither image: checked before anything is read.
    let mut plan = OutputPlan::new();
    plan.input("the first image", &args.a);
    plan.input("the second image", &args.b);
    let heatmap =
        args.heatmap.as_deref().map(|p| plan.output("--heatmap", p, false)).transpose()?;
    let c = compare_images(&read_rgb(&args.a)?, &read_rgb(&args.b)?, args.tolerance)?;
    out(format!(
        "{}x{}: mean abs error {:.4}/255, max {}/255; {:.4} % of pixels off by more than {}/255 \
         ({:.4} % within)",
        c.width,
        c.height,
        c.mean_abs_error,
        c.max_abs_error,
        100.0 * c.fraction_over,
        c.tolerance,
        100.0 * c.fraction_within()
    ))?;
    if let Some(target) = &heatmap {
        let image = c.heatmap();
        let mut files = OutputSet::new();
        files.write(target, |w| encode_rgb8(image.as_raw(), image.width(), image.height(), w))?;
        files.commit()?;
        note(format!("wrote {}", target.path.display()));
    }
    Ok(())
}
