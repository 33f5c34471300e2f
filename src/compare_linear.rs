//! Comparing two linear (EXR) images: the mean of each channel, the RMSE, and `image_error`'s
//! relative figures. Used by `embray compare` when both images are EXRs.

use crate::compare::CompareError;
use crate::film::Film;
use crate::image_error::{ImageError, image_error};
use glam::DVec3;
use std::path::Path;

/// How two linear images differ.
#[derive(Clone, Debug)]
pub struct LinearComparison {
    pub width: u32,
    pub height: u32,
    /// Mean of each channel over the finite pixels of each image.
    pub mean_a: DVec3,
    pub mean_b: DVec3,
    /// √(mean over channels and pixels of (a − b)²), over pixels finite in both.
    pub rmse: f64,
    /// Relative MSE, largest difference and the fraction of pixels off by 1 % of `b`'s
    /// mean, and the pixels left out of them (NaN or infinite in either).
    pub error: ImageError,
}

impl LinearComparison {
    /// The largest relative difference of a channel mean, |a − b| / b; `None` when a
    /// channel's mean is 0 in `b` but not in `a`, where no ratio means anything (dividing
    /// by a tiny floor instead printed 10³² %).
    pub fn mean_relative_difference(&self) -> Option<f64> {
        let (a, b) = (self.mean_a.to_array(), self.mean_b.to_array());
        a.iter().zip(&b).try_fold(0.0f64, |largest, (&a, &b)| match (a == b, b == 0.0) {
            (true, _) => Some(largest),
            (false, true) => None,
            (false, false) => Some(largest.max((a - b).abs() / b.abs())),
        })
    }
}

fn mean(film: &Film) -> DVec3 {
    let finite: Vec<DVec3> =
        film.color.iter().filter(|c| c.is_finite()).map(|c| c.as_dvec3()).collect();
    finite.iter().sum::<DVec3>() / finite.len().max(1) as f64
}

/// Compares `a` with the reference `b` (same size, else an error).
pub fn compare_films(a: &Film, b: &Film) -> Result<LinearComparison, CompareError> {
    if (a.width, a.height) != (b.width, b.height) {
        return Err(CompareError::Size {
            a_width: a.width,
            a_height: a.height,
            b_width: b.width,
            b_height: b.height,
        });
    }
    let (mut sum2, mut n) = (0.0f64, 0usize);
    for (x, y) in a.color.iter().zip(&b.color) {
        if x.is_finite() && y.is_finite() {
            sum2 += (x.as_dvec3() - y.as_dvec3()).length_squared();
            n += 3;
        }
    }
    // An RMSE of 0 over no pixel would read as a perfect match.
    if n == 0 {
        let count = |f: &Film| f.non_finite().map_or(0, |nf| nf.count);
        return Err(CompareError::NothingFinite { a: count(a), b: count(b) });
    }
    Ok(LinearComparison {
        width: a.width,
        height: a.height,
        mean_a: mean(a),
        mean_b: mean(b),
        rmse: (sum2 / n.max(1) as f64).sqrt(),
        error: image_error(a, b),
    })
}

/// Refuses a variance image (`compare --variance`) with a texel that is NaN or infinite:
/// the Z-test divides by it, so +inf passes every image and NaN turns the test into
/// nonsense rather than a failure. A negative texel is kept: Mitsuba's own references have
/// them (various_shapes' variance is -8e-4 at its first pixel: the rounding of E[x²] −
/// E[x]²), and its test, as `mitsuba_rule`, raises every variance to at least 1e-4.
pub fn check_variance(variance: &Film, path: &Path) -> Result<(), CompareError> {
    for (i, texel) in variance.color.iter().enumerate() {
        let bad = texel.to_array().into_iter().zip(['R', 'G', 'B']).find(|(v, _)| !v.is_finite());
        if let Some((value, channel)) = bad {
            let width = variance.width.max(1);
            let (x, y) = (i as u32 % width, i as u32 / width);
            return Err(CompareError::Variance { path: path.to_path_buf(), x, y, channel, value });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// A reference pixel that is NaN is counted and left out, as the first image's are: the
    /// figures stay those of the finite pixels, not NaN (nor a perfect 0 with no word).
    #[test]
    fn a_non_finite_reference_pixel_is_counted_and_left_out() {
        let mut a = Film::new(3, 1);
        let mut b = Film::new(3, 1);
        a.color = vec![Vec3::splat(1.0), Vec3::splat(2.0), Vec3::splat(5.0)];
        b.color = vec![Vec3::splat(1.0), Vec3::splat(1.0), Vec3::splat(f32::NAN)];
        let c = compare_films(&a, &b).unwrap();
        assert_eq!((c.error.non_finite_reference, c.error.non_finite), (1, 0));
        assert_eq!(c.mean_b, DVec3::splat(1.0));
        // Over the two finite pixels: errors 0 and 1 a channel, against references of 1.
        assert_eq!(c.error.relative_mse, 3.0 / 6.0);
        assert_eq!(c.error.max_abs, 1.0);
        assert_eq!(c.error.pixel_relative_mse, 3.0 / 1.01 / 6.0);
        assert_eq!(c.error.fraction_off, 0.5);
    }

    #[test]
    fn figures_of_a_known_difference() {
        let mut a = Film::new(2, 1);
        let mut b = Film::new(2, 1);
        a.color = vec![Vec3::splat(1.0), Vec3::splat(3.0)];
        b.color = vec![Vec3::splat(1.0), Vec3::splat(1.0)];
        let c = compare_films(&a, &b).unwrap();
        assert_eq!(c.mean_a, DVec3::splat(2.0));
        assert_eq!(c.mean_b, DVec3::splat(1.0));
        assert!((c.mean_relative_difference().unwrap() - 1.0).abs() < 1e-12);
        let black = Film::new(2, 1);
        assert_eq!(compare_films(&a, &black).unwrap().mean_relative_difference(), None);
        assert_eq!(compare_films(&black, &black).unwrap().mean_relative_difference(), Some(0.0));
        // Half the samples differ by 2: RMSE √(4/2).
        assert!((c.rmse - 2f64.sqrt()).abs() < 1e-12, "{}", c.rmse);
        assert!(matches!(compare_films(&a, &Film::new(1, 2)), Err(CompareError::Size { .. })));
    }
}
