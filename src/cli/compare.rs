//! `embray compare`: two 8-bit images' difference in 1/255 steps, and optionally a heat map;
//! two EXRs' channel means, RMSE and relative error.

use anyhow::Result;
use clap::Args;
use embray::compare::{compare_images, read_rgb};
use embray::output::{ImageFormat, OutputPlan, OutputSet, encode_display_rgb8};
use std::path::{Path, PathBuf};

use super::console::{note, out};

#[derive(Args, Debug)]
pub struct CompareArgs {
    /// First image (e.g. the render).
    pub a: PathBuf,
    /// Second image (e.g. the reference).
    pub b: PathBuf,
    /// Write a heat map of the per-pixel largest channel difference (PNG, or JPEG for .jpg):
    /// black where equal, blue up to the tolerance, red to yellow beyond it.
    #[arg(long)]
    pub heatmap: Option<PathBuf>,
    /// Per-channel tolerance in 1/255 steps.
    #[arg(long, default_value_t = embray::compare::DEFAULT_TOLERANCE)]
    pub tolerance: u8,
    /// The reference's per-sample variance (EXR): judge the first image by Mitsuba 3's
    /// pass rule (a per-pixel Z-test in XYZ at the Šidák-corrected 1 % level; 99.75 % of
    /// the pixel channels must pass). Needs --spp.
    #[arg(long, requires = "spp")]
    pub variance: Option<PathBuf>,
    /// The first image's samples per pixel (for --variance).
    #[arg(long, requires = "variance")]
    pub spp: Option<u32>,
}

pub fn run(args: &CompareArgs) -> Result<()> {
    if args.spp == Some(0) {
        // The test's standard error is √(variance / spp): at 0 spp every difference passes.
        anyhow::bail!("--spp is 0, but the first image has at least 1 sample per pixel");
    }
    // The heat map may overwrite neither image: checked before anything is read.
    let mut plan = OutputPlan::new();
    plan.input("the first image", &args.a);
    plan.input("the second image", &args.b);
    let heatmap =
        args.heatmap.as_deref().map(|p| plan.output("--heatmap", p, false)).transpose()?;
    let hint = "the heat map is an 8-bit image (.png, .jpg or .jpeg)";
    let heatmap_format = match &args.heatmap {
        Some(path) => {
            ImageFormat::display_of_path(path, "--heatmap", hint).map_err(anyhow::Error::msg)?
        }
        None => ImageFormat::Png,
    };
    match (is_exr(&args.a), is_exr(&args.b)) {
        (true, true) if heatmap.is_some() => {
            anyhow::bail!("--heatmap is for 8-bit images (PNG, JPEG), not EXRs")
        }
        (true, true) => {
            compare_linear(&args.a, &args.b)?;
            if let (Some(variance), Some(spp)) = (&args.variance, args.spp) {
                mitsuba_rule(&args.a, &args.b, variance, spp)?;
            }
            return Ok(());
        }
        (false, false) if args.variance.is_some() => {
            anyhow::bail!("--variance judges EXRs, not 8-bit images")
        }
        (false, false) => {}
        _ => anyhow::bail!(
            "'{}' and '{}': compare an EXR with an EXR, or an 8-bit image with an 8-bit image \
             (`embray tonemap` makes a PNG of an EXR)",
            args.a.display(),
            args.b.display()
        ),
    }
    let c = compare_images(&read_rgb(&args.a)?, &read_rgb(&args.b)?, args.tolerance)?;
    out(format!(
        "{}x{}: mean abs error {:.4}/255, max {}/255; {:.4} % of pixels off by more than {}/255 \
         ({:.4} % within)\n",
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
        let (width, height) = image.dimensions();
        files.write(target, |w| {
            encode_display_rgb8(image.as_raw(), width, height, heatmap_format, w)
        })?;
        files.commit()?;
        note(format!("wrote {}", target.path.display()));
    }
    Ok(())
}

/// Whether `path` names an OpenEXR file (by its extension; the reader checks the contents).
fn is_exr(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr"))
}

fn compare_linear(a: &Path, b: &Path) -> Result<()> {
    use embray::bench::convergence::read_linear_exr;
    let (first, second) = (read_linear_exr(a, "first image")?, read_linear_exr(b, "second image")?);
    let c = embray::compare_linear::compare_films(&first, &second)?;
    let [ra, ga, ba] = c.mean_a.to_array();
    let [rb, gb, bb] = c.mean_b.to_array();
    out(format!(
        "{}x{} linear: channel means [{ra:.6}, {ga:.6}, {ba:.6}] vs [{rb:.6}, {gb:.6}, {bb:.6}] \
         ({}); RMSE {:.6}, relative MSE {:.4e} (Σ err² / Σ ref²), \
         per-pixel relMSE {:.4e}, max abs {:.6}; \
         {:.4} % of pixels off by more than 1 % of the second's mean{}\n",
        c.width,
        c.height,
        match c.mean_relative_difference() {
            Some(d) => format!("largest difference {:.4} %", 100.0 * d),
            None => "no relative difference: a channel's mean is 0 in the second only".to_owned(),
        },
        c.rmse,
        c.error.relative_mse,
        c.error.pixel_relative_mse,
        c.error.max_abs,
        100.0 * c.error.fraction_off,
        [(c.error.non_finite, "first"), (c.error.non_finite_reference, "second")]
            .iter()
            .filter(|(count, _)| *count > 0)
            .map(|(count, which)| format!("; {count} non-finite pixels in the {which} (left out)"))
            .collect::<String>()
    ))?;
    Ok(())
}

/// Mitsuba's pass rule for `a` (rendered at `spp`) against the reference `b` and its
/// per-sample `variance`; a failing image is an exit status of 1.
fn mitsuba_rule(a: &Path, b: &Path, variance: &Path, spp: u32) -> Result<()> {
    use embray::bench::convergence::read_linear_exr;
    let (image, reference, variance_film) = (
        read_linear_exr(a, "image")?,
        read_linear_exr(b, "reference")?,
        read_linear_exr(variance, "variance")?,
    );
    embray::compare_linear::check_variance(&variance_film, variance)?;
    let variance = variance_film;
    let size = |f: &embray::film::Film| (f.width, f.height);
    if size(&image) != size(&reference) || size(&variance) != size(&reference) {
        anyhow::bail!("the image, the reference and the variance must have the same size");
    }
    let verdict = embray::mitsuba_rule::judge(&image.color, &reference.color, &variance.color, spp);
    out(format!(
        "Mitsuba's rule at {spp} spp: {} of {} pixel channels pass ({:.3} %, {:.2} % needed): {}\n",
        verdict.passing,
        verdict.channels,
        100.0 * verdict.fraction(),
        100.0 * embray::mitsuba_rule::PASS_FRACTION,
        if verdict.passes() { "PASS" } else { "FAIL" }
    ))?;
    if !verdict.passes() {
        anyhow::bail!("the image fails Mitsuba's pass rule");
    }
    Ok(())
}
