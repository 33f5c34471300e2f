//! embray: a ray tracer whose intersection work is done by Intel Embree (through FFI) or by
//! the pure-Rust obvhs BVH, rendering in camera-relative, translation-only space.
//!
//! Data flow: `scene::load` → `SceneDesc` (world space, f64) → `compile` (with
//! `render_space`) → `RenderScene` (render space, f32) → `accel` backend → `integrator` →
//! `render` → `film` → `output`. The library knows nothing of the command line.
#![deny(unsafe_code)]
// `!(x > 0.0)` is used on purpose: unlike `x <= 0.0` it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod accel;
pub mod bench;
pub mod bundled;
pub mod camera;
pub mod choice;
pub mod color;
pub mod compare;
pub mod compare_linear;
pub mod compile;
pub mod denoise;
pub mod distributed;
pub mod erf;
pub mod excerpt;
pub mod exr_rgb;
pub mod film;
pub mod float_error;
pub mod fuzz;
pub mod image_decode;
pub mod image_error;
pub mod info;
pub mod input_file;
pub mod integrator;
pub mod intersect;
pub mod intersect_sdf;
pub mod lane_select;
pub mod light;
pub mod limits;
pub mod mitsuba_rule;
pub mod output;
pub mod params;
pub mod phase_times;
pub mod ray;
pub mod ray_columns;
pub mod render;
pub mod render_options;
pub mod render_passes;
pub mod render_scene;
pub mod render_space;
pub mod render_stop;
mod render_tile;
pub mod rgbe;
pub mod sample_sums;
pub mod sampling;
pub mod scene;
pub mod sdf_grid;
pub mod shading;
pub mod splitmix;
pub mod stats;
pub mod texels;
pub mod transform;
pub mod unlit_emitters;
