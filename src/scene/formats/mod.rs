//! Scene file formats. Each reader only translates its syntax into the format-neutral model
//! (`scene::desc`), with the file and line of every error; `toml::write` writes the model
//! back as TOML (with OBJ meshes) for `embray convert`.

pub mod ceng795;
mod line_index;
pub mod mitsuba;
pub(crate) mod obj;
pub(crate) mod ply;
pub(crate) mod serialized;
pub mod toml;
pub mod vol;
pub mod xml;
