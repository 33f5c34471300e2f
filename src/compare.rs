//! Comparing two 8-bit RGB images (a render against a reference): mean absolute error, the
//! fraction of pixels off by more than a tolerance in any channel, and a heat map of the
//! per-pixel largest channel difference. Used by `embray compare` and by the tests.

use image::RgbImage;
use std::path::{Path, PathBuf};

/// The default per-channel tolerance, in 1/255 steps.
pub const DEFAULT_TOLERANCE: u8 = 3;

#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    #[error("cannot read image '{}': {message}", .path.display())]
    Read { path: PathBuf, message: String },
    #[error("the images differ in size: {a_width}x{a_height} and {b_width}x{b_height}")]
    Size { a_width: u32, a_height: u32, b_width: u32, b_height: u32 },
    #[error("cannot write heat map '{}': {message}", .path.display())]
    Write { path: PathBuf, message: String },
    #[error(
        "no pixel is finite in both images ({a} in the first, {b} in the second have a NaN or \
         infinite value): there is nothing to compare"
    )]
    NothingFinite { a: usize, b: usize },
    #[error(
        "variance image '{}': pixel ({x}, {y}) has {channel} = {value}, but a variance must be \
         a finite number (the test divides by it: an infinite one passes any image, and a NaN \
         is no variance)",
        .path.display()
    )]
    Variance { path: PathBuf, x: u32, y: u32, channel: char, value: f32 },
}

/// How two images differ.
#[derive(Clone, Debug)]
pub struct PngComparison {
    pub width: u32,
    pub height: u32,
    /// Mean of |a − b| over every channel of every pixel, in 1/255 units.
    pub mean_abs_error: f64,
    /// The largest channel difference anywhere, in 1/255 units.
    pub max_abs_error: u8,
    /// The tolerance `fraction_over` uses, in 1/255 units.
    pub tolerance: u8,
    /// Fraction of pixels with some channel off by more than `tolerance`.
    pub fraction_over: f64,
    /// Per pixel, the largest channel difference (row-major).
    pub max_channel_diff: Vec<u8>,
}

impl PngComparison {
    /// Fraction of pixels within the tolerance in every channel.
    pub fn fraction_within(&self) -> f64 {
        1.0 - self.fraction_over
    }

    /// The heat map: black where equal, dark blue up to the tolerance, then red → yellow
    /// with growing difference (full yellow at 64/255 and beyond).
    pub fn heatmap(&self) -> RgbImage {
        let tolerance = self.tolerance;
        RgbImage::from_fn(self.width, self.height, |x, y| {
            let d = self.max_channel_diff[(y * self.width + x) as usize];
            image::Rgb(if d == 0 {
                [0, 0, 0]
            } else if d <= tolerance {
                [0, 0, 60 + (120 * d as u32 / tolerance.max(1) as u32) as u8]
            } else {
                let t = (d as u32).min(64) * 255 / 64;
                [160u32.max(t) as u8, t as u8, 0]
            })
        })
    }
}

/// Reads an image file as 8-bit RGB.
/// Only regular files, size-capped like every input (a FIFO would block forever).
pub fn read_rgb(path: &Path) -> Result<RgbImage, CompareError> {
    let error = |message: String| CompareError::Read { path: path.to_path_buf(), message };
    let bytes = crate::scene::read_input_bytes(path).map_err(|e| error(e.to_string()))?;
    let reader = || crate::image_decode::reader(&bytes).map_err(error);
    // The header's size is checked before the decoder allocates for it: a render's size at
    // most, as any image embray wrote is.
    let (width, height) = reader()?.into_dimensions().map_err(|e| error(e.to_string()))?;
    let most = crate::limits::MAX_RESOLUTION;
    if width > most || height > most {
        return Err(error(format!("{width} × {height} pixels; at most {most} a side")));
    }
    let mut reader = reader()?;
    reader.limits(crate::image_decode::limits(width, height));
    reader.decode().map(|i| i.to_rgb8()).map_err(|e| error(e.to_string()))
}

/// Compares the two image files (`DEFAULT_TOLERANCE`).
pub fn compare_png(a: &Path, b: &Path) -> Result<PngComparison, CompareError> {
    compare_images(&read_rgb(a)?, &read_rgb(b)?, DEFAULT_TOLERANCE)
}

