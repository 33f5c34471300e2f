//! Light from infinitely far away in every direction: a latitude-longitude or light-probe
//! radiance map (the course's SphericalDirectionalLight; `env_mapping` has the mappings),
//! importance-sampled by luminance × solid angle. Texels are looked up nearest, so the
//! radiance is exactly the piecewise-constant function the sampling density follows.

use super::env_mapping;
use super::env_mapping::EnvironmentMapping;
use crate::color::luminance;
use crate::sampling::piecewise::Piecewise2D;
use crate::sampling::uniform_sphere;
use glam::{Mat3, Vec2, Vec3};
use std::sync::Arc;

/// The density of directions uniform over the sphere.
const UNIFORM_PDF: f32 = 1.0 / (4.0 * std::f32::consts::PI);

/// Sampling grids have at least this many cells across (and half as many down).
const MIN_CELLS_ACROSS: usize = 64;

/// A radiance map and how render-space directions find their texel.
#[derive(Clone, Debug)]
pub struct EnvironmentLight {
    width: usize,
    height: usize,
    /// Radiance per texel, row 0 at the top (straight up), already scaled.
    texels: Arc<[Vec3]>,
    mapping: EnvironmentMapping,
    /// Render space's rotation back to world space (identity for translation-only spaces).
    world_from_render: Mat3,
    /// Over the image, in proportion to luminance × solid angle per cell; `None` for a black map.
    distribution: Option<Piecewise2D>,
    lookup: TexelLookup,
    /// The radiance of a map that is one radiance everywhere (a constant sky, Mitsuba's
    /// `constant` emitter), if it is lit: sampled uniformly over the sphere, the density it
    /// is in proportion to, without the map's tables or its mapping's trigonometry.
    uniform: Option<Vec3>,
}

