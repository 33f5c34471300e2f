//! `embray merge`: the part files of a split render → its EXR (and PNG).

use super::console::note;
use anyhow::{Result, bail};
use clap::Args;
use embray::distributed::{merge_parts, merge_some_parts};
use embray::output::{DisplayLook, ImageFormat, OutputPlan, OutputSet, encode_display, encode_exr};
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct MergeArgs {
    /// The part files, in any order: every part of one render, each once.
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
    /// The merged EXR (linear RGB, Z, N.X/N.Y/N.Z), as `embray render` writes it.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Also write the tone-mapped display image (.png, or .jpg/.jpeg for JPEG), with the
    /// settings the parts were rendered with.
    #[arg(long)]
    pub png: Option<PathBuf>,
    /// A 3-D LUT (.cube) applied to the PNG last, as a grading look.
    #[arg(long, value_name = "FILE.cube", requires = "png")]
    pub lut: Option<PathBuf>,
    /// Merge the parts there are into a preview, saying which are missing: missing tiles
    /// stay black (alpha 0); missing sample ranges are left out of every pixel's mean (the
    /// EXR records the spp reached).
    #[arg(long)]
    pub partial: bool,
    /// No summary line.
    #[arg(short, long)]
    pub quiet: bool,
}

pub fn run(args: &MergeArgs) -> Result<()> {
    let start = std::time::Instant::now();
    let mut plan = OutputPlan::new();
    for path in &args.parts {
        plan.input("the part file", path);
    }
    let lut = super::read_lut(args.lut.as_deref(), &mut plan)?;
    let exr = plan.output("-o", &args.output, false)?;
    match ImageFormat::of_path(&args.output, "-o").map_err(anyhow::Error::msg)? {
        Some(ImageFormat::Exr) => {}
        None if exr.is_stream() => {}
        _ => bail!(
            "-o '{}': merge writes the EXR there (name it .exr); the display image is --png's",
            args.output.display()
        ),
    }
    let png = args.png.as_deref().map(|p| plan.output("--png", p, false)).transpose()?;
    let display_format = match &args.png {
        None => ImageFormat::Png,
        Some(path) => ImageFormat::display_of_path(path, "--png", "the EXR is -o's")
            .map_err(anyhow::Error::msg)?,
    };
    let merged =
        if args.partial { merge_some_parts(&args.parts)? } else { merge_parts(&args.parts)? };
    let (meta, stats) = (&merged.meta, merged.stats);
    let film = merged.sums.resolve();
    let mut files = OutputSet::new();
    let aovs = embray::output::Aovs::parse(&meta.aovs).map_err(anyhow::Error::msg)?;
    let count = meta.part.count;
    let missing: Vec<String> = merged.missing.iter().map(|i| format!("{i}/{count}")).collect();
    let partial = (!missing.is_empty()).then(|| {
        let split = meta.part.split;
        format!("a partial merge ({split} split): parts {} missing", missing.join(", "))
    });
    let attributes = meta.image_attributes(merged.spp_reached(), partial.clone());
    files.write(&exr, |w| encode_exr(&film, aovs, &attributes, w))?;
    if let Some(png) = &png {
        // Each part's settings were checked as it was read.
        let (curve, exposure, photographic) =
            meta.png.look().map_err(|e| anyhow::anyhow!("the parts' PNG settings: {e}"))?;
        let look = DisplayLook { curve, exposure, photographic: &photographic, lut: lut.as_ref() };
        files.write(png, |w| encode_display(&film, &look, display_format, w))?;
    }
    files.commit()?;
    if let Some(partial) = partial.filter(|_| !args.quiet) {
        note(format!("warning: {partial}; the image is a preview"));
    }
    if !args.quiet {
        let render: f64 = merged.timings.iter().map(|t| t.render_seconds).sum();
        let longest = merged.timings.iter().map(|t| t.render_seconds).fold(0.0, f64::max);
        let cpu: f64 = merged.timings.iter().map(|t| t.cpu_seconds).sum();
        note(format!(
            "merged {} of {} parts ({} split) of {}x{} @ {} spp, {} rays in all (parts rendered for \
             {render:.3} s in all, the longest {longest:.3} s; {cpu:.2} s of CPU), in {:.3} s → {}{}",
            merged.timings.len(),
            meta.part.count,
            meta.part.split,
            meta.width,
            meta.height,
            merged.spp_reached(),
            stats.total_rays(),
            start.elapsed().as_secs_f64(),
            args.output.display(),
            args.png.as_ref().map(|p| format!(", {}", p.display())).unwrap_or_default(),
        ));
    }
    Ok(())
}
