//! `[materials.NAME]` → `MaterialDesc`: a Lambertian part (`albedo` or a `texture`), one
//! specular lobe chosen by `type`, emission, and the course's Phong terms. Each type takes
//! only its own fields.

mod course;
mod material;
mod principled;
mod textures;

pub use material::*;
pub(crate) use textures::*;
