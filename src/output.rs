//! Writing images: EXR (linear float RGB plus depth `Z` and normal `N.X/N.Y/N.Z` channels)
//! and tone-mapped sRGB PNG. Every file is written to a temporary name in the same folder and
//! renamed into place, so a failure never leaves a half-written image behind.

use crate::film::Film;
use glam::Vec3;
use std::path::{Path, PathBuf};

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum ToneMap {
    /// Clamp to [0, 1].
    None,
    /// x / (1 + x) per channel.
    Reinhard,
    /// Narkowicz's fit of the ACES filmic curve.
    #[default]
    Aces,
    /// The CENG795 course's output: radiance is already in 0–255 display units and is
    /// clamped to [0, 255] and truncated to an integer (as the course's reference images
    /// are; rounding makes a quarter of their pixels one step brighter), with no tone curve
    /// and no sRGB encoding.
    #[value(name = "clamp255")]
    Clamp255,
}

#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("cannot write '{path}': {message}")]
    Write { path: PathBuf, message: String },
}

fn write_error(path: &Path, message: impl ToString) -> OutputError {
    OutputError::Write { path: path.to_path_buf(), message: message.to_string() }
}

/// Runs `write` against a temporary path beside `path`, then renames it into place.
fn write_atomically(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<(), OutputError> {
    let file_name =
        path.file_name().ok_or_else(|| write_error(path, "not a file name"))?.to_string_lossy();
    let temp = path.with_file_name(format!(".{file_name}.{}.tmp", std::process::id()));
    if let Err(message) = write(&temp) {
        let _ = std::fs::remove_file(&temp);
        return Err(write_error(path, message));
    }
    std::fs::rename(&temp, path).map_err(|e| {
        let _ = std::fs::remove_file(&temp);
        write_error(path, e)
    })
}

pub fn write_exr(film: &Film, path: &Path) -> Result<(), OutputError> {
    use exr::prelude::*;
    let size = Vec2(film.width as usize, film.height as usize);
    let channel = |name: &str, values: Vec<f32>| AnyChannel::new(name, FlatSamples::F32(values));
    let component = |pick: fn(&glam::Vec3) -> f32, data: &[glam::Vec3]| -> Vec<f32> {
        data.iter().map(pick).collect()
    };
    let channels = SmallVec::from_vec(vec![
        channel("R", component(|c| c.x, &film.color)),
        channel("G", component(|c| c.y, &film.color)),
        channel("B", component(|c| c.z, &film.color)),
        channel("Z", film.depth.clone()),
        channel("N.X", component(|c| c.x, &film.normal)),
        channel("N.Y", component(|c| c.y, &film.normal)),
        channel("N.Z", component(|c| c.z, &film.normal)),
    ]);
    let layer = Layer::new(
        size,
        LayerAttributes::named("embray"),
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(channels),
    );
    let image = Image::from_layer(layer);
    write_atomically(path, |temp| image.write().to_file(temp).map_err(|e| e.to_string()))
}

fn tone_map(c: Vec3, curve: ToneMap) -> Vec3 {
    match curve {
        ToneMap::None | ToneMap::Clamp255 => c,
        ToneMap::Reinhard => c / (Vec3::ONE + c),
        ToneMap::Aces => {
            let (a, b, cc, d, e) = (2.51, 0.03, 2.43, 0.59, 0.14);
            (c * (a * c + b)) / (c * (cc * c + d) + e)
        }
    }
}

fn srgb_encode(linear: f32) -> f32 {
    if linear <= 0.003_130_8 { 12.92 * linear } else { 1.055 * linear.powf(1.0 / 2.4) - 0.055 }
}

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
    fn srgb_encoding_hits_known_points() {
        assert_eq!(srgb_encode(0.0), 0.0);
        assert!((srgb_encode(1.0) - 1.0).abs() < 1e-6);
        assert!((srgb_encode(0.18) - 0.4614).abs() < 1e-3);
    }

    #[test]
    fn clamp255_writes_values_clamped_and_truncated() {
        let mut film = Film::new(3, 1);
        film.color = vec![Vec3::new(0.0, 12.4, 12.99), Vec3::new(254.9, 300.0, -5.0), Vec3::NAN];
        assert_eq!(to_srgb8(&film, ToneMap::Clamp255, 0.0), [0, 12, 12, 254, 255, 0, 0, 0, 0]);
    }

    #[test]
    fn failed_write_leaves_no_file() {
        let dir = std::env::temp_dir().join(format!("embray-out-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let target = dir.join("missing-folder").join("x.png");
        let film = Film::new(2, 2);
        assert!(write_png(&film, &target, ToneMap::Aces, 0.0).is_err());
        assert!(!target.exists());
        let ok = dir.join("ok.exr");
        write_exr(&film, &ok).unwrap();
        assert!(ok.exists());
        let leftovers: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .collect();
        assert!(leftovers.is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
