//! Texture coordinates of a surface point, and a sphere's.

use glam::{Vec2, Vec3};

/// A hit's texture coordinates, worked out when asked for: a sphere's take an arc tangent
/// and an arc cosine (a twentieth of a rough conductor's bounce), which a material without
/// textures never needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TexCoords {
    Known(Vec2),
    /// On a sphere, with this unit normal in the sphere's own frame (`sphere_uv`).
    OnSphere(Vec3),
}

impl TexCoords {
    #[inline]
    pub fn get(self) -> Vec2 {
        match self {
            TexCoords::Known(uv) => uv,
            TexCoords::OnSphere(n) => sphere_uv(n),
        }
    }
}

/// Texture coordinates of the point with unit normal `n` (in the sphere's own frame) on a
/// sphere: u grows eastwards seen from outside (so that images are not mirrored), v from
/// the +Y pole (the image's top row) down. The course's sphere mapping.
pub(crate) fn sphere_uv(n: Vec3) -> Vec2 {
    Vec2::new(
        0.5 - n.z.atan2(n.x) / std::f32::consts::TAU,
        n.y.clamp(-1.0, 1.0).acos() / std::f32::consts::PI,
    )
}
