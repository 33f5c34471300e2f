//! XML scenes: a Mitsuba 3 file (`<scene version=…>`) or a CENG795 course file (`<Scene>`),
//! told apart by the root element.

use super::ceng795::{self, CameraScene};
use super::mitsuba;
use crate::scene::error::SceneError;
use std::io::Write as _;
use std::path::Path;

/// The scenes of the XML file at `path`, one per camera. `defines` are Mitsuba's
/// `-D name=value` parameters. Warnings go to stderr.
pub fn load(path: &Path, defines: &[(String, String)]) -> Result<Vec<CameraScene>, SceneError> {
    let (scenes, warnings) = load_with_warnings(path, defines)?;
    for warning in &warnings {
        let _ = writeln!(std::io::stderr(), "warning: {}", crate::excerpt::terminal_safe(warning));
    }
    Ok(scenes)
}

/// As `load`, returning the warnings instead of printing them.
pub fn load_with_warnings(
    path: &Path,
    defines: &[(String, String)],
) -> Result<(Vec<CameraScene>, Vec<String>), SceneError> {
    let text = crate::scene::read_scene_file(path)?;
    if mitsuba::is_mitsuba(&text) {
        let (scene, warnings) = mitsuba::load(path, &text, defines)?;
        let stem = path.file_stem().map_or("render".into(), |s| s.to_string_lossy());
        return Ok((vec![CameraScene { image_name: format!("{stem}.png"), scene }], warnings));
    }
    if let Some(define) = defines.first() {
        return Err(not_a_parameter(path, define, "a CENG795 scene"));
    }
    ceng795::load_str_with_warnings(&text, path)
}

/// The error for `-D` given with a scene that has no parameters (of the format `kind`): it
/// would change nothing, though it was meant to.
pub fn not_a_parameter(path: &Path, define: &(String, String), kind: &str) -> SceneError {
    mitsuba::define_error(
        path,
        define,
        format!("parameters are for Mitsuba 3 scenes, and this is {kind}"),
    )
}
