//! Distribution effects, materials, instancing and shading space, on every compiled backend.
//! Scenes are built in code so the checks do not depend on the file format.

#[path = "../common/mod.rs"]
mod common;

mod camera_effects;
mod forcing;
mod instancing;
mod light_and_energy;
mod textures;

use common::build::*;
use common::*;
use embray::accel::{AccelOptions, BackendKind, build as build_accel};
use embray::choice::Choice;
use embray::compile::EffectsMode;
use embray::film::Film;
use embray::ray::Ray;
use embray::render::{RenderOptions, prepare_scene, render};
use embray::scene::{Directional, Point};
use embray::scene::{MaterialDesc, Pattern, SceneDesc, ShapeDesc, Specular, TextureDesc};
use embray::stats::TraversalCounters;
use glam::{DAffine3, DVec3, Vec3};

pub(crate) fn luminance_sum(film: &Film) -> f64 {
    film.color.iter().map(|c| c.element_sum() as f64).sum()
}

pub(crate) fn direct_only(scene: &SceneDesc, backend: BackendKind, spp: u32) -> RenderOptions {
    let mut o = options(scene, backend, spp);
    o.max_depth = 1;
    o
}