/// How a direction's radiance is read from the map.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TexelLookup {
    /// The texel the direction falls in (constant over each texel's cell).
    #[default]
    Nearest,
    /// Bilinear between texel centres, periodic in u, with the first and last rows on the
    /// poles (Mitsuba 3's `envmap`: row j at v = j / (H − 1)).
    BilinearPoles,
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
        mapping: EnvironmentMapping,
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
        // solid angle per cell varies little within it and sampling stays close to uniform in
        // solid angle; each texel is a whole block of cells, so the radiance is still
        // constant on every cell.
        let (across, down) = (width.max(MIN_CELLS_ACROSS), height.max(MIN_CELLS_ACROSS / 2));
        let (across, down) = (width * across.div_ceil(width), height * down.div_ceil(height));
        let weights: Vec<f32> = (0..across * down)
            .map(|i| {
                let (col, row) = (i % across, i / across);
                let texel = texels[row * height / down * width + col * width / across];
                let centre =
                    Vec2::new((col as f32 + 0.5) / across as f32, (row as f32 + 0.5) / down as f32);
                let half = Vec2::new(0.5 / across as f32, 0.5 / down as f32);
                luminance(texel) * env_mapping::cell_solid_angle(mapping, centre, half)
            })
            .collect();
        let distribution = Piecewise2D::new(&weights, across, down);
        let first = texels[0];
        let uniform =
            (distribution.is_some() && texels.iter().all(|t| *t == first)).then_some(first);
        EnvironmentLight {
            width,
            height,
            texels,
            mapping,
            world_from_render,
            distribution,
            lookup: TexelLookup::Nearest,
            uniform,
        }
    }

    /// The same map read with `lookup` (sampling stays in proportion to the texels).
    pub fn with_lookup(mut self, lookup: TexelLookup) -> Self {
        self.lookup = lookup;
        self
    }

    fn texel(&self, uv: Vec2) -> Vec3 {
        if self.lookup == TexelLookup::BilinearPoles {
            return self.bilinear(uv);
        }
        // u wraps (u = 1 is u = 0); v = 1 is the bottom row.
        let col = ((uv.x * self.width as f32) as usize) % self.width;
        let row = ((uv.y * self.height as f32) as usize).min(self.height - 1);
        self.texels[row * self.width + col]
    }

    fn bilinear(&self, uv: Vec2) -> Vec3 {
        let (w, h) = (self.width, self.height);
        let x = (uv.x - uv.x.floor()) * w as f32 - 0.5;
        let y = uv.y.clamp(0.0, 1.0) * (h - 1) as f32;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let col0 = (x0 as i64).rem_euclid(w as i64) as usize;
        let col1 = (col0 + 1) % w;
        let row0 = (y0 as usize).min(h - 1);
        let row1 = (row0 + 1).min(h - 1);
        let at = |row: usize, col: usize| self.texels[row * w + col];
        let top = at(row0, col0) * (1.0 - fx) + at(row0, col1) * fx;
        let bottom = at(row1, col0) * (1.0 - fx) + at(row1, col1) * fx;
        top * (1.0 - fy) + bottom * fy
    }

    /// Radiance arriving from direction `dir` (render space, any length).
    pub fn radiance(&self, dir: Vec3) -> Vec3 {
        let d = (self.world_from_render * dir).normalize();
        if !d.is_finite() {
            return Vec3::ZERO;
        }
        if let Some(radiance) = self.uniform {
            return radiance;
        }
        self.texel(env_mapping::uv_of(self.mapping, d).0)
    }

    /// Density per unit solid angle with which `sample` picks the render-space direction
    /// `dir`.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        let Some(distribution) = &self.distribution else { return 0.0 };
        if self.uniform.is_some() {
            return UNIFORM_PDF;
        }
        let d = (self.world_from_render * dir).normalize();
        let (uv, solid_angle) = env_mapping::uv_of(self.mapping, d);
        if !(solid_angle > 0.0) {
            return 0.0;
        }
        let uv = uv.clamp(Vec2::ZERO, Vec2::splat(1.0_f32.next_down()));
        distribution.pdf(uv) / solid_angle
    }

    /// A direction drawn in proportion to luminance with `u`; `None` for a black map.
    pub fn sample(&self, u: Vec2) -> Option<EnvironmentSample> {
        let distribution = self.distribution.as_ref()?;
        if let Some(radiance) = self.uniform {
            let wi: Vec3 = self.world_from_render.transpose() * uniform_sphere(u);
            return Some(EnvironmentSample { wi, radiance, pdf: UNIFORM_PDF });
        }
        let (uv, pdf_uv) = distribution.sample(u);
        let (d, solid_angle) = env_mapping::direction_of(self.mapping, uv)?;
        if !(solid_angle > 0.0) || !(pdf_uv > 0.0) {
            return None;
        }
        let wi = self.world_from_render.transpose() * d;
        Some(EnvironmentSample { wi, radiance: self.texel(uv), pdf: pdf_uv / solid_angle })
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
    use env_mapping::{direction_of, uv_of};
    use std::f32::consts::PI;

    const LAT_LONG: EnvironmentMapping = EnvironmentMapping::LatLong;

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
        let (uv, _) = uv_of(LAT_LONG, Vec3::NEG_Z);
        assert!((uv - Vec2::new(0.5, 0.5)).length() < 1e-6, "{uv}");
        let (uv, _) = uv_of(LAT_LONG, Vec3::X);
        assert!((uv - Vec2::new(0.75, 0.5)).length() < 1e-6, "{uv}");
        assert!(uv_of(LAT_LONG, Vec3::Y).0.y.abs() < 1e-6);
        for uv in [Vec2::new(0.1, 0.2), Vec2::new(0.7, 0.9), Vec2::new(0.5, 0.5)] {
            let (d, _) = direction_of(LAT_LONG, uv).unwrap();
            assert!((uv_of(LAT_LONG, d).0 - uv).length() < 1e-5, "round trip {uv}");
        }
    }

    /// A sun's map by its luminance; a constant sky's (one texel, or several all alike)
    /// uniformly.
    #[test]
    fn sampling_density_matches_pdf_by_chi_square() {
        for mapping in [EnvironmentMapping::LatLong, EnvironmentMapping::Probe] {
            let (w, h) = (16, 8);
            let sun = EnvironmentLight::new(w, h, &sun_map(w, h), Vec3::ONE, mapping, rotation());
            assert!(sun.uniform.is_none());
            sampling_matches_pdf(&sun, mapping);
            let sky = Vec3::new(0.25, 0.5, 1.0);
            for (w, h) in [(1, 1), (4, 2)] {
                let constant =
                    EnvironmentLight::new(w, h, &vec![sky; w * h], Vec3::ONE, mapping, rotation());
                assert_eq!(constant.uniform, Some(sky));
                assert_eq!(constant.pdf(Vec3::new(0.3, -2.0, 0.1)), UNIFORM_PDF);
                sampling_matches_pdf(&constant, mapping);
            }
        }
    }

    fn sampling_matches_pdf(light: &EnvironmentLight, mapping: EnvironmentMapping) {
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
        // A probe's rim cells reach past the disc: draws landing there return `None` (they
        // carry no light, so the estimate stays unbiased), and the last bin counts them.
        let total: f64 = expected.iter().sum();
        assert!(total <= 1.0 + 1e-3 && total > 0.97, "the pdf integrates to {total}");
        expected.push((1.0 - total).max(0.0));
        let mut rng = SplitMix64(7);
        let samples = 300_000u64;
        let mut counts = vec![0u64; bands * sectors + 1];
        for _ in 0..samples {
            let Some(s) = light.sample(Vec2::new(rng.unit(), rng.unit())) else {
                counts[bands * sectors] += 1;
                continue;
            };
            assert!((s.wi.length() - 1.0).abs() < 1e-5);
            let pdf = light.pdf(s.wi);
            assert!((pdf - s.pdf).abs() <= 1e-3 * s.pdf, "pdf {pdf} vs sampled {}", s.pdf);
            assert_eq!(light.radiance(s.wi), s.radiance);
            counts[cell_of(rotation() * s.wi)] += 1;
        }
        assert_fits(&format!("environment sampling ({mapping:?})"), &counts, &expected, samples);
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
        let light = EnvironmentLight::new(w, h, &sun_map(w, h), Vec3::ONE, LAT_LONG, rotation());
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
        let light =
            EnvironmentLight::new(2, 1, &[Vec3::ZERO; 2], Vec3::ONE, LAT_LONG, Mat3::IDENTITY);
        assert!(!light.is_lit());
        assert!(light.sample(Vec2::new(0.3, 0.3)).is_none());
        assert_eq!(light.pdf(Vec3::X), 0.0);
        let light = EnvironmentLight::new(
            1,
            1,
            &[Vec3::new(f32::NAN, 1.0, 1.0)],
            Vec3::ONE,
            LAT_LONG,
            Mat3::IDENTITY,
        );
        assert_eq!(light.radiance(Vec3::Y), Vec3::ZERO);
    }
}
