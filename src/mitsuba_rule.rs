//! Mitsuba 3's pass rule for its render regression suite (`test_renders.py`): an image
//! rendered with `spp` samples per pixel passes against a reference (the mean of many
//! samples) and its per-sample variance when at least 99.75 % of the pixel channels, in CIE
//! XYZ, pass a two-sided Z-test at the Šidák-corrected 1 % level.

use glam::{Mat3, Vec3};

/// Linear sRGB → CIE XYZ (D65).
const XYZ_FROM_SRGB: Mat3 = Mat3::from_cols_array(&[
    0.412453, 0.212671, 0.019334, 0.357580, 0.715160, 0.119193, 0.180423, 0.072169, 0.950227,
]);

/// The fraction of pixel channels that must pass.
pub const PASS_FRACTION: f64 = 0.9975;

/// How an image fared against a reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Verdict {
    /// Pixel channels whose p-value is above the corrected level.
    pub passing: usize,
    pub channels: usize,
}

impl Verdict {
    pub fn fraction(&self) -> f64 {
        self.passing as f64 / self.channels.max(1) as f64
    }

    pub fn passes(&self) -> bool {
        self.fraction() >= PASS_FRACTION
    }
}

/// The Z-test of `image` (rendered with `spp` samples per pixel) against `reference` and
/// `variance`, all linear sRGB of the same size.
pub fn judge(image: &[Vec3], reference: &[Vec3], variance: &[Vec3], spp: u32) -> Verdict {
    assert!(image.len() == reference.len() && image.len() == variance.len());
    let pixels = image.len();
    let alpha = 1.0 - 0.99f64.powf(1.0 / pixels as f64);
    let mut passing = 0;
    for ((&x, &r), &v) in image.iter().zip(reference).zip(variance) {
        let (x, r, v) = (XYZ_FROM_SRGB * x, XYZ_FROM_SRGB * r, XYZ_FROM_SRGB * v);
        for c in 0..3 {
            let z = f64::from((x[c] - r[c]).abs())
                * (f64::from(spp) / f64::from(v[c]).max(1e-4)).sqrt();
            let p = crate::erf::erfc(z / std::f64::consts::SQRT_2);
            if p > alpha {
                passing += 1;
            }
        }
    }
    Verdict { passing, channels: 3 * pixels }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_image_equal_to_its_reference_passes_and_an_offset_one_fails() {
        let reference = vec![Vec3::new(0.5, 0.25, 0.125); 64];
        let variance = vec![Vec3::splat(0.01); 64];
        assert!(judge(&reference, &reference, &variance, 100).passes());
        // 0.1 off with a standard error of 0.01: z ≈ 10 in every channel.
        let off: Vec<Vec3> = reference.iter().map(|r| *r + Vec3::splat(0.1)).collect();
        let verdict = judge(&off, &reference, &variance, 100);
        assert_eq!(verdict.passing, 0, "{verdict:?}");
        assert!(!verdict.passes());
    }
}
