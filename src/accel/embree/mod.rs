//! Embree backend. Layers, bottom up: `ffi` (bindings), `compat` (Embree 3 vs 4),
//! `callback_data`/`device`/`geometry`/`scene` (safe RAII wrappers), `ray`/`rayn` (ray
//! struct conversions), `sphere` (user geometry), `backend` (the `Accel` impl).
//!
//! This is the only module of the crate allowed `unsafe`; every block says why it is sound.
#![allow(unsafe_code)]
#![warn(clippy::undocumented_unsafe_blocks)]

mod backend;
mod callback_data;
mod compat;
mod device;
mod ffi;
mod geometry;
mod ray;
mod rayn;
mod scene;
mod sphere;
#[cfg(test)]
mod tests;

pub use backend::EmbreeAccel;
