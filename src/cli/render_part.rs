//! `embray render SCENE --part I/N`: one part of a split render, written as a part file for
//! `embray merge`.

use super::console::{note, out};
use super::render_args::RenderArgs;
use anyhow::{Result, bail};
use embray::distributed::{
    Part, PartMeta, PartTiming, PngSettings, encode_part, hash_files, options_fingerprint,
};
use embray::output::stats::stats_table;
use embray::output::{OutputPlan, OutputSet};
use embray::render::{TILE_SIZE, render_part};
use std::path::PathBuf;

/// The part file's default name.
pub fn default_part_path(part: Part) -> PathBuf {
    PathBuf::from(format!("part-{}-of-{}.exr", part.index, part.count))
}

/// Renders `part` of the scene `args` names and commits its part file.
pub fn run(args: &RenderArgs, part: Part) -> Result<()> {
    if let Some(problem) = args.part_flag_problem() {
        bail!(problem);
    }
    let mut plan = OutputPlan::new();
    if let Some(path) = &args.scene {
        plan.input("the scene", path);
    }
    let mut scene = match args.scene.as_deref() {
        Some(path) if embray::scene::ceng795::is_ceng795_path(path) => {
            let cameras = embray::scene::xml::load(path, &args.defines)?;
            let mut cameras =
                super::preview::select_cameras(cameras, args.camera.as_deref(), path)?;
            if cameras.len() != 1 {
                bail!(
                    "'{}' has {} cameras; --part renders one image: choose one with \
                     --camera",
                    path.display(),
                    cameras.len()
                );
            }
            cameras.swap_remove(0).scene
        }
        path => super::load_scene(path, &args.defines)?,
    };
    args.apply_preview(&mut scene)?;
    if let Some(problem) = RenderArgs::part_scene_problem(&scene) {
        bail!(problem);
    }
    plan.inputs_read(&embray::input_file::files_read());
    let output = args.output.clone().unwrap_or_else(|| default_part_path(part));
    let target = plan.output(
        if args.output.is_some() { "-o" } else { "the part file (default)" },
        &output,
        false,
    )?;
    let options = args.to_options(&scene)?;
    let camera = args.camera.as_ref().map(|c| format!("camera '{c}'"));
    args.check_samples(&scene, options.spp, camera.as_deref())?;
    let files = embray::scene::files_read();
    let scene_hash = hash_files(&files)?;
    let rendered = render_part(&scene, &options, part)?;
    let timing = PartTiming {
        build_seconds: rendered.build_time.as_secs_f64(),
        render_seconds: rendered.render_time.as_secs_f64(),
        cpu_seconds: embray::distributed::process_cpu_seconds(),
        threads: options.worker_threads(),
        host: std::fs::read_to_string("/proc/sys/kernel/hostname")
            .unwrap_or_default()
            .trim()
            .to_owned(),
    };
    let meta = part_meta(args, &scene, &options, part, scene_hash, rendered.stats, timing)?;
    let mut set = OutputSet::new();
    set.write(&target, |w| encode_part(&meta, &rendered.sums, w))?;
    set.commit()?;
    if !args.quiet {
        let samples = part.samples(options.spp);
        note(format!(
            "part {part} ({} split; samples {}..{} of {}) of {}x{} on {}: render {:.3} s, {} rays → {}",
            part.split,
            samples.start,
            samples.end,
            options.spp,
            meta.width,
            meta.height,
            rendered.backend,
            rendered.render_time.as_secs_f64(),
            rendered.stats.total_rays(),
            output.display()
        ));
    }
    if args.stats || args.time_phases {
        out(stats_table(&rendered.stats, rendered.observes, options.time_phases))?;
    }
    Ok(())
}

/// The metadata of a render of `scene` (`part` of it): what a part file holds, and what a
/// final EXR says about itself (`PartMeta::image_attributes`).
pub fn part_meta(
    args: &RenderArgs,
    scene: &embray::scene::SceneDesc,
    options: &embray::render::RenderOptions,
    part: Part,
    scene_hash: String,
    stats: embray::stats::RenderStats,
    timing: PartTiming,
) -> Result<PartMeta> {
    let photographic = args.look.photographic.resolve(scene.settings.tonemap.as_ref())?;
    let uses_embree = options.backend == embray::accel::BackendKind::Embree;
    Ok(PartMeta {
        format: embray::distributed::PART_FORMAT.to_owned(),
        embray_version: env!("CARGO_PKG_VERSION").to_owned(),
        embree: uses_embree.then(embray::accel::embree_library).flatten().map(|l| l.to_string()),
        scene: args
            .scene
            .as_ref()
            .map_or("(built-in Cornell box)".to_owned(), |p| p.display().to_string()),
        scene_hash,
        options: options_fingerprint(options),
        camera: embray::distributed::camera_fingerprint(&scene.camera),
        width: scene.camera.width,
        height: scene.camera.height,
        spp: options.spp,
        tile_size: TILE_SIZE,
        part,
        aovs: args.aovs_for(scene).to_string(),
        png: PngSettings {
            curve: args.tonemap.resolve(&scene.settings).to_string(),
            exposure: args.look.exposure,
            photographic: [
                photographic.key,
                photographic.burn_out,
                photographic.saturation,
                photographic.gamma,
            ],
        },
        stats,
        timing,
    })
}
