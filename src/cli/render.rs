//! `embray render`: one scene (or every camera of a CENG795 file) to EXR and PNG, with the
//! summary line and the statistics.

use super::console::{note, out};
use super::load_scene;
use super::render_args::RenderArgs;
use anyhow::{Result, bail};
use embray::distributed::Part;
use embray::excerpt::excerpt;
use embray::output::stats::{StatsReport, stats_table};
use embray::output::{
    OutputPlan, OutputSet, Target, camera_outputs, encode_exr, encode_png_graded,
};
use embray::render::{RenderOptions, RenderOutput, render};
use embray::scene::{SceneDesc, ceng795};
use std::path::Path;

/// One image of the run: the scene as its camera sees it and where its files go.
struct Job {
    scene: SceneDesc,
    exr: Target,
    png: Target,
}

/// Renders the scene (every camera of a CENG795 file), then commits all the files together:
/// every output path is checked first (usable, not an input, not another output), and
/// nothing is replaced unless every image was rendered and written.
pub fn run(args: &RenderArgs) -> Result<()> {
    if let Some(text) = &args.part {
        return super::render_part::run(args, Part::parse(text, args.split)?);
    }
    let mut plan = OutputPlan::new();
    if let Some(path) = &args.scene {
        plan.input("the scene", path);
    }
    let lut = super::read_lut(args.look.lut.as_deref(), &mut plan)?;
    let jobs = match args.scene.as_deref().filter(|p| ceng795::is_ceng795_path(p)) {
        Some(path) => ceng795_jobs(args, path, &mut plan)?,
        None => {
            if args.out_dir != Path::new(".") {
                note(
                    "warning: --out-dir is used for CENG795 .xml scenes only; this scene's \
                      files are named by -o and --png",
                );
            }
            let scene = load_scene(args.scene.as_deref())?;
            plan.inputs_read(&embray::input_file::files_read());
            let exr_what = if args.output.is_some() { "-o" } else { "the EXR (default)" };
            let exr = plan.output(exr_what, &args.output_path(), false)?;
            let png = png_target(args, &exr, &args.png_path(), false, &mut plan)?;
            vec![Job { scene, exr, png }]
        }
    };
    let stats_json =
        args.stats_json.as_deref().map(|p| plan.output("--stats-json", p, false)).transpose()?;
    for job in &jobs {
        args.to_options(&job.scene)?;
        args.look.photographic.resolve(job.scene.settings.tonemap.as_ref())?;
    }
    let mut files = OutputSet::new();
    let mut reports = Vec::new();
    for job in &jobs {
        let options = args.to_options(&job.scene)?;
        let output = render(&job.scene, &options)?;
        files.write(&job.exr, |w| encode_exr(&output.film, w))?;
        let curve = args.tonemap.resolve(&job.scene.settings);
        let photographic = args.look.photographic.resolve(job.scene.settings.tonemap.as_ref())?;
        files.write(&job.png, |w| {
            encode_png_graded(
                &output.film,
                curve,
                args.look.exposure,
                &photographic,
                lut.as_ref(),
                w,
            )
        })?;
        if let Some(target) = &stats_json {
            let report = StatsReport::new(&output, &options);
            files.write(target, |w| report.encode(w))?;
        }
        let line = summary(&output, &options, &job.exr.path, &job.png.path);
        reports.push((line, stats_table(&output.stats, output.observes)));
    }
    files.commit()?;
    for (line, table) in reports {
        if !args.quiet {
            note(line);
        }
        if args.stats {
            out(table)?;
        }
    }
    Ok(())
}

/// The PNG target. A PNG named after a device EXR (`-o /dev/null` → `/dev/null.png`) would
/// create a file among the devices, so it must be named.
fn png_target(
    args: &RenderArgs,
    exr: &Target,
    png: &Path,
    new_folders: bool,
    plan: &mut OutputPlan,
) -> Result<Target> {
    if args.png.is_some() {
        return Ok(plan.output("--png", png, new_folders)?);
    }
    if exr.is_stream() && args.output.is_some() {
        bail!(
            "-o '{}' is a device or FIFO, so the PNG's default name '{}' (the EXR's with .png) \
             is not used: name the PNG with --png (e.g. --png /dev/null)",
            exr.path.display(),
            png.display()
        );
    }
    Ok(plan.output("the PNG (named after the EXR)", png, new_folders)?)
}

/// The jobs of a CENG795 file: each camera to its ImageName (PNG) in --out-dir and an EXR of
/// the same stem, or, for a one-camera file, to -o/--png when given.
fn ceng795_jobs(args: &RenderArgs, path: &Path, plan: &mut OutputPlan) -> Result<Vec<Job>> {
    let cameras = ceng795::load(path)?;
    plan.inputs_read(&embray::input_file::files_read());
    if cameras.len() > 1 {
        for (flag, given) in [
            ("-o", args.output.is_some()),
            ("--png", args.png.is_some()),
            ("--stats-json", args.stats_json.is_some()),
        ] {
            if given {
                bail!(
                    "{flag} names one file, but '{}' has {} cameras: their images are written \
                     to --out-dir under their ImageName",
                    path.display(),
                    cameras.len()
                );
            }
        }
    }
    let new_folders = args.output.is_none();
    let mut jobs = Vec::new();
    for camera in cameras {
        let (exr, png) = camera_outputs(
            &camera.image_name,
            &args.out_dir,
            args.output.as_deref(),
            args.png.as_deref(),
        );
        let exr_what = match &args.output {
            Some(_) => "-o".to_owned(),
            None => format!("the EXR of camera '{}'", excerpt(&camera.image_name)),
        };
        let exr = plan.output(&exr_what, &exr, new_folders)?;
        let png = if args.png.is_none() && args.output.is_none() {
            let what = format!("the PNG of camera '{}'", excerpt(&camera.image_name));
            plan.output(&what, &png, new_folders)?
        } else {
            png_target(args, &exr, &png, new_folders, plan)?
        };
        jobs.push(Job { scene: camera.scene, exr, png });
    }
    Ok(jobs)
}

fn summary(output: &RenderOutput, options: &RenderOptions, exr: &Path, png: &Path) -> String {
    let seconds = output.render_time.as_secs_f64();
    let rays = output.stats.total_rays();
    format!(
        "{}x{} @ {} spp ({} sampler) on {} ({}): build {:.1} ms, render {:.3} s, {} rays, {:.2} Mrays/s → {}, {}",
        output.film.width,
        output.film.height,
        options.spp,
        options.sampler,
        output.backend,
        options.render_space,
        output.build_time.as_secs_f64() * 1e3,
        seconds,
        rays,
        rays as f64 / seconds.max(1e-9) / 1e6,
        exr.display(),
        png.display(),
    )
}
