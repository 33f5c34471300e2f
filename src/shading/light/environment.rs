//! Light from infinitely far away in every direction: a latitude-longitude radiance map
//! (the course's SphericalDirectionalLight), importance-sampled by luminance. Directions map
//! to the image as hw5.tex defines it, in world space (y up): u = (1 + atan2(x, −z)/π)/2,
//! v = acos(y)/π, so the image's centre is seen looking along −z and its top row is
//! straight up. Texels are looked up nearest, so the radiance is exactly the piecewise-
//! constant function the sampling density follows.

use crate::color::luminance;
use crate::sampling::piecewise::Piecewise2D;
use glam::{Mat3, Vec2, Vec3};
use std::f32::consts::PI;
use std::sync::Arc;

/// Sampling grids have at least this many cells across (and half as many down).
const MIN_CELLS_ACROSS: usize = 64;

/// A radiance map and how render-space directions find their texel.
#[derive(Clone, Debug)]
pub struct EnvironmentLight {
    width: usize,
    height: usize,
    /// Radiance per texel, row 0 at the top (straight up), already scaled.
    texels: Arc<[Vec3]>,
    /// Render space's rotation back to world space (identity for translation-only spaces).
    world_from_render: Mat3,
    /// Over the image, in proportion to luminance × sin θ; `None` for a black map.
    distribution: Option<Piecewise2D>,
}

/// A direction sampled towards the environment.
#[derive(Clone, Copy, Debug)]
pub struct EnvironmentSample {
    /// Unit direction, in render space.
    pub wi: Vec3,
    pub radiance: Vec3,
    /// Density per unit solid angle.
    pub pdf: f32,
}

impl EnvironmentLight {
    /// A `width` × `height` map of radiances `texels` (row-major from the top) times
    /// `scale`. Non-finite and negative values count as black (callers refuse them first).
    pub fn new(
        width: usize,
        height: usize,
        texels: &[Vec3],
        scale: Vec3,
        world_from_render: Mat3,
    ) -> Self {
        assert_eq!(texels.len(), width * height, "a texel per pixel");
        let texels: Arc<[Vec3]> = texels
            .iter()
            .map(|t| {
                let t = *t * scale;
                if t.is_finite() { t.max(Vec3::ZERO) } else { Vec3::ZERO }
            })
            .collect();
        // Tiny maps (a constant sky is one texel) are sampled on a finer grid, so that the
        // sin θ factor varies little within a cell and sampling stays close to uniform in
        // solid angle; each texel is a whole block of cells, so the radiance is still
        // constant on every cell.
        let (across, down) = (width.max(MIN_CELLS_ACROSS), height.max(MIN_CELLS_ACROSS / 2));
        let (across, down) = (width * across.div_ceil(width), height * down.div_ceil(height));
        let weights: Vec<f32> = (0..across * down)
            .map(|i| {
                let (col, row) = (i % across, i / across);
                let texel = texels[row * height / down * width + col * width / across];
                let theta = (row as f32 + 0.5) / down as f32 * PI;
                luminance(texel) * theta.sin()
            })
            .collect();
        let distribution = Piecewise2D::new(&weights, across, down);
        EnvironmentLight { width, height, texels, world_from_render, distribution }
    }

    /// Image coordinates in [0, 1]² of the unit world direction `d`, and sin θ.
    fn uv_of(d: Vec3) -> (Vec2, f32) {
        let u = 0.5 * (1.0 + d.x.atan2(-d.z) / PI);
        // sin θ from the horizontal components stays accurate near the poles, where
        // 1 − cos² θ cancels.
        let sin_theta = d.x.hypot(d.z);
        let v = sin_theta.atan2(d.y) / PI;
        (Vec2::new(u, v), sin_theta)
    }

    /// The unit world direction at image coordinates `uv`, and sin θ.
    fn direction_of(uv: Vec2) -> (Vec3, f32) {
        let (sin_theta, cos_theta) = (uv.y * PI).sin_cos();
        let (sin_phi, cos_phi) = ((2.0 * uv.x - 1.0) * PI).sin_cos();
        (Vec3::new(sin_theta * sin_phi, cos_theta, -sin_theta * cos_phi), sin_theta)
    }

    fn texel(&self, uv: Vec2) -> Vec3 {
        // u wraps (u = 1 is u = 0); v = 1 is the bottom row.
        let col = ((uv.x * self.width as f32) as usize) % self.width;
        let row = ((uv.y * self.height as f32) as usize).min(self.height - 1);
        self.texels[row * self.width + col]
    }

