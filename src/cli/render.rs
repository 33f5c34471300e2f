//! `embray render`: one scene (or every camera of a CENG795 file) to EXR and PNG, with the
//! summary line and the statistics.

use super::console::{note, out};
use super::load_scene;
use super::render_args::RenderArgs;
use super::render_part::part_meta;
use anyhow::{Result, bail};
use embray::distributed::Part;
use embray::distributed::{PartMeta, PartTiming};
use embray::excerpt::excerpt;
use embray::film::Film;
use embray::output::Aovs;
use embray::output::stats::{StatsReport, stats_table};
use embray::output::{
    DisplayLook, ImageFormat, OutputPlan, OutputSet, Target, camera_outputs, encode_display,
    encode_exr,
};
use embray::render::{RenderOptions, RenderOutput, render_with};
use embray::render_stop::{Stop, StopReason};
use embray::sample_sums::FilmSums;
use embray::scene::{SceneDesc, ceng795};
use std::path::Path;
use std::time::{Duration, Instant};

/// One image of the run: the scene as its camera sees it and where its files go (the EXR,
/// the display image, or both).
struct Job {
    scene: SceneDesc,
    exr: Option<Target>,
    display: Option<DisplayTarget>,
}

/// Where a display image goes, and as what.
type DisplayTarget = (Target, ImageFormat);

/// Renders the scene (every camera of a CENG795 file), then commits all the files together:
/// every output path is checked first (usable, not an input, not another output), and
/// nothing is replaced unless every image was rendered and written.
pub fn run(args: &RenderArgs) -> Result<()> {
    let started = Instant::now();
    if let Some(text) = &args.part {
        return super::render_part::run(args, Part::parse(text, args.split)?);
    }
    let mut plan = OutputPlan::new();
    if let Some(path) = &args.scene {
        plan.input("the scene", path);
    }
    let lut = super::read_lut(args.look.lut.as_deref(), &mut plan)?;
    // The scene's files are what is read from here on (the LUT grades the PNG only).
    let read_before_scene = embray::scene::files_read().len();
    let jobs = match args.scene.as_deref().filter(|p| ceng795::is_ceng795_path(p)) {
        Some(path) => ceng795_jobs(args, path, &mut plan)?,
        None => {
            if args.out_dir != Path::new(".") {
                note(
                    "warning: --out-dir is used for CENG795 .xml scenes only; this scene's \
                      files are named by -o and --png",
                );
            }
            if args.camera.is_some() {
                bail!(
                    "--camera chooses among the cameras of a CENG795 .xml file; this scene has one"
                );
            }
            let mut scene = load_scene(args.scene.as_deref(), &args.defines)?;
            args.apply_preview(&mut scene)?;
            plan.inputs_read(&embray::input_file::files_read());
            let (exr, display) = scene_outputs(args, &mut plan)?;
            vec![Job { scene, exr, display }]
        }
    };
    let stats_json =
        args.stats_json.as_deref().map(|p| plan.output("--stats-json", p, false)).transpose()?;
    for job in &jobs {
        args.to_options(&job.scene)?;
        args.look.photographic.resolve(job.scene.settings.tonemap.as_ref())?;
        if job.display.is_some() {
            args.look.photographic.check_curve(args.tonemap.resolve(&job.scene.settings))?;
        }
    }
    let stop = Stop::new(args.time_limit.map(|s| started + Duration::from_secs_f64(s)));
    stop.watch();
    let scene_files = embray::scene::files_read().split_off(read_before_scene);
    let scene_hash = embray::distributed::hash_files(&scene_files)?;
    let rendered = render_jobs(args, &scene_hash, &jobs, &stop, lut.as_ref(), stats_json.as_ref());
    stop.unwatch();
    let (files, reports, stopped) = rendered?;
    files.commit()?;
    for (line, table) in reports {
        if !args.quiet {
            note(line);
        }
        if args.stats {
            out(table)?;
        }
    }
    match stopped {
        Some(Stopped { reason, skipped, .. }) => {
            if !skipped.is_empty() {
                note(format!("not rendered ({reason}): {}", skipped.join(", ")));
            }
            // A signal still ends the process as the signal would have: scripts see it.
            if let StopReason::Signal(signal) = reason {
                std::process::exit(128 + signal);
            }
            Ok(())
        }
        None => Ok(()),
    }
}

/// The EXR's AOVs and text attributes.
type ExrLook = (Aovs, Vec<(String, String)>);

