//! Embree backend. Layers, bottom up: `ffi` (bindings), `compat` (Embree 3 vs 4),
//! `callback_data`/`device`/`geometry`/`scene` (safe RAII wrappers), `ray`/`rayn` (ray
//! struct conversions), `sphere` and `user_triangles` (user geometry; the latter only in
//! counting mode), `backend` (the `Accel` impl: baked geometry in the top scene, one shared
//! child scene per instanced prototype, static and moving instances of it).
//!
//! This is the only module of the crate allowed `unsafe`; every block says why it is sound.
#![allow(unsafe_code)]
#![warn(clippy::undocumented_unsafe_blocks)]

mod backend;
mod batch;
#[cfg(test)]
mod batch_tests;
mod callback_data;
mod compat;
#[cfg(test)]
mod counting_tests;
mod device;
mod ffi;
mod geometry_handle;
mod instance;
#[cfg(test)]
mod instance_tests;
#[cfg(test)]
mod large_coordinate_tests;
mod library;
mod ray;
mod rayn;
mod scene;
mod sdf_grid;
mod sphere;
#[cfg(test)]
mod test_scenes;
#[cfg(test)]
mod tests;
mod user_triangles;

pub use backend::EmbreeAccel;
pub use batch::BatchKind;
pub use library::library;
