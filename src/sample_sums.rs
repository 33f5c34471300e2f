//! Per-pixel sums of samples in fixed point, so that adding them is exact and associative.
//!
//! A render split into sample ranges (or tiles) must merge to the image of the whole render
//! bit for bit. Floating-point sums depend on their order; integer sums do not. Every
//! sample's colour, depth and normal is converted once to a fixed-point integer with
//! `FRACTION_BITS` fractional bits (exact for any f32 of magnitude at least 2⁻³², truncated
//! below, clamped beyond 2^`MAX_MAGNITUDE_LOG2`), summed in `i128`, and turned back into a float
//! only when the pixel is resolved. The whole render goes through the same path, so a
//! split render and the whole one see the same integers whatever the grouping.

use crate::film::Film;
use glam::{DVec3, Vec3};

/// Fractional bits of the fixed-point representation: a sample of 1.0 is 2⁵⁶.
const FRACTION_BITS: i32 = 56;
/// Largest magnitude one sample contributes (2⁵⁰ ≈ 1.1·10¹⁵, beyond any radiance or depth a
/// scene within the coordinate limits gives): one sample is at most 2¹⁰⁶ in fixed point, so
/// the sum of `limits::MAX_SPP` = 2²⁰ samples stays below 2¹²⁶, inside `i128`.
const MAX_MAGNITUDE_LOG2: i32 = 50;
/// The largest magnitude of one sample's value, 2^`MAX_MAGNITUDE_LOG2`: beyond it, the value
/// is summed as this.
pub const LARGEST_SAMPLE: f32 = (1u64 << MAX_MAGNITUDE_LOG2) as f32;
/// The smallest magnitude whose every bit the sums keep; below it, the value is truncated.
pub const SMALLEST_EXACT: f32 = 1.0 / (1u64 << 32) as f32;
/// The squares' sums (for the variance) keep 16 fractional bits fewer, so that they reach
/// 2¹⁶ times further: a square up to 2⁶⁶ (a sample of 8.6·10⁹, a sun seen directly) is
/// summed whole. With the values' scale a square clamped at 2⁵⁰, a sample of 3.4·10⁷, and
/// the variance of pixels on bright lights came out 0. The same sum bound holds (2¹⁰⁶ a
/// sample).
const SQUARE_FRACTION_BITS: i32 = FRACTION_BITS - 16;
const SQUARE_MAX_LOG2: i32 = MAX_MAGNITUDE_LOG2 + 16;

/// `value` in fixed point (NaN counts as 0; ±∞ and huge values are clamped), truncated
/// toward zero: `value · 2^FRACTION_BITS` exactly, through an i64 when it fits, else read off
/// the float's bits. (Seven of these per sample; the f64 → i128 cast is a software routine
/// that cost ~1 % of a render.)
pub fn to_fixed(value: f32) -> i128 {
    to_fixed_scaled::<FRACTION_BITS, MAX_MAGNITUDE_LOG2>(value)
}

/// `to_fixed` for a sample's square, in the squares' scale (`SQUARE_FRACTION_BITS`).
pub fn square_to_fixed(square: f32) -> i128 {
    to_fixed_scaled::<SQUARE_FRACTION_BITS, SQUARE_MAX_LOG2>(square)
}

/// `value · 2^FRACTION`, truncated, clamped at 2^MAX_LOG2.
#[inline]
fn to_fixed_scaled<const FRACTION: i32, const MAX_LOG2: i32>(value: f32) -> i128 {
    // Colours, normals and most depths are below 2⁷: then value · 2⁵⁶ fits an i64, to which
    // the f64 product (exact: 24 significant bits) converts in one instruction, truncating.
    if value.abs() < (1u64 << (63 - FRACTION)) as f32 {
        return (f64::from(value) * 2f64.powi(FRACTION)) as i64 as i128;
    }
    if value.is_nan() {
        return 0;
    }
    let bits = value.to_bits();
    let biased_exponent = ((bits >> 23) & 0xff) as i32;
    let fraction = bits & 0x7f_ffff;
    // value = ±significand · 2^exponent (subnormals have no implicit bit).
    let (significand, exponent) = if biased_exponent == 0 {
        (fraction, -126 - 23)
    } else {
        (fraction | 1 << 23, biased_exponent - 127 - 23)
    };
    let magnitude: i128 = if exponent + 23 >= MAX_LOG2 {
        1 << (MAX_LOG2 + FRACTION)
    } else {
        let shift = exponent + FRACTION;
        if shift >= 0 {
            (significand as i128) << shift
        } else if shift > -32 {
            (significand >> -shift) as i128
        } else {
            0
        }
    };
    if bits >> 31 == 1 { -magnitude } else { magnitude }
}

