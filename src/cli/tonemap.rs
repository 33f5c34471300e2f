//! `embray tonemap`: a tone curve (the photographic operator by default) applied to an
//! existing EXR, without rendering: how the course's EXR/PNG reference pairs check it, and
//! how a render's PNG is remade from its EXR with another curve or look.

use super::choices::{LookArgs, choice};
use anyhow::Result;
use clap::Args;
use embray::output::{DisplayLook, ImageFormat, OutputPlan, OutputSet, ToneMap, encode_display};
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct TonemapArgs {
    /// Linear EXR (its R, G, B channels; half or float, any compression).
    pub input: PathBuf,
    /// The image to write: PNG (.png, or no extension) or JPEG (.jpg, .jpeg).
    #[arg(short, long)]
    pub output: PathBuf,
    /// The tone curve: photographic (Reinhard et al.'s global operator: --key, --burn-out,
    /// --saturation, --gamma), aces, reinhard, none (clamp) or clamp255 (the course's);
    /// every curve `render --tonemap` names but `auto`, which needs the scene.
    #[arg(long, value_parser = choice::<ToneMap>(), default_value = "photographic")]
    pub tonemap: ToneMap,
    #[command(flatten)]
    pub look: LookArgs,
}

pub fn run(args: &TonemapArgs) -> Result<()> {
    args.look.check()?;
    args.look.photographic.check_curve(args.tonemap)?;
    let photographic = args.look.photographic.resolve(None)?;
    // The PNG may not overwrite the EXR: checked before anything is read.
    let mut plan = OutputPlan::new();
    plan.input("the EXR", &args.input);
    let lut = super::read_lut(args.look.lut.as_deref(), &mut plan)?;
    let png = plan.output("-o", &args.output, false)?;
    let hint = "tonemap writes a tone-mapped PNG or JPEG (.png, .jpg or .jpeg)";
    let format =
        ImageFormat::display_of_path(&args.output, "-o", hint).map_err(anyhow::Error::msg)?;
    let film = embray::bench::convergence::read_linear_exr(&args.input, "input")?;
    // Showing non-finite pixels is this command's job, but never as a silent black image.
    if let Some(bad) = film.non_finite() {
        let input = args.input.display();
        if bad.count == film.color.len() {
            anyhow::bail!("every pixel of '{input}' is NaN or infinite: there is nothing to show");
        }
        super::console::note(format!(
            "warning: '{input}' has {bad}; NaN is shown black, infinity white"
        ));
    }
    let mut files = OutputSet::new();
    let look = DisplayLook {
        curve: args.tonemap,
        exposure: args.look.exposure,
        photographic: &photographic,
        lut: lut.as_ref(),
    };
    files.write(&png, |w| encode_display(&film, &look, format, w))?;
    files.commit()?;
    Ok(())
}
