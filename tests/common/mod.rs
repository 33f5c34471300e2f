//! Helpers shared by the integration tests: tiny scenes, renders and image comparison.
#![allow(dead_code)]

use embray::accel::BackendKind;
#[allow(unused_imports)]
pub use embray::image_error::image_error;
use embray::render::{RenderOptions, RenderOutput, render};
use embray::scene::{SceneDesc, load, load_str};
use std::path::{Path, PathBuf};

pub fn repo_path(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(relative)
}

/// The bundled default scene, at a test-sized resolution.
pub fn cornell(width: u32, height: u32) -> SceneDesc {
    let mut scene = load(&repo_path("scenes/cornell.toml")).expect("default scene loads");
    scene.camera.width = width;
    scene.camera.height = height;
    scene
}

pub fn scene_from_str(text: &str) -> SceneDesc {
    load_str(text, &repo_path("tests/inline.toml")).expect("test scene loads")
}

/// Options for a small deterministic test render.
pub fn options(scene: &SceneDesc, backend: BackendKind, spp: u32) -> RenderOptions {
    let mut o = RenderOptions::for_scene(scene);
    o.spp = spp;
    o.seed = 7;
    o.backend = backend;
    o
}

pub fn render_ok(scene: &SceneDesc, options: &RenderOptions) -> RenderOutput {
    render(scene, options).expect("render succeeds")
}

/// Backends compiled into this build.
pub fn backends() -> Vec<BackendKind> {
    let mut all = Vec::new();
    if cfg!(feature = "embree") {
        all.push(BackendKind::Embree);
    }
    if cfg!(feature = "obvhs") {
        all.push(BackendKind::Obvhs);
    }
    all
}