/// The float value of a fixed-point sum (rounded once, then scaled exactly).
pub fn from_fixed(sum: i128) -> f64 {
    sum as f64 * 2f64.powi(-FRACTION_BITS)
}

/// `from_fixed` of a sum of squares (`square_to_fixed`).
fn square_from_fixed(sum: i128) -> f64 {
    sum as f64 * 2f64.powi(-SQUARE_FRACTION_BITS)
}

/// The sums of one pixel's samples.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PixelSums {
    pub color: [i128; 3],
    /// Samples summed.
    pub samples: u32,
    /// Distances to the first hit, over the samples that hit something.
    pub depth: i128,
    pub depth_samples: u32,
    /// World-space shading normals at the first hit.
    pub normal: [i128; 3],
    /// First-hit albedos (over the samples that hit something).
    pub albedo: [i128; 3],
    /// Squared sample values, for the per-pixel sample variance.
    pub square: [i128; 3],
}

impl PixelSums {
    /// Adds one sample: its radiance and, where it hit something, its depth, normal and
    /// albedo.
    pub fn add_sample(
        &mut self,
        radiance: Vec3,
        depth: Option<f32>,
        normal: Option<Vec3>,
        albedo: Option<Vec3>,
    ) {
        for ((sum, square), v) in
            self.color.iter_mut().zip(&mut self.square).zip(radiance.to_array())
        {
            *sum += to_fixed(v);
            *square += square_to_fixed(v * v);
        }
        if let Some(a) = albedo {
            for (sum, v) in self.albedo.iter_mut().zip(a.to_array()) {
                *sum += to_fixed(v);
            }
        }
        self.samples += 1;
        if let Some(d) = depth {
            self.depth += to_fixed(d);
            self.depth_samples += 1;
        }
        if let Some(n) = normal {
            for (sum, v) in self.normal.iter_mut().zip(n.to_array()) {
                *sum += to_fixed(v);
            }
        }
    }

    /// Adds another set of sums of the same pixel from this render, whose sums stay below
    /// `i128::MAX` for up to `limits::MAX_SPP` samples (see `MAX_MAGNITUDE_LOG2`), as
    /// `add_sample` adds: without the checks of `checked_add` (for part files, which come
    /// from outside), which cost a Cornell box render 0.6 % of its threads' time as every
    /// tile of every pass was added to the film.
    #[inline]
    pub(crate) fn add(&mut self, other: &PixelSums) {
        let add3 =
            |a: &mut [i128; 3], b: &[i128; 3]| a.iter_mut().zip(b).for_each(|(a, b)| *a += b);
        add3(&mut self.color, &other.color);
        self.samples += other.samples;
        self.depth += other.depth;
        self.depth_samples += other.depth_samples;
        add3(&mut self.normal, &other.normal);
        add3(&mut self.albedo, &other.albedo);
        add3(&mut self.square, &other.square);
    }

    /// Adds another set of sums of the same pixel; `None` if a sum overflows (only a
    /// corrupted part file can do that).
    pub fn checked_add(&self, other: &PixelSums) -> Option<PixelSums> {
        let add3 = |a: [i128; 3], b: [i128; 3]| -> Option<[i128; 3]> {
            Some([a[0].checked_add(b[0])?, a[1].checked_add(b[1])?, a[2].checked_add(b[2])?])
        };
        Some(PixelSums {
            color: add3(self.color, other.color)?,
            samples: self.samples.checked_add(other.samples)?,
            depth: self.depth.checked_add(other.depth)?,
            depth_samples: self.depth_samples.checked_add(other.depth_samples)?,
            normal: add3(self.normal, other.normal)?,
            albedo: add3(self.albedo, other.albedo)?,
            square: add3(self.square, other.square)?,
        })
    }

