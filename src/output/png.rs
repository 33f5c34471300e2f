//! The display PNG: exposure, a tone curve and sRGB encoding, 8 bits per channel.

use super::format::{ImageFormat, encode_display_rgb8};
use super::photographic::Photographic;
use super::tonemap::{ToneMap, srgb_encode, tone_map};
use super::{OutputError, WriteSeek, write_one};
use crate::film::Film;
use glam::Vec3;
use std::path::Path;

/// The largest exposure adjustment, in stops either way: 2^128 is past f32's range, where a
/// black pixel times the infinite scale becomes NaN (and white); 2^64 brightens 1e-19 to 1.
pub const MAX_EXPOSURE_STOPS: f32 = 64.0;

/// Whether `exposure` (stops) is one `to_srgb8` takes: finite, within `MAX_EXPOSURE_STOPS`.
pub fn exposure_in_range(exposure: f32) -> bool {
    exposure.abs() <= MAX_EXPOSURE_STOPS
}

/// 8-bit sRGB pixels of `film` after exposure (in stops) and tone mapping. NaN becomes 0.
/// With `ToneMap::Clamp255` the pixels are the values themselves, clamped to [0, 255] and
/// truncated (no sRGB encoding). With `ToneMap::Photographic`, `photographic` maps the
/// whole image (with its own gamma, no sRGB encoding).
pub fn to_srgb8(
    film: &Film,
    curve: ToneMap,
    exposure: f32,
    photographic: &Photographic,
) -> Vec<u8> {
    let scale = 2.0f32.powf(exposure);
    if curve == ToneMap::Photographic {
        let exposed: Vec<Vec3> = film.color.iter().map(|&c| c * scale).collect();
        return photographic.to_rgb8(&exposed);
    }
    if curve == ToneMap::Clamp255 {
        return film
            .color
            .iter()
            .flat_map(|&c| {
                (c * scale).to_array().map(|v| {
                    // NaN becomes 0 (`as` saturates).
                    v.clamp(0.0, 255.0) as u8
                })
            })
            .collect();
    }
    film.color
        .iter()
        .flat_map(|&c| {
            let mapped = tone_map(c.max(Vec3::ZERO) * scale, curve);
            mapped.to_array().map(|v| {
                let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
                (srgb_encode(v) * 255.0 + 0.5) as u8
            })
        })
        .collect()
}

/// Writes `film` as PNG to `path` on its own (see `OutputSet` for a run's several outputs).
pub fn write_png(
    film: &Film,
    path: &Path,
    curve: ToneMap,
    exposure: f32,
    photographic: &Photographic,
) -> Result<(), OutputError> {
    write_one(path, |w| encode_png(film, curve, exposure, photographic, w))
}

/// Encodes `film` as an 8-bit sRGB PNG into `sink`; every write error is returned.
pub fn encode_png(
    film: &Film,
    curve: ToneMap,
    exposure: f32,
    photographic: &Photographic,
    sink: &mut dyn WriteSeek,
) -> std::io::Result<()> {
    encode_png_graded(film, curve, exposure, photographic, None, sink)
}

/// As [`encode_png`], with `lut` (if any) grading the display pixels last.
pub fn encode_png_graded(
    film: &Film,
    curve: ToneMap,
    exposure: f32,
    photographic: &Photographic,
    lut: Option<&super::Lut3d>,
    sink: &mut dyn WriteSeek,
) -> std::io::Result<()> {
    let look = DisplayLook { curve, exposure, photographic, lut };
    encode_display(film, &look, ImageFormat::Png, sink)
}

/// How a film becomes display pixels.
pub struct DisplayLook<'a> {
    pub curve: ToneMap,
    /// In stops.
    pub exposure: f32,
    pub photographic: &'a Photographic,
    /// Grades the display pixels last.
    pub lut: Option<&'a super::Lut3d>,
}

/// Encodes `film` as a display image (PNG or JPEG) with `look`.
pub fn encode_display(
    film: &Film,
    look: &DisplayLook,
    format: ImageFormat,
    sink: &mut dyn WriteSeek,
) -> std::io::Result<()> {
    let mut pixels = to_srgb8(film, look.curve, look.exposure, look.photographic);
    if let Some(lut) = look.lut {
        lut.apply_rgb8(&mut pixels);
    }
    encode_display_rgb8(&pixels, film.width, film.height, format, sink)
}

/// Encodes 8-bit RGB pixels as PNG into `sink`.
pub fn encode_rgb8(
    pixels: &[u8],
    width: u32,
    height: u32,
    sink: &mut dyn WriteSeek,
) -> std::io::Result<()> {
    encode_display_rgb8(pixels, width, height, ImageFormat::Png, sink)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamp255_writes_values_clamped_and_truncated() {
        let mut film = Film::new(3, 1);
        film.color = vec![Vec3::new(0.0, 12.4, 12.99), Vec3::new(254.9, 300.0, -5.0), Vec3::NAN];
        let pixels = to_srgb8(&film, ToneMap::Clamp255, 0.0, &Default::default());
        assert_eq!(pixels, [0, 12, 12, 254, 255, 0, 0, 0, 0]);
    }
}
