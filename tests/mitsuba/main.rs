//! Mitsuba 3 scenes: the reader's syntax and semantics on scenes written here (always), and
//! Mitsuba's own render regression suite and Cornell box judged by Mitsuba's pass rule (when
//! `../shared/data/mitsuba` is there).

#[path = "../common/mod.rs"]
mod common;

mod blend;
mod bsdfs;
mod emitters_compat;
mod film_sampler;
mod glass;
mod principled;
mod reader;
mod shapes_compat;
mod suite;

use embray::scene::SceneDesc;
use std::path::Path;

/// The one scene of the Mitsuba file at `path`, with `-D` parameters.
fn load_mitsuba(path: &Path, defines: &[(&str, &str)]) -> Result<SceneDesc, String> {
    let defines: Vec<(String, String)> =
        defines.iter().map(|(n, v)| (n.to_string(), v.to_string())).collect();
    let (mut scenes, _) =
        embray::scene::xml::load_with_warnings(path, &defines).map_err(|e| e.to_string())?;
    assert_eq!(scenes.len(), 1, "a Mitsuba file is one scene");
    Ok(scenes.remove(0).scene)
}

/// `scene`, read from the Mitsuba file at `path`, as `embray convert` writes it to TOML
/// (beside `path`) and reads it back.
fn converted(path: &Path, scene: &SceneDesc) -> SceneDesc {
    let dir = path.parent().unwrap();
    let mut writer = embray::scene::toml_writer::TomlWriter::new(dir.join("meshes"));
    let toml = dir.join("scene.toml");
    writer.write(scene, &toml, "round trip").unwrap();
    embray::scene::load(&toml).unwrap_or_else(|e| panic!("{e}"))
}
