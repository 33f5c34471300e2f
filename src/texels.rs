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
    /// Texels of `width` × `height` as they are (not sRGB-decoded, not HDR, rows top first).
    pub fn plain(file: PathBuf, width: u32, height: u32, texels: Vec<Vec3>) -> Self {
        let (srgb_decoded, hdr, rows_flipped) = (false, false, false);
        TextureImage { file, width, height, texels, srgb_decoded, hdr, rows_flipped }
    }

    /// Texel (i, j), the indices wrapped around the image.
    pub fn wrapped_texel(&self, i: i64, j: i64) -> Vec3 {
        let i = i.rem_euclid(self.width as i64) as usize;
        let j = j.rem_euclid(self.height as i64) as usize;
        self.texels[j * self.width as usize + i]
    }

    /// Bilinear between texel centres (texel i at u·width = i + ½), repeating across the
    /// edges: Mitsuba's bitmap lookup (and OpenGL's); v = 0 is the top row.
    pub fn centred_bilinear(&self, uv: Vec2) -> Vec3 {
        let Some(([f00, f10, f01, f11], dx, dy)) = self.centred_cell(uv) else {
            return Vec3::ZERO;
        };
        f00 * (1.0 - dx) * (1.0 - dy)
            + f10 * dx * (1.0 - dy)
            + f01 * (1.0 - dx) * dy
            + f11 * dx * dy
    }

    /// The derivatives of `centred_bilinear` along u and along v at `uv`: exact within the
    /// cell between four texel centres that holds it (Mitsuba's `eval_1_grad`).
    pub fn centred_bilinear_slopes(&self, uv: Vec2) -> [Vec3; 2] {
        let Some(([f00, f10, f01, f11], dx, dy)) = self.centred_cell(uv) else {
            return [Vec3::ZERO; 2];
        };
        let along_x = (f10 - f00) * (1.0 - dy) + (f11 - f01) * dy;
        let along_y = (f01 - f00) * (1.0 - dx) + (f11 - f10) * dx;
        [along_x * self.width as f32, along_y * self.height as f32]
    }

    /// The four texels around `uv` (wrapped), top-left first, and its place between them.
    fn centred_cell(&self, uv: Vec2) -> Option<([Vec3; 4], f32, f32)> {
        let wrapped = uv - uv.floor();
        if !wrapped.is_finite() {
            return None;
        }
        let x = wrapped.x * self.width as f32 - 0.5;
        let y = wrapped.y * self.height as f32 - 0.5;
        let (p, q) = (x.floor(), y.floor());
        let (dx, dy) = (x - p, y - q);
        let (p, q) = (p as i64, q as i64);
        let texels = [
            self.wrapped_texel(p, q),
            self.wrapped_texel(p + 1, q),
            self.wrapped_texel(p, q + 1),
            self.wrapped_texel(p + 1, q + 1),
        ];
        Some((texels, dx, dy))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The slopes are the bilinear function's own: central differences taken inside one
    /// cell, and across the wrap of the image's edges.
    #[test]
    fn centred_bilinear_slopes_are_the_derivatives_within_a_cell() {
        let (width, height) = (5u32, 3u32);
        let texels = (0..width * height)
            .map(|k| Vec3::new((k * 7 % 11) as f32, (k * 5 % 13) as f32, k as f32))
            .collect();
        let image = TextureImage::plain("ramp".into(), width, height, texels);
        let h = 1e-3;
        for uv in [Vec2::new(0.37, 0.61), Vec2::new(0.05, 0.9), Vec2::new(0.99, 0.02)] {
            let [along_u, along_v] = image.centred_bilinear_slopes(uv);
            let du = (image.centred_bilinear(uv + Vec2::new(h, 0.0))
                - image.centred_bilinear(uv - Vec2::new(h, 0.0)))
                / (2.0 * h);
            let dv = (image.centred_bilinear(uv + Vec2::new(0.0, h))
                - image.centred_bilinear(uv - Vec2::new(0.0, h)))
                / (2.0 * h);
            assert!((along_u - du).abs().max_element() < 1e-2, "{uv}: {along_u} vs {du}");
            assert!((along_v - dv).abs().max_element() < 1e-2, "{uv}: {along_v} vs {dv}");
            assert!(along_u.abs().max_element() > 1.0, "a slope worth checking");
        }
    }
}
