//! Where a render run's images go: one job per image (every camera of a CENG795 file),
//! each with its EXR and display image, and their denoised siblings with `--denoise`. Every
//! path is planned (checked usable, not an input, not another output) before rendering.

use super::render_args::RenderArgs;
use anyhow::{Result, bail};
use embray::excerpt::excerpt;
use embray::output::{ImageFormat, OutputPlan, Target, camera_outputs};
use embray::scene::SceneDesc;
use std::path::{Path, PathBuf};

/// One image of the run: the scene as its camera sees it and where its files go (the EXR,
/// the display image, or both).
pub(super) struct Job {
    pub scene: SceneDesc,
    pub exr: Option<Target>,
    pub display: Option<DisplayTarget>,
    /// The denoised beauty's files (`--denoise`), beside the others.
    pub denoised: Option<(Option<Target>, Option<DisplayTarget>)>,
    /// Which camera of a CENG795 file it renders (`camera 2 of 3 ('side.png')`).
    pub camera: Option<String>,
}

/// Where a display image goes, and as what.
pub(super) type DisplayTarget = (Target, ImageFormat);

impl Job {
    pub fn new(scene: SceneDesc, exr: Option<Target>, display: Option<DisplayTarget>) -> Self {
        Job { scene, exr, display, denoised: None, camera: None }
    }

    /// The paths of the files it writes, for messages.
    pub fn paths(&self) -> Vec<&Path> {
        let denoised = self
            .denoised
            .iter()
            .flat_map(|(exr, display)| exr.iter().chain(display.iter().map(|(t, _)| t)));
        let display = self.display.iter().map(|(t, _)| t);
        self.exr.iter().chain(display).chain(denoised).map(|t| &*t.path).collect()
    }

    /// Plans the denoised beauty beside each image: `NAME.denoised.EXT`.
    pub fn plan_denoised(&mut self, plan: &mut OutputPlan) -> Result<()> {
        let sibling = |target: &Target, plan: &mut OutputPlan| -> Result<Target> {
            if target.is_stream() {
                bail!(
                    "--denoise writes its image beside '{}', a device or FIFO: name a file",
                    target.path.display()
                );
            }
            let path = denoised_path(&target.path);
            Ok(plan.output("the denoised image (--denoise)", &path, false)?)
        };
        let exr = self.exr.as_ref().map(|t| sibling(t, plan)).transpose()?;
        let display =
            self.display.as_ref().map(|(t, f)| sibling(t, plan).map(|d| (d, *f))).transpose()?;
        self.denoised = Some((exr, display));
        Ok(())
    }
}

/// `out.exr` → `out.denoised.exr`.
fn denoised_path(path: &Path) -> PathBuf {
    let stem = path.file_stem().map_or("render".into(), |s| s.to_string_lossy());
    let name = match path.extension() {
        Some(ext) => format!("{stem}.denoised.{}", ext.to_string_lossy()),
        None => format!("{stem}.denoised"),
    };
    path.with_file_name(name)
}

/// The files a job writes, for messages.
pub(super) fn job_paths(job: &Job) -> Vec<String> {
    job.paths().iter().map(|p| p.display().to_string()).collect()
}

/// Where a scene's images go. `-o` chooses the format by its extension: an EXR (with the
/// PNG beside it, or `--png`), or only a PNG or JPEG; `--png` alone writes only that image;
/// with neither, both are named after the scene (`cornell.exr`, `cornell.png`).
pub(super) fn scene_outputs(
    args: &RenderArgs,
    plan: &mut OutputPlan,
) -> Result<(Option<Target>, Option<DisplayTarget>)> {
    let display_format = |path: &Path| -> Result<ImageFormat> {
        ImageFormat::display_of_path(path, "--png", "the EXR is -o's").map_err(anyhow::Error::msg)
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
pub(super) fn ceng795_jobs(
    args: &RenderArgs,
    path: &Path,
    plan: &mut OutputPlan,
) -> Result<Vec<Job>> {
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
        return Ok(vec![Job::new(scene, exr, display)]);
    }
    let new_folders = args.output.is_none();
    let mut jobs = Vec::new();
    let count = cameras.len();
    for (k, camera) in cameras.into_iter().enumerate() {
        let name = excerpt(&camera.image_name);
        let label = match count {
            1 => format!("camera '{name}'"),
            _ => format!("camera {} of {count} ('{name}')", k + 1),
        };
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
        // A JPEG where the name says so (an ImageName of .jpg), else a PNG.
        let format = match ImageFormat::of_path(&png.path, "--png") {
            Ok(Some(format)) if format.is_display() => format,
            _ => ImageFormat::Png,
        };
        let job = Job::new(camera.scene, Some(exr), Some((png, format)));
        jobs.push(Job { camera: Some(label), ..job });
    }
    Ok(jobs)
}
