//! What happens at a surface: materials and textures, microfacet distributions and
//! coatings, BSDFs, the surface interaction at a hit, and how rays leave it.

mod beckmann;
pub mod bsdf;
pub mod coating;
pub mod course_brdf;
pub mod course_lobe;
pub mod fresnel;
mod ggx;
pub mod material;
pub mod microfacet;
pub mod normal_map;
pub mod principled;
pub mod spawn;
pub mod surface;
pub mod tex_coords;
pub mod texture;
