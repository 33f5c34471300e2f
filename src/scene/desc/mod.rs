//! `SceneDesc`: a validated scene in world space with f64 transforms, independent of the file
//! format it came from.

mod camera;
mod light;
mod material;
mod mesh_attribute;
mod principled;
mod scene;
mod sdf_grid;
mod settings;
mod shape;
mod texture;

pub use camera::*;
pub use light::*;
pub use material::*;
pub use mesh_attribute::*;
pub use principled::*;
pub use scene::*;
pub use sdf_grid::*;
pub use settings::*;
pub use shape::*;
pub use texture::*;