    /// The pixel's values: its mean colour and the AOVs.
    pub fn resolve(&self) -> Resolved {
        let mean = |sum: i128, n: u32| from_fixed(sum) / n.max(1) as f64;
        let mean3 = |sums: [i128; 3], n: u32| {
            DVec3::new(mean(sums[0], n), mean(sums[1], n), mean(sums[2], n))
        };
        let color = mean3(self.color, self.samples);
        let depth = if self.depth_samples > 0 {
            mean(self.depth, self.depth_samples) as f32
        } else {
            f32::INFINITY
        };
        let normal = DVec3::new(
            from_fixed(self.normal[0]),
            from_fixed(self.normal[1]),
            from_fixed(self.normal[2]),
        );
        // The unbiased sample variance of the samples (not of their mean: divide by spp).
        let n = f64::from(self.samples);
        let variance = match self.samples {
            0 | 1 => DVec3::ZERO,
            _ => {
                let square = |i: usize| square_from_fixed(self.square[i]) / n;
                let mean_square = DVec3::new(square(0), square(1), square(2));
                ((mean_square - color * color) * (n / (n - 1.0))).max(DVec3::ZERO)
            }
        };
        Resolved {
            color: color.as_vec3(),
            depth,
            normal: normal.normalize_or_zero().as_vec3(),
            albedo: mean3(self.albedo, self.depth_samples).as_vec3(),
            variance: variance.as_vec3(),
            alpha: (f64::from(self.depth_samples) / n.max(1.0)) as f32,
        }
    }
}

/// One pixel's values (`PixelSums::resolve`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Resolved {
    pub color: Vec3,
    /// Mean distance to the first hit over the samples that hit; +∞ where none did.
    pub depth: f32,
    pub normal: Vec3,
    pub albedo: Vec3,
    pub variance: Vec3,
    /// The fraction of samples that hit something.
    pub alpha: f32,
}

/// The sums of every pixel of an image (or of the part of it one task rendered).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FilmSums {
    pub width: u32,
    pub height: u32,
    /// Row-major from the top-left pixel.
    pub pixels: Vec<PixelSums>,
}