/// A run that stopped early: why, and the images it did not render.
struct Stopped {
    reason: StopReason,
    skipped: Vec<String>,
}

type Rendered = (OutputSet, Vec<(String, String)>, Option<Stopped>);

/// Renders every job into `files` (not yet committed), until a stop.
fn render_jobs(
    args: &RenderArgs,
    scene_hash: &str,
    jobs: &[Job],
    stop: &Stop,
    lut: Option<&embray::output::Lut3d>,
    stats_json: Option<&Target>,
) -> Result<Rendered> {
    let mut files = OutputSet::new();
    let mut reports = Vec::new();
    for (k, job) in jobs.iter().enumerate() {
        let mut options = args.to_options(&job.scene)?;
        options.stop = Some(stop.clone());
        let curve = args.tonemap.resolve(&job.scene.settings);
        let photographic = args.look.photographic.resolve(job.scene.settings.tonemap.as_ref())?;
        let look =
            DisplayLook { curve, exposure: args.look.exposure, photographic: &photographic, lut };
        let mut last_write = Instant::now();
        let every = args.checkpoint_every.map(Duration::from_secs_f64);
        let spp = options.spp.max(1);
        let (hash, whole) = (scene_hash.to_owned(), Part::WHOLE);
        let timing = PartTiming::default();
        let meta = part_meta(args, &job.scene, &options, whole, hash, Default::default(), timing)?;
        let mut on_pass = |sums: &FilmSums, done: u32| {
            if every.is_some_and(|every| last_write.elapsed() >= every) && done < spp {
                checkpoint(job, &sums.resolve(), &look, &meta, args.aovs, done);
                last_write = Instant::now();
            }
        };
        let output = render_with(&job.scene, &options, &mut on_pass)?;
        if let (Some(reason), 0) = (output.stopped, output.spp_done) {
            bail!("{reason} before the first pass over the image ended: no image written");
        }
        for warning in output.warnings.iter().filter(|_| !args.quiet) {
            super::console::note(format!("warning: {warning}"));
        }
        if output.film.color.iter().all(|c| *c == glam::Vec3::ZERO) && !args.quiet {
            // A black image with exit 0 is the worst kind of silence: say what to look at.
            super::console::note(
                "warning: the image is black: no light reached the camera (an emitter facing \
                 away from the scene (a quad emits along u × v), a light inside a closed \
                 object, max_depth 0?); `embray info` lists the lights",
            );
        }
        let stopped = output.stopped.map(|reason| reason.to_string());
        let exr_look = (args.aovs, meta.image_attributes(output.spp_done, stopped));
        write_job(&mut files, job, &output.film, &look, &exr_look)?;
        if let Some(target) = stats_json {
            let report = StatsReport::new(&output, &options);
            files.write(target, |w| report.encode(w))?;
        }
        let written: Vec<&Path> =
            job.exr.iter().chain(job.display.iter().map(|(t, _)| t)).map(|t| &*t.path).collect();
        let line = summary(&output, &options, &written);
        reports.push((line, stats_table(&output.stats, output.observes)));
        if let Some(reason) = output.stopped {
            let skipped = jobs[k + 1..].iter().flat_map(job_paths).collect();
            return Ok((files, reports, Some(Stopped { reason, skipped })));
        }
    }
    Ok((files, reports, None))
}

/// The files a job writes, for messages.
fn job_paths(job: &Job) -> Vec<String> {
    let exr = job.exr.iter();
    exr.chain(job.display.iter().map(|(t, _)| t)).map(|t| t.path.display().to_string()).collect()
}

/// Adds a job's images to `files`.
fn write_job(
    files: &mut OutputSet,
    job: &Job,
    film: &Film,
    look: &DisplayLook,
    exr_look: &ExrLook,
) -> Result<()> {
    if let Some(exr) = &job.exr {
        files.write(exr, |w| encode_exr(film, exr_look.0, &exr_look.1, w))?;
    }
    if let Some((target, format)) = &job.display {
        files.write(target, |w| encode_display(film, look, *format, w))?;
    }
    Ok(())
}

