//! Scene files → `SceneDesc`.
//!
//! `load` reads a TOML scene, `load_str` parses text that came from `source` (used in
//! messages and to resolve relative OBJ paths). The stages: TOML syntax (`source_map`), a
//! scan rejecting every NaN/inf, serde into `toml_format` (unknown keys are errors), then
//! `convert` validates and builds the world-space `SceneDesc`.
//!
//! `ceng795` reads the METU CENG795 course's XML format (one `SceneDesc` per camera), and
//! `toml_writer` writes a `SceneDesc` back as TOML with OBJ meshes.
pub mod budget;
pub mod ceng795;
pub mod desc;
pub use desc::*;

mod camera_settings;
mod error;
mod from_toml;
pub use crate::input_file::{MAX_INPUT_BYTES, files_read, read_bytes as read_input_bytes};
mod materials;
mod mesh_file;
mod obj;
mod obj_scan;
mod ply;
mod shapes;
mod source_map;
pub mod texture_image;
mod toml_format;
pub mod toml_writer;
mod transform_list;
mod validate;

pub use camera_settings::MAX_RESOLUTION;
pub use error::{Line, SceneError};
pub use from_toml::MAX_REPEAT_COPIES;
pub use materials::with_texture_space;
pub use mesh_file::area_weighted_normals;

use std::io::Write;
use std::path::Path;

/// Loads the scene file at `path`. Warnings (a missing MTL file) go to stderr.
pub fn load(path: &Path) -> Result<SceneDesc, SceneError> {
    let (scene, warnings) = load_with_warnings(path)?;
    print_warnings(&warnings);
    Ok(scene)
}

/// Parses scene text read from `source`. Warnings go to stderr.
pub fn load_str(text: &str, source: &Path) -> Result<SceneDesc, SceneError> {
    let (scene, warnings) = load_str_with_warnings(text, source)?;
    print_warnings(&warnings);
    Ok(scene)
}

/// As `load`, returning the warnings instead of printing them.
pub fn load_with_warnings(path: &Path) -> Result<(SceneDesc, Vec<String>), SceneError> {
    load_str_with_warnings(&read_scene_file(path)?, path)
}

/// The text of a scene file, or an error naming it.
pub(crate) fn read_scene_file(path: &Path) -> Result<String, SceneError> {
    crate::input_file::read_text(path)
        .map_err(|error| SceneError::Read { path: path.to_path_buf(), error })
}

/// As `load_str`, returning the warnings instead of printing them.
pub fn load_str_with_warnings(
    text: &str,
    source: &Path,
) -> Result<(SceneDesc, Vec<String>), SceneError> {
    let map = source_map::SourceMap::parse(text, source)?;
    map.check_finite(source)?;
    let file: toml_format::SceneFile =
        toml::from_str(text).map_err(|e| source_map::toml_error(source, &e))?;
    let ctx = validate::Ctx { file: source, map };
    let base_dir = source.parent().unwrap_or(Path::new(""));
    let mut warnings = Vec::new();
    let scene = from_toml::scene_desc(file, &ctx, base_dir, &mut warnings)?;
    Ok((scene, warnings))
}

fn print_warnings(warnings: &[String]) {
    for warning in warnings {
        let _ = writeln!(std::io::stderr(), "warning: {warning}");
    }
}
