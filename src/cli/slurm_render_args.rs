//! What `embray slurm` checks of the render options before it submits anything: that they
//! parse as `embray render`'s, that the split works for the scene, and what every part will
//! record of the scene and options.

use anyhow::{Context, Result, bail};
use clap::Parser;
use embray::distributed::slurm::JobFile;
use embray::distributed::{Part, PartIdentity, Split};
use std::path::Path;

/// What the job's parts must record, from its scene and options as they are now (a part
/// rendered now records that); asked at most once per command, as following a job asks
/// for its status every few seconds.
pub(super) fn identity_source() -> impl FnMut(&JobFile) -> Result<PartIdentity, String> {
    let mut known: Option<Result<PartIdentity, String>> = None;
    move |job| {
        let identity = || check_render_args(&job.scene, job.parts, job.split, &job.render_args);
        known.get_or_insert_with(|| identity().map_err(|e| format!("{e:#}"))).clone()
    }
}

/// Parses the render options as `embray render` would and checks that the split works for
/// the scene, so that nothing is submitted that every task would refuse. Returns what each
/// part will record of the scene and the options.
pub(super) fn check_render_args(
    scene: &Path,
    parts: u32,
    split: Split,
    render_args: &[String],
) -> Result<PartIdentity> {
    let read_before_scene = embray::scene::files_read().len();
    let mut argv = vec!["embray".to_owned(), "render".to_owned()];
    argv.push(scene.to_string_lossy().into_owned());
    argv.extend(render_args.iter().cloned());
    let cli = super::Cli::try_parse_from(&argv).context("the render options (after --)")?;
    let super::Command::Render(render) = cli.command else {
        bail!("the render options (after --) are not `embray render` options");
    };
    let mut desc = if embray::scene::ceng795::is_ceng795_path(scene) {
        let cameras = embray::scene::xml::load(scene, &render.defines)?;
        let mut cameras = super::preview::select_cameras(cameras, render.camera.as_deref(), scene)?;
        if cameras.len() != 1 {
            bail!(
                "'{}' has {} cameras; a split render is one image: choose one with --camera \
                 (after --)",
                scene.display(),
                cameras.len()
            );
        }
        cameras.swap_remove(0).scene
    } else {
        super::load_scene(Some(scene), &render.defines)?
    };
    render.apply_preview(&mut desc)?;
    if let Some(problem) = render.part_flag_problem() {
        bail!("{problem} (after --: a split render's parts are `embray render --part`)");
    }
    if let Some(problem) = super::render_args::RenderArgs::part_scene_problem(&desc) {
        bail!(problem);
    }
    let options = render.to_options(&desc)?;
    let camera = render.camera.as_ref().map(|c| format!("camera '{c}'"));
    render.check_samples(&desc, options.spp, camera.as_deref())?;
    let part = Part { index: 0, count: parts, split };
    let size = (desc.camera.width, desc.camera.height);
    part.check(size, embray::render::TILE_SIZE, options.spp.max(1))?;
    // As `render --part` hashes them: the scene and every file it read, in order.
    let scene_files = embray::scene::files_read().split_off(read_before_scene);
    let scene_hash = embray::distributed::hash_files(&scene_files)?;
    Ok(PartIdentity { scene_hash, options: embray::distributed::options_fingerprint(&options) })
}