/// Writes the image so far over the job's outputs (each atomically); a failure is a
/// warning, as the render goes on.
fn checkpoint(job: &Job, film: &Film, look: &DisplayLook, meta: &PartMeta, aovs: Aovs, done: u32) {
    let spp = meta.spp.max(1);
    let exr_look = (aovs, meta.image_attributes(done, Some("in progress (a checkpoint)".into())));
    let mut files = OutputSet::new();
    match write_job(&mut files, job, film, look, &exr_look).and_then(|()| Ok(files.commit()?)) {
        Ok(()) => note(format!("checkpoint: {done} of {spp} spp → {}", job_paths(job).join(", "))),
        Err(e) => note(format!("warning: checkpoint at {done} spp not written: {e:#}")),
    }
}

/// Where a scene's images go. `-o` chooses the format by its extension: an EXR (with the
/// PNG beside it, or `--png`), or only a PNG or JPEG; `--png` alone writes only that image;
/// with neither, both are named after the scene (`cornell.exr`, `cornell.png`).
fn scene_outputs(
    args: &RenderArgs,
    plan: &mut OutputPlan,
) -> Result<(Option<Target>, Option<DisplayTarget>)> {
    let display_format = |path: &Path| -> Result<ImageFormat> {
        match ImageFormat::of_path(path, "--png").map_err(anyhow::Error::msg)? {
            Some(ImageFormat::Exr) => {
                bail!("--png '{}' names an EXR: the EXR is -o's", path.display())
            }
            Some(format) => Ok(format),
            None => Ok(ImageFormat::Png),
        }
    };
    let Some(output) = &args.output else {
        if let Some(png) = &args.png {
            let target = plan.output("--png", png, false)?;
            return Ok((None, Some((target, display_format(png)?))));
        }
        let stem = args.scene.clone().unwrap_or_else(embray::bundled::default_scene);
        let stem = stem.file_stem().map_or("render".into(), |s| s.to_string_lossy());
        let exr = plan.output("the EXR (default)", Path::new(&format!("{stem}.exr")), false)?;
        let png = Path::new(&format!("{stem}.png")).to_path_buf();
        let png = plan.output("the PNG (default)", &png, false)?;
        return Ok((Some(exr), Some((png, ImageFormat::Png))));
    };
    let target = plan.output("-o", output, false)?;
    match ImageFormat::of_path(output, "-o").map_err(anyhow::Error::msg)? {
        Some(format) if format.is_display() => {
            if args.png.is_some() {
                bail!(
                    "-o '{}' is the display image already; --png would name a second one \
                     (give -o an .exr to write both)",
                    output.display()
                );
            }
            Ok((None, Some((target, format))))
        }
        format => {
            if format.is_none() && !target.is_stream() {
                bail!(
                    "-o '{}' has no extension: name the format (.exr, .png, .jpg or .jpeg)",
                    output.display()
                );
            }
            let png = png_target(args, &target, &args.png_path(), false, plan)?;
            let format = display_format(&png.path)?;
            Ok((Some(target), Some((png, format))))
        }
    }
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
    let cameras = embray::scene::xml::load(path, &args.defines)?;
    let mut cameras = super::preview::select_cameras(cameras, args.camera.as_deref(), path)?;
    for camera in &mut cameras {
        args.apply_preview(&mut camera.scene)?;
    }
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
    if cameras.len() == 1 && (args.output.is_some() || args.png.is_some()) {
        // One camera named by -o/--png: the formats follow the names, as for any scene.
        let (exr, display) = scene_outputs(args, plan)?;
        let scene = cameras.into_iter().next().unwrap().scene;
        return Ok(vec![Job { scene, exr, display }]);
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
        jobs.push(Job {
            scene: camera.scene,
            exr: Some(exr),
            display: Some((png, ImageFormat::Png)),
        });
    }
    Ok(jobs)
}

fn summary(output: &RenderOutput, options: &RenderOptions, written: &[&Path]) -> String {
    let seconds = output.render_time.as_secs_f64();
    let rays = output.stats.total_rays();
    format!(
        "{}x{} @ {} ({} sampler) on {} ({}): build {:.1} ms, render {:.3} s, {} rays, {:.2} Mrays/s → {}",
        output.film.width,
        output.film.height,
        match output.stopped {
            Some(reason) => format!("{} of {} spp, {reason}", output.spp_done, options.spp.max(1)),
            None => format!("{} spp", options.spp),
        },
        options.sampler,
        output.backend,
        options.render_space,
        output.build_time.as_secs_f64() * 1e3,
        seconds,
        rays,
        rays as f64 / seconds.max(1e-9) / 1e6,
        written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", "),
    )
}
