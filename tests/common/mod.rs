//! Helpers shared by the integration tests: tiny scenes, renders and image comparison.
#![allow(dead_code)]

use embray::accel::BackendKind;
use embray::film::Film;
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

/// Image difference statistics of `test` against `reference`.
#[derive(Debug, Clone, Copy)]
pub struct ImageError {
    /// Σ(a−b)² / Σ b² over all channels.
    pub relative_mse: f64,
    pub max_abs: f64,
    /// Fraction of pixels with any channel off by more than 1 % of the reference's mean.
    pub fraction_off: f64,
    pub non_finite: usize,
}

pub fn image_error(test: &Film, reference: &Film) -> ImageError {
    assert_eq!((test.width, test.height), (reference.width, reference.height));
    let mean = reference.color.iter().map(|c| c.element_sum() as f64).sum::<f64>()
        / (3.0 * reference.color.len() as f64);
    let (mut err2, mut ref2, mut max_abs, mut off, mut non_finite) = (0.0, 0.0, 0.0f64, 0, 0);
    for (a, b) in test.color.iter().zip(&reference.color) {
        if !a.is_finite() {
            non_finite += 1;
            continue;
        }
        let d = (*a - *b).as_dvec3();
        err2 += d.length_squared();
        ref2 += b.as_dvec3().length_squared();
        max_abs = max_abs.max(d.abs().max_element());
        if d.abs().max_element() > 0.01 * mean {
            off += 1;
        }
    }
    ImageError {
        relative_mse: err2 / ref2.max(1e-300),
        max_abs,
        fraction_off: off as f64 / test.color.len() as f64,
        non_finite,
    }
}
