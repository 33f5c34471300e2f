//! The scene loader on bad (and good) input: every error names the file, the field or line,
//! and the offending value; nothing panics. CLI-level tests live elsewhere.

use embray::scene::{self, LightDesc, SceneDesc, ShapeDesc};
use glam::{DVec3, Vec3};
use std::path::Path;

#[path = "../common/mod.rs"]
mod common;

use common::scene_files::{CAMERA, data_dir, source};

const WHITE: &str = "\
[materials.white]
albedo = [0.73, 0.73, 0.73]
";

fn load(text: &str) -> SceneDesc {
    match scene::load_str(text, &source()) {
        Ok(scene) => scene,
        Err(e) => panic!("scene should load, got: {e}"),
    }
}

fn load_err(text: &str) -> String {
    match scene::load_str(text, &source()) {
        Ok(_) => panic!("scene should be rejected:\n{text}"),
        Err(e) => e.to_string(),
    }
}

#[track_caller]
fn assert_contains(message: &str, parts: &[&str]) {
    for part in parts {
        assert!(message.contains(part), "expected {part:?} in the message:\n{message}");
    }
}

/// A unit box of the white material, for transforms to act on.
const BOX: &str =
    "[[objects]]\ntype = \"box\"\nmaterial = \"white\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n";

/// `CAMERA`, the white material and `rest`.
fn scene_with(rest: &str) -> String {
    format!("{CAMERA}{WHITE}{rest}")
}

fn mesh_of(scene: &SceneDesc, object: usize) -> &embray::scene::MeshData {
    match &scene.objects[object].shape {
        ShapeDesc::Mesh(mesh) => mesh,
        other => panic!("object {object} is not a mesh: {other:?}"),
    }
}

mod lights;
mod loads;
mod materials;
mod meshes;
mod ranges;
mod syntax;
mod transforms;
