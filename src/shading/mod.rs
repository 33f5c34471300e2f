//! What happens at a surface: materials and textures, BSDFs, the
//! surface interaction at a hit, and how rays leave it.

pub mod bsdf;
pub mod course_brdf;
pub mod course_lobe;
pub mod fresnel;
pub mod material;
pub mod normal_map;
pub mod spawn;
pub mod surface;
pub mod texture;
