//! embray: a ray tracer whose intersection work is done by Intel Embree (through FFI) or by
//! the pure-Rust obvhs BVH, rendering in camera-relative, translation-only space.
//!
//! Data flow: `scene::load` → `SceneDesc` (world space, f64) → `render_space` →
//! `RenderScene` (render space, f32) → `accel` backend → `integrator` → `film` → `output`.
#![deny(unsafe_code)]
// `!(x > 0.0)` is used on purpose: unlike `x <= 0.0` it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod accel;
pub mod bench;
pub mod bsdf;
pub mod camera;
pub mod compare;
pub mod effects;
pub mod film;
pub mod geometry;
pub mod image_error;
pub mod integrator;
pub mod light;
pub mod material;
pub mod output;
pub mod render;
pub mod render_scene;
pub mod render_space;
pub mod sampling;
pub mod scene;
pub mod spawn;
pub mod stats;
pub mod surface;
#[cfg(test)]
mod test_rng;
pub mod transform;
pub mod whitted;
