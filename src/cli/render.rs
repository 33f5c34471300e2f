//! `embray render`: one scene (or every camera of a CENG795 file) to EXR and PNG, with the
//! summary line and the statistics.

use super::console::{note, out};
use super::load_scene;
use super::render_args::RenderArgs;
use super::render_outputs::{DisplayTarget, Job, ceng795_jobs, job_paths, scene_outputs};
use super::render_part::part_meta;
use anyhow::{Result, bail};
use embray::distributed::Part;
use embray::distributed::{PartMeta, PartTiming};
use embray::film::Film;
use embray::output::Aovs;
use embray::output::stats::{StatsReport, stats_table};
use embray::output::{DisplayLook, OutputPlan, OutputSet, Target, encode_display, encode_exr};
use embray::render::{RenderOptions, RenderOutput, render_with};
use embray::render_stop::{Stop, StopReason};
use embray::sample_sums::FilmSums;
use embray::scene::ceng795;
use std::path::Path;
use std::time::{Duration, Instant};

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
            vec![Job::new(scene, exr, display)]
        }
    };
    let mut jobs = jobs;
    if args.aovs.is_some() && jobs.iter().all(|job| job.exr.is_none()) {
        note(
            "warning: --aovs chooses the EXR's channels, and no EXR is written (-o names a display image)",
        );
    }
    if args.denoise {
        if !embray::denoise::BUILT_IN {
            bail!(embray::denoise::DenoiseError::NotBuiltIn);
        }
        for job in &mut jobs {
            job.plan_denoised(&mut plan)?;
        }
    }
    let stats_json =
        args.stats_json.as_deref().map(|p| plan.output("--stats-json", p, false)).transpose()?;
    for job in &jobs {
        let options = args.to_options(&job.scene)?;
        args.check_samples(&job.scene, options.spp, job.camera.as_deref())?;
        if args.denoise {
            let triangle = options.backend.bytes_per_triangle();
            embray::denoise::check_memory(&job.scene, triangle, options.worker_threads())?;
        }
        args.look.photographic.resolve(job.scene.settings.tonemap.as_ref())?;
        if job.display.is_some() {
            args.look.photographic.check_curve(args.tonemap.resolve(&job.scene.settings))?;
        }
    }
    // Watched from the first tile on (`render_passes`), unwatched after the last camera.
    let stop = Stop::new(args.time_limit.map(|s| started + Duration::from_secs_f64(s)));
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
        if args.stats || args.time_phases {
            out(table)?;
        }
    }
    match stopped {
        Some(Stopped { reason, stopped_in, skipped }) => {
            if !skipped.is_empty() {
                // Exit 0 as for any time limit (README: Progressive renders), so the warning
                // is what tells a script's log that whole cameras are missing.
                let skipped: Vec<String> = skipped
                    .iter()
                    .map(|(camera, files)| format!("{camera} ({})", files.join(", ")))
                    .collect();
                note(format!(
                    "warning: {reason} in {}, whose image holds the passes done; the later \
                     cameras were skipped and their files not written: {} (render one alone \
                     with --camera NAME)",
                    stopped_in.as_deref().unwrap_or("the first camera"),
                    skipped.join(", ")
                ));
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

/// A run that stopped early: why, in which camera, and the cameras it did not render
/// (each with the files it would have written).
struct Stopped {
    reason: StopReason,
    stopped_in: Option<String>,
    skipped: Vec<(String, Vec<String>)>,
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
                checkpoint(job, &sums.resolve(), &look, &meta, args.aovs_for(&job.scene), done);
                last_write = Instant::now();
            }
        };
        let output = render_with(&job.scene, &options, &mut on_pass)?;
        if let (Some(reason), 0) = (output.stopped, output.spp_done) {
            if k == 0 {
                bail!("{reason} before the first pass over the image ended: no image written");
            }
            // Stopped before this camera's first pass ended: the cameras before it are kept,
            // this one is skipped with the rest.
            return Ok((files, reports, Some(stop_in(jobs, reason, k - 1, k))));
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
        let exr_look = (args.aovs_for(&job.scene), meta.image_attributes(output.spp_done, stopped));
        write_images(&mut files, (&job.exr, &job.display), &output.film, &look, &exr_look)?;
        if let Some((exr, display)) = &job.denoised {
            let started = Instant::now();
            let color = embray::denoise::denoise(&output.film)?;
            let film = Film { color, ..output.film.clone() };
            let (aovs, mut attributes) = exr_look;
            attributes.push(("denoised".into(), embray::denoise::DENOISER.into()));
            write_images(&mut files, (exr, display), &film, &look, &(aovs, attributes))?;
            if !args.quiet {
                note(format!("denoised in {:.2} s", started.elapsed().as_secs_f64()));
            }
        }
        if let Some(target) = stats_json {
            let report = StatsReport::new(&output, &options);
            files.write(target, |w| report.encode(w))?;
        }
        let line = summary(&output, &options, &job.paths());
        let table = stats_table(&output.stats, output.observes, options.time_phases);
        if let cut @ 1.. = output.stats.bounces.cut_trees {
            note(format!(
                "warning: {cut} samples' reflection and refraction trees reached {} rays and \
                 ended there (max depth {}: glass between mirrors branches at every hit)",
                embray::integrator::whitted::MAX_RAYS_PER_SAMPLE,
                options.max_depth
            ));
        }
        reports.push((line, table));
        if let Some(reason) = output.stopped {
            return Ok((files, reports, Some(stop_in(jobs, reason, k, k + 1))));
        }
    }
    Ok((files, reports, None))
}

/// A stop in camera `stopped_in` of `jobs`, the cameras from `first_skipped` on not rendered.
fn stop_in(jobs: &[Job], reason: StopReason, stopped_in: usize, first_skipped: usize) -> Stopped {
    let label = |job: &Job| job.camera.clone().unwrap_or_else(|| "the scene".into());
    let skipped = jobs[first_skipped..].iter().map(|job| (label(job), job_paths(job))).collect();
    Stopped { reason, stopped_in: jobs[stopped_in].camera.clone(), skipped }
}

/// Adds an image's EXR and display image (where wanted) to `files`.
fn write_images(
    files: &mut OutputSet,
    (exr, display): (&Option<Target>, &Option<DisplayTarget>),
    film: &Film,
    look: &DisplayLook,
    exr_look: &ExrLook,
) -> Result<()> {
    if let Some(exr) = exr {
        files.write(exr, |w| encode_exr(film, exr_look.0, &exr_look.1, w))?;
    }
    if let Some((target, format)) = display {
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
    let targets = (&job.exr, &job.display);
    match write_images(&mut files, targets, film, look, &exr_look)
        .and_then(|()| Ok(files.commit()?))
    {
        Ok(()) => {
            let paths = job.exr.iter().chain(job.display.iter().map(|(t, _)| t));
            let paths: Vec<String> = paths.map(|t| t.path.display().to_string()).collect();
            note(format!("checkpoint: {done} of {spp} spp → {}", paths.join(", ")))
        }
        Err(e) => note(format!("warning: checkpoint at {done} spp not written: {e:#}")),
    }
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
