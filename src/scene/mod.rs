//! Scene files → `SceneDesc`.
//!
//! The format-neutral scene model (`desc`), its limits checks (`budget`), and the readers
//! of each file format (`formats`), which only translate syntax into the model.
//!
//! `load` reads a TOML scene, `load_str` parses text that came from `source` (used in
//! messages and to resolve relative OBJ paths); `ceng795` reads the METU CENG795 course's
//! XML format (one `SceneDesc` per camera), and `toml_writer` writes a `SceneDesc` back as
//! TOML with OBJ meshes.
pub mod budget;
pub mod desc;
pub(crate) mod reading_budget;
pub use desc::*;

mod error;
pub mod formats;
pub use crate::input_file::{MAX_INPUT_BYTES, files_read, read_bytes as read_input_bytes};
mod image_cache;
mod image_ref;
mod mesh_file;
mod round_shapes;
mod shapes;
pub mod texture_image;
mod vertex_normals;

pub use crate::limits::MAX_RESOLUTION;
pub use error::{Line, SceneError};
pub use formats::ceng795;
pub use formats::toml::MAX_REPEAT_COPIES;
pub use formats::toml::materials::with_texture_space;
pub use formats::toml::write as toml_writer;
pub use formats::{mitsuba, xml};
pub use vertex_normals::VertexNormals;

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
    formats::toml::load_str_with_warnings(text, source)
}

fn print_warnings(warnings: &[String]) {
    for warning in warnings {
        let _ = writeln!(std::io::stderr(), "warning: {}", crate::excerpt::terminal_safe(warning));
    }
}
