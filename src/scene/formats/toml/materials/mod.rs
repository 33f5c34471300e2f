//! `[materials.NAME]` → `MaterialDesc`: a Lambertian part (`albedo` or a `texture`), one
//! specular lobe chosen by `type`, emission, and the course's Phong terms. Each type takes
//! only its own fields.

mod blend;
mod course;
mod material;
mod principled;
mod specular;
mod textures;

pub(super) use blend::resolve_blends;
pub use material::*;
pub(crate) use textures::*;