    /// Radiance arriving from direction `dir` (render space, any length).
    pub fn radiance(&self, dir: Vec3) -> Vec3 {
        let d = (self.world_from_render * dir).normalize();
        if !d.is_finite() {
            return Vec3::ZERO;
        }
        self.texel(Self::uv_of(d).0)
    }

    /// Density per unit solid angle with which `sample` picks the render-space direction
    /// `dir`.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        let Some(distribution) = &self.distribution else { return 0.0 };
        let d = (self.world_from_render * dir).normalize();
        let (uv, sin_theta) = Self::uv_of(d);
        if !(sin_theta > 0.0) {
            return 0.0;
        }
        let uv = uv.min(Vec2::splat(1.0_f32.next_down()));
        distribution.pdf(uv) / (2.0 * PI * PI * sin_theta)
    }

    /// A direction drawn in proportion to luminance with `u`; `None` for a black map.
    pub fn sample(&self, u: Vec2) -> Option<EnvironmentSample> {
        let distribution = self.distribution.as_ref()?;
        let (uv, pdf_uv) = distribution.sample(u);
        let (d, sin_theta) = Self::direction_of(uv);
        if !(sin_theta > 0.0) || !(pdf_uv > 0.0) {
            return None;
        }
        let wi = self.world_from_render.transpose() * d;
        Some(EnvironmentSample {
            wi,
            radiance: self.texel(uv),
            pdf: pdf_uv / (2.0 * PI * PI * sin_theta),
        })
    }

    /// Whether the map sends any light (a black one is only a background).
    pub fn is_lit(&self) -> bool {
        self.distribution.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::chi_square::assert_fits;
    use crate::splitmix::SplitMix64;

    /// A dim sky with a small bright sun, `width` × `height`.
    pub(crate) fn sun_map(width: usize, height: usize) -> Vec<Vec3> {
        (0..width * height)
            .map(|i| {
                let (col, row) = (i % width, i / width);
                let sun = (col as i64 - (width * 5 / 8) as i64).abs() <= 1
                    && (row as i64 - (height / 4) as i64).abs() <= 1;
                if sun { Vec3::new(4000.0, 3600.0, 3000.0) } else { Vec3::new(0.3, 0.5, 0.9) }
            })
            .collect()
    }

    fn rotation() -> Mat3 {
        Mat3::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 0.7)
    }

    #[test]
    fn directions_map_as_the_course_defines() {
        // Looking along −z sees the image centre; +x is u = 3/4; straight up is the top.
        let (uv, _) = EnvironmentLight::uv_of(Vec3::NEG_Z);
        assert!((uv - Vec2::new(0.5, 0.5)).length() < 1e-6, "{uv}");
        let (uv, _) = EnvironmentLight::uv_of(Vec3::X);
        assert!((uv - Vec2::new(0.75, 0.5)).length() < 1e-6, "{uv}");
        assert!(EnvironmentLight::uv_of(Vec3::Y).0.y.abs() < 1e-6);
        for uv in [Vec2::new(0.1, 0.2), Vec2::new(0.7, 0.9), Vec2::new(0.5, 0.5)] {
            let (d, _) = EnvironmentLight::direction_of(uv);
            assert!((EnvironmentLight::uv_of(d).0 - uv).length() < 1e-5, "round trip {uv}");
        }
    }

    #[test]
    fn sampling_density_matches_pdf_by_chi_square() {
        let (w, h) = (16, 8);
        let light = EnvironmentLight::new(w, h, &sun_map(w, h), Vec3::ONE, rotation());
        // Cells: 12 bands of cos θ × 24 of φ, in world space, each of equal solid angle.
        let (bands, sectors) = (12usize, 24usize);
        let cell_of = |d: Vec3| {
            let band = (((d.y + 1.0) * 0.5 * bands as f32) as usize).min(bands - 1);
            let phi = d.z.atan2(d.x) / (2.0 * PI) + 0.5;
            band * sectors + ((phi * sectors as f32) as usize).min(sectors - 1)
        };
        // Each cell's probability: the pdf integrated over it on a fine midpoint grid.
        let grid = 64;
        let mut expected = vec![0.0f64; bands * sectors];
        for (cell, e) in expected.iter_mut().enumerate() {
            let (band, sector) = (cell / sectors, cell % sectors);
            for i in 0..grid * grid {
                let y = ((band * grid + i / grid) as f32 + 0.5) / (bands * grid) as f32;
                let x = ((sector * grid + i % grid) as f32 + 0.5) / (sectors * grid) as f32;
                let (z, phi) = (2.0 * y - 1.0, (x - 0.5) * 2.0 * PI);
                let r = (1.0 - z * z).max(0.0).sqrt();
                let d = Vec3::new(r * phi.cos(), z, r * phi.sin());
                *e += f64::from(light.pdf(rotation().transpose() * d));
            }
            *e *= 4.0 * std::f64::consts::PI / (bands * sectors * grid * grid) as f64;
        }
        let total: f64 = expected.iter().sum();
        assert!((total - 1.0).abs() < 0.01, "the pdf integrates to {total}");
        let mut rng = SplitMix64(7);
        let samples = 300_000u64;
        let mut counts = vec![0u64; bands * sectors];
        for _ in 0..samples {
            let s = light.sample(Vec2::new(rng.unit(), rng.unit())).unwrap();
            assert!((s.wi.length() - 1.0).abs() < 1e-5);
            let pdf = light.pdf(s.wi);
            assert!((pdf - s.pdf).abs() <= 1e-3 * s.pdf, "pdf {pdf} vs sampled {}", s.pdf);
            assert_eq!(light.radiance(s.wi), s.radiance);
            counts[cell_of(rotation() * s.wi)] += 1;
        }
        let normalised: Vec<f64> = expected.iter().map(|e| e / total).collect();
        assert_fits("environment sampling", &counts, &normalised, samples);
    }

    /// Irradiance at a surface facing `n` estimated with `samples` directions: by the
    /// luminance distribution, or uniformly over the sphere. Returns (mean, variance) of the
    /// luminance of one-sample estimates.
    fn irradiance_estimates(light: &EnvironmentLight, n: Vec3, importance: bool) -> (f64, f64) {
        let mut rng = SplitMix64(99);
        let samples = 200_000;
        let (mut sum, mut sum2) = (0.0f64, 0.0f64);
        for _ in 0..samples {
            let u = Vec2::new(rng.unit(), rng.unit());
            let (wi, radiance, pdf) = if importance {
                let s = light.sample(u).unwrap();
                (s.wi, s.radiance, s.pdf)
            } else {
                let z = 1.0 - 2.0 * u.x;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let (sin, cos) = (2.0 * PI * u.y).sin_cos();
                let wi = Vec3::new(r * cos, r * sin, z);
                (wi, light.radiance(wi), 1.0 / (4.0 * PI))
            };
            let estimate = f64::from(luminance(radiance) * n.dot(wi).max(0.0) / pdf);
            sum += estimate;
            sum2 += estimate * estimate;
        }
        let mean = sum / samples as f64;
        (mean, sum2 / samples as f64 - mean * mean)
    }

    #[test]
    fn importance_sampling_beats_uniform_sampling_on_a_sun() {
        let (w, h) = (64, 32);
        let light = EnvironmentLight::new(w, h, &sun_map(w, h), Vec3::ONE, rotation());
        // A surface that faces the sun's general direction.
        let sun = light.sample(Vec2::new(0.5, 0.5)).unwrap().wi;
        let n = (sun + Vec3::new(0.2, 0.1, 0.0)).normalize();
        let (mean_is, var_is) = irradiance_estimates(&light, n, true);
        let (mean_uniform, var_uniform) = irradiance_estimates(&light, n, false);
        let ratio = var_uniform / var_is;
        println!(
            "irradiance {mean_is:.3} (importance) vs {mean_uniform:.3} (uniform); \
             variance ratio uniform/importance {ratio:.1}"
        );
        // Both estimate the same integral (to their standard errors).
        let error = 4.0 * ((var_is + var_uniform) / 200_000.0).sqrt();
        assert!((mean_is - mean_uniform).abs() < error, "{mean_is} vs {mean_uniform}");
        assert!(ratio > 20.0, "importance sampling lowers variance only {ratio:.1}×");
    }

    #[test]
    fn a_black_map_is_not_sampled_and_sends_nothing() {
        let light = EnvironmentLight::new(2, 1, &[Vec3::ZERO; 2], Vec3::ONE, Mat3::IDENTITY);
        assert!(!light.is_lit());
        assert!(light.sample(Vec2::new(0.3, 0.3)).is_none());
        assert_eq!(light.pdf(Vec3::X), 0.0);
        let light = EnvironmentLight::new(
            1,
            1,
            &[Vec3::new(f32::NAN, 1.0, 1.0)],
            Vec3::ONE,
            Mat3::IDENTITY,
        );
        assert_eq!(light.radiance(Vec3::Y), Vec3::ZERO);
    }
}