impl FilmSums {
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        FilmSums { width, height, pixels: vec![PixelSums::default(); n] }
    }

    pub fn index(&self, x: u32, y: u32) -> usize {
        y as usize * self.width as usize + x as usize
    }

    /// The image: each pixel's means.
    pub fn resolve(&self) -> Film {
        let mut film = Film::new(self.width, self.height);
        for (i, sums) in self.pixels.iter().enumerate() {
            let pixel = sums.resolve();
            film.color[i] = pixel.color;
            film.depth[i] = pixel.depth;
            film.normal[i] = pixel.normal;
            film.albedo[i] = pixel.albedo;
            film.variance[i] = pixel.variance;
            film.alpha[i] = pixel.alpha;
        }
        film
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_point_is_exact_for_ordinary_values() {
        for v in [0.0f32, 1.0, -1.0, 0.1, 2e-10, 12345.678, 3.0e14, -7.25e-9] {
            assert_eq!(from_fixed(to_fixed(v)) as f32, v, "{v}");
        }
    }

    #[test]
    fn fixed_point_equals_the_exact_product_truncated() {
        // The definition: value · 2^FRACTION_BITS in f64 (exact), clamped, truncated.
        let by_definition = |value: f32| -> i128 {
            let limit = (1u64 << MAX_MAGNITUDE_LOG2) as f64;
            ((value as f64).clamp(-limit, limit) * 2f64.powi(FRACTION_BITS)) as i128
        };
        let mut bits = 0x1234_5678_u32;
        let specials = [
            0.0f32,
            -0.0,
            f32::MIN_POSITIVE,
            1e-45,
            -1e-45,
            2f32.powi(-56),
            2f32.powi(-57),
            -2f32.powi(-56),
            2f32.powi(50),
            2f32.powi(50) * (1.0 - f32::EPSILON / 2.0),
            -2f32.powi(49) * 1.5,
            f32::MAX,
            -f32::MAX,
            0.75,
            -1.5e-9,
            3.3e6,
            128.0,
            -128.0,
            128.0 * (1.0 - f32::EPSILON / 2.0),
            -128.0 * (1.0 - f32::EPSILON / 2.0),
            2f32.powi(-60),
            -3.0 * 2f32.powi(-58),
        ];
        let random = (0..200_000).map(|_| {
            bits ^= bits << 13;
            bits ^= bits >> 17;
            bits ^= bits << 5;
            f32::from_bits(bits)
        });
        // Random bits are mostly huge or tiny; ordinary magnitudes too.
        let ordinary = (0..200_000).map(|i| (i as f32 * 0.618_034).fract() * 300.0 - 150.0);
        for v in specials.into_iter().chain(random).chain(ordinary).filter(|v| !v.is_nan()) {
            assert_eq!(to_fixed(v), by_definition(v), "{v:e} ({:#x})", v.to_bits());
        }
    }

    #[test]
    fn the_variance_holds_for_bright_and_dim_samples() {
        let variance = |a: f32, b: f32| {
            let mut pixel = PixelSums::default();
            pixel.add_sample(Vec3::splat(a), None, None, None);
            pixel.add_sample(Vec3::splat(b), None, None, None);
            pixel.resolve().variance.x as f64
        };
        // Two samples a, b: (a − b)² / 2.
        for (a, b) in [(0.0, 1e9), (1e8, 3e8), (1e-3, 3e-3), (0.25, 0.75)] {
            let expected = (f64::from(a) - f64::from(b)).powi(2) / 2.0;
            let relative = (variance(a, b) - expected).abs() / expected;
            assert!(relative < 1e-5, "{a} {b}: {} vs {expected}", variance(a, b));
        }
    }

    #[test]
    fn fixed_point_clamps_what_would_overflow() {
        assert_eq!(to_fixed(f32::NAN), 0);
        assert_eq!(to_fixed(f32::INFINITY), to_fixed(1e30));
        assert_eq!(to_fixed(f32::NEG_INFINITY), -to_fixed(1e30));
        let most = to_fixed(f32::MAX);
        assert!(most.checked_mul(i128::from(crate::limits::MAX_SPP)).is_some());
        assert!(
            most.checked_mul(i128::from(crate::limits::MAX_SPP) * 4).is_none(),
            "no slack wasted"
        );
    }

    #[test]
    fn sums_in_any_grouping_are_identical() {
        let values: Vec<f32> =
            (0..97).map(|i| ((i * 7919) % 1000) as f32 * 0.37e-3 + 1e-7).collect();
        // Every field of the sums differs from the others, so a field added to the wrong
        // one, or left out, shows.
        let add = |sums: &mut PixelSums, v: f32| {
            let normal = Vec3::new(v, -2.0 * v, 0.5);
            sums.add_sample(Vec3::new(v, 3.0 * v, -v), Some(5.0 * v), Some(normal), Some(-normal))
        };
        let mut whole = PixelSums::default();
        for v in &values {
            add(&mut whole, *v);
        }
        for cut in [1usize, 13, 50, 96] {
            let (mut a, mut b) = (PixelSums::default(), PixelSums::default());
            for v in &values[cut..] {
                add(&mut b, *v);
            }
            for v in &values[..cut] {
                add(&mut a, *v);
            }
            assert_eq!(b.checked_add(&a), Some(whole), "cut at {cut}");
            // A render's own tiles are added unchecked: the same sums, in either order.
            let (mut ab, mut ba) = (a, b);
            ab.add(&b);
            ba.add(&a);
            assert_eq!((ab, ba), (whole, whole), "cut at {cut}, unchecked");
        }
    }

    #[test]
    fn resolve_gives_means_and_marks_pixels_nothing_hit() {
        let mut sums = PixelSums::default();
        sums.add_sample(Vec3::new(1.0, 2.0, 3.0), None, None, None);
        sums.add_sample(Vec3::new(3.0, 2.0, 1.0), None, None, None);
        let pixel = sums.resolve();
        assert_eq!(pixel.color, Vec3::splat(2.0));
        assert_eq!(pixel.depth, f32::INFINITY);
        assert_eq!((pixel.normal, pixel.albedo, pixel.alpha), (Vec3::ZERO, Vec3::ZERO, 0.0));
        // Sample variance of (1, 3), (2, 2), (3, 1): 2, 0, 2.
        assert_eq!(pixel.variance, Vec3::new(2.0, 0.0, 2.0));
        let albedo = Vec3::new(0.5, 0.25, 1.0);
        sums.add_sample(Vec3::ZERO, Some(4.0), Some(Vec3::new(0.0, 0.0, 2.0)), Some(albedo));
        let pixel = sums.resolve();
        assert_eq!((pixel.depth, pixel.normal, pixel.albedo), (4.0, Vec3::Z, albedo));
        assert_eq!(pixel.alpha, 1.0 / 3.0);
    }
}
