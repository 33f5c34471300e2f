//! The display PNG: exposure, a tone curve and sRGB encoding, 8 bits per channel.

use super::tonemap::{ToneMap, srgb_encode, tone_map};
use super::{OutputError, write_atomically, write_error};
use crate::film::Film;
use glam::Vec3;
use std::path::Path;

/// 8-bit sRGB pixels of `film` after exposure (in stops) and tone mapping. NaN becomes 0.
/// With `ToneMap::Clamp255` the pixels are the values themselves, clamped to [0, 255] and
/// truncated (no sRGB encoding).
pub fn to_srgb8(film: &Film, curve: ToneMap, exposure: f32) -> Vec<u8> {
    let scale = 2.0f32.powf(exposure);
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

pub fn write_png(
    film: &Film,
    path: &Path,
    curve: ToneMap,
    exposure: f32,
) -> Result<(), OutputError> {
    let pixels = to_srgb8(film, curve, exposure);
    let image = image::RgbImage::from_raw(film.width, film.height, pixels)
        .ok_or_else(|| write_error(path, "image buffer has the wrong size"))?;
    write_atomically(path, |temp| {
        image.save_with_format(temp, image::ImageFormat::Png).map_err(|e| e.to_string())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamp255_writes_values_clamped_and_truncated() {
        let mut film = Film::new(3, 1);
        film.color = vec![Vec3::new(0.0, 12.4, 12.99), Vec3::new(254.9, 300.0, -5.0), Vec3::NAN];
        assert_eq!(to_srgb8(&film, ToneMap::Clamp255, 0.0), [0, 12, 12, 254, 255, 0, 0, 0, 0]);
    }
}
