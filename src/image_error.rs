//! How far one rendered image is from a reference: the numbers every comparison reports.

use crate::film::Film;

#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ImageError {
    /// Σ(a−b)² / Σ b² over all channels: weighted by energy, so a light's bright pixels
    /// can dominate it.
    pub relative_mse: f64,
    /// The mean over pixel channels of (a−b)² / (b² + 0.01): the per-pixel relative MSE
    /// denoising work reports, in which every pixel counts alike.
    pub pixel_relative_mse: f64,
    /// Largest absolute difference of any channel.
    pub max_abs: f64,
    /// Fraction of the pixels compared (finite in both) with a channel off by more than 1 %
    /// of the reference's mean value.
    pub fraction_off: f64,
    /// Pixels of the test image that are NaN or infinite, and of the reference where the
    /// test's are finite: both excluded from every other number (a NaN in either must be
    /// seen here, not hidden or spread into a NaN figure).
    pub non_finite: usize,
    pub non_finite_reference: usize,
}

/// Compares `test` with `reference` (same size).
pub fn image_error(test: &Film, reference: &Film) -> ImageError {
    assert_eq!(
        (test.width, test.height),
        (reference.width, reference.height),
        "image sizes differ"
    );
    let finite_reference = reference.color.iter().filter(|c| c.is_finite());
    let mean = finite_reference.clone().map(|c| c.element_sum() as f64).sum::<f64>()
        / (3.0 * finite_reference.count().max(1) as f64);
    let (mut err2, mut ref2, mut max_abs, mut off) = (0.0, 0.0, 0.0f64, 0);
    let (mut non_finite, mut non_finite_reference) = (0, 0);
    let mut pixel_relative = 0.0;
    for (a, b) in test.color.iter().zip(&reference.color) {
        if !a.is_finite() {
            non_finite += 1;
            continue;
        }
        if !b.is_finite() {
            non_finite_reference += 1;
            continue;
        }
        let d = (*a - *b).as_dvec3();
        err2 += d.length_squared();
        let b2 = b.as_dvec3() * b.as_dvec3();
        pixel_relative += (d * d / (b2 + 0.01)).element_sum();
        ref2 += b.as_dvec3().length_squared();
        max_abs = max_abs.max(d.abs().max_element());
        if d.abs().max_element() > 0.01 * mean {
            off += 1;
        }
    }
    let compared = (test.color.len() - non_finite - non_finite_reference).max(1);
    ImageError {
        relative_mse: if ref2 > 0.0 { err2 / ref2 } else { err2 },
        pixel_relative_mse: pixel_relative / (3 * compared) as f64,
        max_abs,
        fraction_off: off as f64 / compared as f64,
        non_finite,
        non_finite_reference,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn identical_images_have_zero_error_and_nan_is_counted() {
        let mut a = Film::new(2, 1);
        a.color = vec![Vec3::ONE, Vec3::splat(2.0)];
        assert_eq!(image_error(&a, &a).relative_mse, 0.0);
        let mut b = a.clone();
        b.color[0] = Vec3::NAN;
        b.color[1] = Vec3::splat(3.0);
        let e = image_error(&b, &a);
        assert_eq!(e.non_finite, 1);
        // Of the pixels compared (finite in both), the one is off.
        assert!((e.max_abs - 1.0).abs() < 1e-12 && e.fraction_off == 1.0);
        // Only the finite pixel counts: 1² / (2² + 0.01) per channel.
        assert!((e.pixel_relative_mse - 1.0 / 4.01).abs() < 1e-9, "{}", e.pixel_relative_mse);
        // Energy-weighted against per pixel: the bright pixel's error swamps the first, not
        // the second.
        let mut c = a.clone();
        c.color = vec![Vec3::splat(1.5), Vec3::splat(2.2)];
        let e = image_error(&c, &a);
        let expected_relative = (3.0 * 0.25 + 3.0 * 0.04) / (3.0 + 12.0);
        let expected_pixel = (0.25 / 1.01 + 0.04 / 4.01) / 2.0;
        assert!((e.relative_mse - expected_relative).abs() < 1e-6, "{}", e.relative_mse);
        assert!((e.pixel_relative_mse - expected_pixel).abs() < 1e-6, "{}", e.pixel_relative_mse);
    }
}
