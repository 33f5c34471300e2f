//! The scene format's newer parts, parsed into the right `SceneDesc` values: lens and
//! render settings, material types, textures, motion, repeat grids, shared meshes, smooth
//! normals, PLY files, the new light types, and the bundled scenes that use them. (Errors
//! are tested in `bad_input_scene`.)

use embray::scene::{
    self, IntegratorKind, LensShape, LightDesc, MaterialDesc, MeshData, Pattern, PhongDesc,
    SceneDesc, ShapeDesc, Specular,
};
use glam::{DAffine3, DVec3, Vec2, Vec3};
use std::path::Path;
use std::sync::Arc;

#[path = "../common/mod.rs"]
mod common;

use common::scene_files::{CAMERA, data_dir, load, mesh_of, scene_with, source};

fn material<'a>(scene: &'a SceneDesc, name: &str) -> &'a MaterialDesc {
    scene.materials.iter().find(|m| m.name == name).unwrap_or_else(|| panic!("no {name}"))
}

#[track_caller]
fn assert_close(a: DVec3, b: DVec3) {
    assert!((a - b).length() < 1e-12, "{a} != {b}");
}

fn ply_scene(file: &str, smooth: Option<bool>) -> String {
    let smooth = smooth.map_or(String::new(), |s| format!("smooth = {s}\n"));
    format!("[[objects]]\ntype = \"mesh\"\nmaterial = \"white\"\nfile = \"{file}\"\n{smooth}")
}

mod lights_and_bundled;
mod motion_and_meshes;
mod mtl;
mod ply;
mod principled;
mod settings_and_materials;
