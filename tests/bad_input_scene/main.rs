//! The scene loader on bad (and good) input: every error names the file, the field or line,
//! and the offending value; nothing panics. CLI-level tests live elsewhere.

use embray::scene::{self, LightDesc, ShapeDesc};
use glam::{DVec3, Vec3};
use std::path::Path;

#[path = "../common/mod.rs"]
mod common;

use common::assert_contains;
use common::scene_files::{CAMERA, WHITE, data_dir, load, mesh_of, scene_with, source};

fn load_err(text: &str) -> String {
    match scene::load_str(text, &source()) {
        Ok(_) => panic!("scene should be rejected:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// A unit box of the white material, for transforms to act on.
const BOX: &str =
    "[[objects]]\ntype = \"box\"\nmaterial = \"white\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n";

mod lights;
mod loads;
mod materials;
mod meshes;
mod principled;
mod ranges;
mod syntax;
mod transforms;
