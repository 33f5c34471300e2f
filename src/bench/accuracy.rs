//! `embray bench accuracy`: render space × backend × distance from the origin over a set of
//! scenes, with times, counters, image error, charts, an image strip and the spawn-method
//! comparison, written into one folder.

use super::grid::{Grid, Measurement, measure};
use super::spawn_report::{self, SpawnRow};
use super::{plots, strip, table};
use crate::accel::BackendKind;
use crate::render::{RenderError, RenderOptions, render};
use crate::render_space::RenderSpace;
use crate::scene::{SceneDesc, SceneError, load};
use crate::shading::spawn::SpawnMode;
use glam::DVec3;
use std::path::PathBuf;

#[derive(Clone, Debug)]
pub struct AccuracyOptions {
    pub scenes: Vec<PathBuf>,
    pub offsets: Vec<f64>,
    pub backends: Vec<BackendKind>,
    pub runs: usize,
    pub spp: u32,
    /// Longest image side; larger scenes are scaled down.
    pub max_size: u32,
    pub threads: Option<usize>,
    pub out_dir: PathBuf,
    /// Scenes for the spawn comparison (grazing plane, thin walls); skipped if `None`.
    pub spawn_scenes: Option<(PathBuf, PathBuf)>,
    pub spawn_methods: Vec<SpawnMode>,
}

#[derive(Debug)]
pub struct AccuracyReport {
    pub rows: Vec<Measurement>,
    pub spawn_rows: Vec<SpawnRow>,
    /// Files written into `out_dir`.
    pub files: Vec<PathBuf>,
    /// Things that could not be produced (e.g. charts without a font).
    pub warnings: Vec<String>,
}

#[derive(Debug, thiserror::Error)]
pub enum AccuracyError {
    #[error(transparent)]
    Scene(#[from] SceneError),
    #[error(transparent)]
    Render(#[from] RenderError),
    #[error("cannot write '{path}': {message}")]
    Write { path: PathBuf, message: String },
}

/// The bundled scenes of the default report: the Cornell box and the precision scenes.
pub fn default_scenes() -> Vec<PathBuf> {
    let mut scenes = vec![crate::bundled::default_scene()];
    scenes.extend(crate::bundled::scenes_in("scenes/precision"));
    scenes
}

fn shrink(scene: &mut SceneDesc, max_size: u32) {
    let longest = scene.camera.width.max(scene.camera.height);
    if longest > max_size {
        let scale = max_size as f64 / longest as f64;
        scene.camera.width = ((scene.camera.width as f64 * scale).round() as u32).max(1);
        scene.camera.height = ((scene.camera.height as f64 * scale).round() as u32).max(1);
    }
}

fn write(path: PathBuf, text: &str, files: &mut Vec<PathBuf>) -> Result<(), AccuracyError> {
    crate::output::write_one(&path, |sink| sink.write_all(text.as_bytes()))
        .map_err(|e| AccuracyError::Write { path: path.clone(), message: e.to_string() })?;
    files.push(path);
    Ok(())
}

fn base_options(scene: &SceneDesc, options: &AccuracyOptions) -> RenderOptions {
    let mut base = RenderOptions::for_scene(scene);
    base.spp = options.spp;
    base.threads = options.threads;
    base.seed = 1;
    base
}

/// The scene with the largest `world`-space error at the largest offset.
fn worst_world_scene(rows: &[Measurement]) -> Option<String> {
    let largest = rows.iter().map(|r| r.offset).fold(f64::NEG_INFINITY, f64::max);
    rows.iter()
        .filter(|r| r.render_space == "world" && r.offset == largest)
        .max_by(|a, b| a.error.relative_mse.total_cmp(&b.error.relative_mse))
        .map(|r| r.scene.clone())
}

/// Runs the whole report; `progress` hears a short message after each configuration.
pub fn run(
    options: &AccuracyOptions,
    mut progress: impl FnMut(&str),
) -> Result<AccuracyReport, AccuracyError> {
    std::fs::create_dir_all(&options.out_dir).map_err(|e| AccuracyError::Write {
        path: options.out_dir.clone(),
        message: e.to_string(),
    })?;
    let grid = Grid {
        backends: options.backends.clone(),
        spaces: vec![RenderSpace::World, RenderSpace::Camera, RenderSpace::Cameraworld],
        offsets: options.offsets.clone(),
        runs: options.runs,
    };
    let mut rows = Vec::new();
    let mut strip_rows: Vec<Vec<crate::film::Film>> = Vec::new();
    for path in &options.scenes {
        let mut scene = load(path)?;
        shrink(&mut scene, options.max_size);
        let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        let base = base_options(&scene, options);
        rows.extend(measure(&name, &scene, &base, &grid, |row| {
            progress(&format!(
                "{} {} {} {:e}",
                row.scene, row.render_space, row.backend, row.offset
            ));
        })?);
    }
    // The strip shows the scene that world space damages most at the largest offset.
    if let Some(worst) = worst_world_scene(&rows) {
        let path = options
            .scenes
            .iter()
            .find(|p| p.file_stem().is_some_and(|s| s.to_string_lossy() == worst));
        if let Some(path) = path {
            let mut scene = load(path)?;
            shrink(&mut scene, options.max_size);
            let mut base = base_options(&scene, options);
            base.spp = base.spp.max(16);
            for space in [RenderSpace::World, RenderSpace::Cameraworld] {
                let mut films = Vec::new();
                for &offset in &options.offsets {
                    let mut o = base.clone();
                    o.backend = options.backends[0];
                    o.render_space = space;
                    o.offset = DVec3::splat(offset);
                    films.push(render(&scene, &o)?.film);
                }
                strip_rows.push(films);
            }
        }
    }
    let mut spawn_rows = Vec::new();
    if let Some((grazing, thin)) = &options.spawn_scenes {
        let (mut grazing, mut thin) = (load(grazing)?, load(thin)?);
        shrink(&mut grazing, options.max_size);
        shrink(&mut thin, options.max_size);
        let base = base_options(&grazing, options);
        progress("spawn methods");
        spawn_rows = spawn_report::compare(
            &grazing,
            &thin,
            &base,
            &options.backends,
            &options.spawn_methods,
            options.runs,
        )?;
    }
    let mut files = Vec::new();
    let mut warnings = Vec::new();
    let mut markdown = table::markdown(&rows);
    if !spawn_rows.is_empty() {
        markdown += "\n";
        markdown += &spawn_report::markdown(&spawn_rows);
    }
    write(options.out_dir.join("report.md"), &markdown, &mut files)?;
    write(options.out_dir.join("report.csv"), &table::csv(&rows), &mut files)?;
    match plots::write_charts(&options.out_dir, &rows) {
        Ok(mut charts) => files.append(&mut charts),
        Err(message) => warnings.push(message),
    }
    let strip_path = options.out_dir.join("strip.png");
    match strip::write_strip(&strip_path, &strip_rows, 48, 3) {
        Ok(()) => files.push(strip_path),
        Err(message) => warnings.push(message),
    }
    Ok(AccuracyReport { rows, spawn_rows, files, warnings })
}
