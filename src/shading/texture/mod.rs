//! Textures as the integrators evaluate them: a scene `Pattern` with the f32 transform from
//! the attached object's space to the pattern's space.

mod image;
pub mod perlin;

use crate::scene::{NoiseConversion, Pattern, TextureMode};
use glam::{Affine3A, Vec2, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    pub pattern: Pattern,
    pub mode: TextureMode,
    /// From the attached object's space to the pattern's space.
    pub texture_from_object: Affine3A,
}

impl Texture {
    pub fn from_desc(desc: &crate::scene::TextureDesc) -> Self {
        Texture {
            pattern: desc.pattern.clone(),
            mode: desc.mode,
            texture_from_object: Affine3A::from_mat4(
                glam::DMat4::from(desc.texture_from_object).as_mat4(),
            ),
        }
    }

    /// The colour at object-space point `p_object` with texture coordinates `uv`.
    pub fn eval(&self, p_object: Vec3, uv: Vec2) -> Vec3 {
        let parity = |cells: &[f32]| cells.iter().map(|c| c.floor() as i64).sum::<i64>() & 1;
        let p = || self.texture_from_object.transform_point3(p_object);
        match &self.pattern {
            Pattern::Checker2d { scale, even, odd } => {
                if parity(&[uv.x * scale, uv.y * scale]) == 0 { *even } else { *odd }
            }
            Pattern::Checker3d { scale, even, odd } => {
                let p = p() * *scale;
                if parity(&[p.x, p.y, p.z]) == 0 { *even } else { *odd }
            }
            Pattern::CourseChecker { scale, offset, black, white } => {
                let odd = |c: f32| ((c + offset) * scale) as i64 % 2 != 0;
                let p = p();
                if (odd(p.x) != odd(p.y)) != odd(p.z) { *black } else { *white }
            }
            Pattern::Perlin { scale, conversion } => {
                let n = perlin::noise(p() * *scale);
                Vec3::splat(match conversion {
                    NoiseConversion::Absolute => n.abs(),
                    NoiseConversion::Linear => (n + 1.0) * 0.5,
                })
            }
            Pattern::Image { image, interpolation, normalizer } => {
                image::lookup(image, *interpolation, uv) / *normalizer
            }
        }
    }

    /// The step in texture coordinates over which a height field's slope is taken: one
    /// texel of an image, else a small fraction of the unit square.
    pub fn uv_step(&self) -> Vec2 {
        match &self.pattern {
            Pattern::Image { image, .. } => {
                Vec2::new(1.0 / image.width as f32, 1.0 / image.height as f32)
            }
            _ => Vec2::splat(1e-3),
        }
    }

    pub fn needs_object_point(&self) -> bool {
        matches!(
            self.pattern,
            Pattern::Checker3d { .. } | Pattern::CourseChecker { .. } | Pattern::Perlin { .. }
        )
    }

    /// The diffuse reflectance at a point whose material's own is `albedo`, with this
    /// texture's colour `color` there.
    pub fn apply_to_albedo(&self, albedo: Vec3, color: Vec3) -> Vec3 {
        match self.mode {
            TextureMode::Replace | TextureMode::ReplaceAll => color,
            TextureMode::Blend => (albedo + color) * 0.5,
        }
    }
}
