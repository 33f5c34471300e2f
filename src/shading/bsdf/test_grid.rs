//! The chi-square test the BSDF tests share: sampled directions counted in (θ, φ) cells of
//! the upper hemisphere or the whole sphere, against the density `eval` gives, integrated
//! over each cell; samples the density does not cover (delta lobes, refusals) go to one
//! more cell, whose share is what the density leaves.

use super::Bsdf;
use crate::splitmix::SplitMix64;
use glam::{Vec2, Vec3};
use std::f64::consts::PI;

/// Mean energy of the sample weights for `wo`: the directional albedo ∫ f cos dω (the
/// radiance compression of refraction undone: energy does not carry it).
pub(super) fn energy(bsdf: &Bsdf, wo: Vec3, samples: usize, seed: u64) -> Vec3 {
    let mut rng = SplitMix64(seed);
    let mut total = Vec3::ZERO;
    for _ in 0..samples {
        let u_lobe = rng.unit();
        if let Some(s) = bsdf.sample(wo, u_lobe, Vec2::new(rng.unit(), rng.unit())) {
            total += s.weight * s.eta_scale;
        }
    }
    total / samples as f32
}

pub(super) struct Grid {
    /// π/2 for the upper hemisphere, π for the sphere.
    pub theta_max: f64,
    pub theta_cells: usize,
    pub phi_cells: usize,
    /// Sub-samples per cell side when integrating the density over a cell.
    pub sub: usize,
    /// Delta samples are allowed (counted in the extra cell) or a failure.
    pub delta_allowed: bool,
    pub samples: u64,
}

impl Grid {
    /// The whole sphere in 16 × 16 cells, each integrated on a 64 × 64 grid: fine enough for
    /// the sharpest lobes tested (α 0.05) and for the edge of rough glass's transmission,
    /// where refraction through facets seen edge-on piles directions up.
    pub fn whole_sphere(delta_allowed: bool) -> Grid {
        Grid {
            theta_max: PI,
            theta_cells: 16,
            phi_cells: 16,
            sub: 64,
            delta_allowed,
            samples: 200_000,
        }
    }

    fn cells(&self) -> usize {
        self.theta_cells * self.phi_cells
    }

    fn cell_of(&self, w: Vec3) -> usize {
        let theta = f64::from(w.z.clamp(-1.0, 1.0)).acos();
        let c =
            ((theta / self.theta_max * self.theta_cells as f64) as usize).min(self.theta_cells - 1);
        let phi = f64::from(w.y.atan2(w.x)).rem_euclid(2.0 * PI);
        let p = ((phi / (2.0 * PI) * self.phi_cells as f64) as usize).min(self.phi_cells - 1);
        c * self.phi_cells + p
    }

    /// ∫ pdf dω over each cell (midpoint rule on a sub × sub grid; dω = sin θ dθ dφ).
    fn expected_fractions(&self, bsdf: &Bsdf, wo: Vec3) -> Vec<f64> {
        let dtheta = self.theta_max / (self.theta_cells * self.sub) as f64;
        let dphi = 2.0 * PI / (self.phi_cells * self.sub) as f64;
        (0..self.cells())
            .map(|cell| {
                let (c, p) = (cell / self.phi_cells, cell % self.phi_cells);
                let mut sum = 0.0f64;
                for i in 0..self.sub {
                    let theta = ((c * self.sub + i) as f64 + 0.5) * dtheta;
                    for j in 0..self.sub {
                        let phi = ((p * self.sub + j) as f64 + 0.5) * dphi;
                        let (st, ct) = theta.sin_cos();
                        let wi =
                            Vec3::new((st * phi.cos()) as f32, (st * phi.sin()) as f32, ct as f32);
                        sum += bsdf.eval(wo, wi).1 as f64 * st * dtheta * dphi;
                    }
                }
                sum
            })
            .collect()
    }

    /// Samples `bsdf` for `wo`, checks each smooth sample's density and weight against
    /// `eval`, and the counts against the density by chi-square.
    pub fn test(&self, name: &str, bsdf: &Bsdf, wo: Vec3, seed: u64) {
        let mut rng = SplitMix64(seed);
        let mut counts = vec![0u64; self.cells() + 1];
        for _ in 0..self.samples {
            let u_lobe = rng.unit();
            let u = Vec2::new(rng.unit(), rng.unit());
            match bsdf.sample(wo, u_lobe, u) {
                Some(s) if !s.delta => {
                    assert!(s.pdf > 0.0 && s.weight.is_finite(), "{name}: {s:?}");
                    let (value, pdf) = bsdf.eval(wo, s.wi);
                    assert!((pdf - s.pdf).abs() <= 1e-3 * pdf, "{name}: pdf {} vs {pdf}", s.pdf);
                    let weight = value / pdf;
                    let error = (weight - s.weight).abs().max_element();
                    assert!(error <= 1e-3 * weight.max_element().max(1e-3), "{name}: {s:?}");
                    counts[self.cell_of(s.wi)] += 1;
                }
                Some(s) => {
                    assert!(self.delta_allowed, "{name}: a smooth lobe returned {s:?}");
                    counts[self.cells()] += 1;
                }
                None => counts[self.cells()] += 1,
            }
        }
        let mut expected = self.expected_fractions(bsdf, wo);
        let covered: f64 = expected.iter().sum();
        expected.push((1.0 - covered).max(0.0));
        crate::sampling::chi_square::assert_fits(
            &format!("{name} (∫pdf {covered:.4})"),
            &counts,
            &expected,
            self.samples,
        );
    }
}
