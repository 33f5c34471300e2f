//! The scene file as written: serde structs for the TOML format. Every struct denies unknown
//! keys. Objects and lights are flat structs (one optional field per key any type uses)
//! rather than internally tagged enums, because serde buffers tagged enums and toml then
//! loses the line of the offending key; `convert` checks which fields each type takes.

mod file;
mod lights;
mod materials;
mod objects;
mod principled;
mod textures;
mod transforms;
mod values;

pub(crate) use file::*;
pub(crate) use lights::*;
pub(crate) use materials::*;
pub(crate) use objects::*;
pub(crate) use principled::*;
pub(crate) use textures::*;
pub(crate) use transforms::*;
pub(crate) use values::*;