/// Compares two images of the same size.
pub fn compare_images(
    a: &RgbImage,
    b: &RgbImage,
    tolerance: u8,
) -> Result<PngComparison, CompareError> {
    if a.dimensions() != b.dimensions() {
        return Err(CompareError::Size {
            a_width: a.width(),
            a_height: a.height(),
            b_width: b.width(),
            b_height: b.height(),
        });
    }
    let (width, height) = a.dimensions();
    let mut sum = 0u64;
    let mut over = 0u64;
    let mut max_channel_diff = Vec::with_capacity((width * height) as usize);
    for (pa, pb) in a.pixels().zip(b.pixels()) {
        let mut worst = 0u8;
        for c in 0..3 {
            let d = pa[c].abs_diff(pb[c]);
            sum += d as u64;
            worst = worst.max(d);
        }
        over += (worst > tolerance) as u64;
        max_channel_diff.push(worst);
    }
    let pixels = (width as u64 * height as u64).max(1);
    Ok(PngComparison {
        width,
        height,
        mean_abs_error: sum as f64 / (3 * pixels) as f64,
        max_abs_error: max_channel_diff.iter().copied().max().unwrap_or(0),
        tolerance,
        fraction_over: over as f64 / pixels as f64,
        max_channel_diff,
    })
}

/// Writes the comparison's heat map as PNG (through the output module: checked writes, a
/// temporary file renamed into place).
pub fn write_heatmap(comparison: &PngComparison, path: &Path) -> Result<(), CompareError> {
    let image = comparison.heatmap();
    crate::output::write_one(path, |w| {
        crate::output::encode_rgb8(image.as_raw(), image.width(), image.height(), w)
    })
    .map_err(|e| CompareError::Write { path: path.to_path_buf(), message: e.to_string() })
}

/// `image` shrunk by `factor` in each direction, each output pixel the mean of its
/// `factor`×`factor` block (a box filter; the edges are cropped to whole blocks).
pub fn downsample_box(image: &RgbImage, factor: u32) -> RgbImage {
    let factor = factor.max(1);
    let (w, h) = (image.width() / factor, image.height() / factor);
    let n = factor * factor;
    RgbImage::from_fn(w, h, |x, y| {
        let mut sum = [0u32; 3];
        for dy in 0..factor {
            for dx in 0..factor {
                let p = image.get_pixel(x * factor + dx, y * factor + dy);
                for c in 0..3 {
                    sum[c] += p[c] as u32;
                }
            }
        }
        image::Rgb(sum.map(|s| ((s + n / 2) / n) as u8))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_of_a_known_difference() {
        let a = RgbImage::from_pixel(2, 2, image::Rgb([10, 10, 10]));
        let mut b = a.clone();
        b.put_pixel(0, 0, image::Rgb([14, 10, 10])); // 4 off: over the tolerance
        b.put_pixel(1, 0, image::Rgb([10, 7, 10])); // 3 off: within it
        let c = compare_images(&a, &b, 3).unwrap();
        assert_eq!(c.max_abs_error, 4);
        assert!((c.fraction_over - 0.25).abs() < 1e-12);
        assert!((c.mean_abs_error - 7.0 / 12.0).abs() < 1e-12);
        assert_eq!(c.max_channel_diff, [4, 3, 0, 0]);
        let heat = c.heatmap();
        assert_eq!(heat.get_pixel(1, 1).0, [0, 0, 0]);
        assert!(heat.get_pixel(0, 0)[0] > 0 && heat.get_pixel(1, 0)[2] > 0);
    }

    #[test]
    fn different_sizes_are_an_error() {
        let a = RgbImage::new(2, 2);
        let b = RgbImage::new(2, 3);
        assert!(compare_images(&a, &b, 3).unwrap_err().to_string().contains("2x2 and 2x3"));
    }

    #[test]
    fn box_downsampling_averages_blocks() {
        let mut img = RgbImage::new(4, 2);
        img.put_pixel(0, 0, image::Rgb([255, 0, 0]));
        img.put_pixel(1, 1, image::Rgb([255, 0, 0]));
        let small = downsample_box(&img, 2);
        assert_eq!(small.dimensions(), (2, 1));
        assert_eq!(small.get_pixel(0, 0).0, [128, 0, 0]);
        assert_eq!(small.get_pixel(1, 0).0, [0, 0, 0]);
    }
}
