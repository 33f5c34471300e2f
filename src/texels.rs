//! An image's texels, decoded: what textures and environment lights look up.

use glam::{Vec2, Vec3};
use std::path::PathBuf;

/// Decoded texels, row-major from the top-left: 0–255 for integer files whatever their bit
/// depth (a 16-bit file's values divided by 257, so that a normalizer means the same for
/// both), linear values for float ones, or linear [0, 1] where the loader was asked to
/// decode sRGB. `file` is kept for messages and for writing the scene back out.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureImage {
    pub file: PathBuf,
    pub width: u32,
    pub height: u32,
    pub texels: Vec<Vec3>,
    /// True if the texels were decoded from sRGB to linear [0, 1].
    pub srgb_decoded: bool,
    /// True if the texels are an EXR file's linear values (high dynamic range).
    pub hdr: bool,
    /// True if the file's rows are stored bottom row first, so that v runs up the image as
    /// OBJ/MTL texture coordinates do (`flip_v`), where embray's run down.
    pub rows_flipped: bool,
}

impl TextureImage {
    /// Texel (i, j), the indices wrapped around the image.
    pub fn wrapped_texel(&self, i: i64, j: i64) -> Vec3 {
        let i = i.rem_euclid(self.width as i64) as usize;
        let j = j.rem_euclid(self.height as i64) as usize;
        self.texels[j * self.width as usize + i]
    }

    /// Bilinear between texel centres (texel i at u·width = i + ½), repeating across the
    /// edges: Mitsuba's bitmap lookup (and OpenGL's); v = 0 is the top row.
    pub fn centred_bilinear(&self, uv: Vec2) -> Vec3 {
        let wrapped = uv - uv.floor();
        if !wrapped.is_finite() {
            return Vec3::ZERO;
        }
        let x = wrapped.x * self.width as f32 - 0.5;
        let y = wrapped.y * self.height as f32 - 0.5;
        let (p, q) = (x.floor(), y.floor());
        let (dx, dy) = (x - p, y - q);
        let (p, q) = (p as i64, q as i64);
        self.wrapped_texel(p, q) * (1.0 - dx) * (1.0 - dy)
            + self.wrapped_texel(p + 1, q) * dx * (1.0 - dy)
            + self.wrapped_texel(p, q + 1) * (1.0 - dx) * dy
            + self.wrapped_texel(p + 1, q + 1) * dx * dy
    }
}
