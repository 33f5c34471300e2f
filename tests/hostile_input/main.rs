//! The `embray` binary under hostile but realistic input (issue 13): malformed and
//! out-of-range scenes and meshes, colliding output paths, devices, FIFOs and special files,
//! a full disk (a file-size limit), signals during a write, closed pipes. Every case checks
//! the exit code, the message (file, line, field where known), that nothing panicked, and
//! that no file that existed before the run changed and no temporary file was left behind.
//!
//! Images are 8×8 at 1 spp, so the whole binary runs in seconds.

mod ceng795;
mod collisions;
#[path = "../common/mod.rs"]
mod common;
mod fifth_probe;
mod fourth_probe;
mod harness;
mod inflating;
mod limits;
mod memory_before_spending;
mod meshes;
mod mitsuba_conflicts;
mod nesting;
mod numbers;
mod outputs;
mod process;
mod scenes;
mod sdfgrid;
mod seventh_probe;
mod sixth_probe;
mod texture_values;
mod tools_and_environment;
mod unread;
mod wrong_images;
