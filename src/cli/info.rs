//! `embray info`: what a scene (or each camera's scene of a CENG795 file) contains.

use super::console::out;
use anyhow::Result;
use embray::info::describe;
use embray::scene::ceng795;
use std::path::Path;

pub fn run(scene: Option<&Path>, defines: &[(String, String)]) -> Result<()> {
    out(format!("backends: {}\n", embray::accel::backends_description()))?;
    if let Some(path) = scene.filter(|p| ceng795::is_ceng795_path(p)) {
        for camera in embray::scene::xml::load(path, defines)? {
            out(format!("camera: {}\n{}", camera.image_name, describe(&camera.scene)))?;
        }
        return Ok(());
    }
    out(describe(&super::load_scene(scene, defines)?))
}
