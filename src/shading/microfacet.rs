//! A microfacet distribution of roughness αx along the local frame's tangent (+X) and αy
//! along its bitangent (+Y), normal +Z: GGX or Beckmann, each sampled by its visible
//! normals (`beckmann` for Beckmann's). Shadowing is Smith's,
//! height-correlated; Beckmann's Λ is the rational fit Mitsuba and pbrt use (under 0.35 %
//! from the exact erf form). Isotropic roughness keeps the isotropic arithmetic.

use super::{beckmann, ggx};
use crate::scene::{Distribution, Shadowing};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet {
    pub distribution: Distribution,
    pub alpha_x: f32,
    pub alpha_y: f32,
}

impl Microfacet {
    pub fn isotropic(distribution: Distribution, alpha: f32) -> Self {
        Microfacet { distribution, alpha_x: alpha, alpha_y: alpha }
    }

    /// Density of normals `h` (unit, h.z > 0), per unit projected area.
    pub fn d(&self, h: Vec3) -> f32 {
        let (ax, ay) = (self.alpha_x, self.alpha_y);
        match self.distribution {
            Distribution::Ggx => ggx::d(h, ax, ay),
            Distribution::Beckmann => {
                let cos2 = h.z * h.z;
                if cos2 <= 0.0 {
                    return 0.0;
                }
                if ax == ay {
                    let tan2 = (1.0 - cos2).max(0.0) / cos2;
                    let a2 = ax * ax;
                    return (-tan2 / a2).exp() / (PI * a2 * cos2 * cos2);
                }
                let (x, y) = (h.x / ax, h.y / ay);
                (-(x * x + y * y) / cos2).exp() / (PI * ax * ay * cos2 * cos2)
            }
        }
    }

    fn lambda(&self, w: Vec3) -> f32 {
        let (ax, ay) = (self.alpha_x, self.alpha_y);
        match self.distribution {
            Distribution::Ggx => ggx::lambda(w, ax, ay),
            Distribution::Beckmann => {
                let cos2 = w.z * w.z;
                let sin2 = (1.0 - cos2).max(0.0);
                if sin2 == 0.0 {
                    return 0.0;
                }
                if cos2 == 0.0 {
                    return f32::INFINITY;
                }
                // 1 / (α(w) tan θ), with α(w) the roughness projected on w's azimuth.
                let a = if ax == ay {
                    (cos2 / sin2).sqrt() / ax
                } else {
                    let projected = (ax * ax * w.x * w.x + ay * ay * w.y * w.y).sqrt();
                    if projected == 0.0 {
                        return 0.0;
                    }
                    w.z.abs() / projected
                };
                if a >= 1.6 {
                    return 0.0;
                }
                (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a)
            }
        }
    }

    /// Smith's masking of direction `w` (either side).
    pub fn g1(&self, w: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// Height-correlated masking-shadowing of the pair.
    pub fn g2(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self.distribution {
            Distribution::Ggx => ggx::g2(wo, wi, self.alpha_x, self.alpha_y),
            Distribution::Beckmann => 1.0 / (1.0 + self.lambda(wo) + self.lambda(wi)),
        }
    }

    /// A normal drawn for the view `wo` (wo.z > 0).
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Vec3 {
        let (ax, ay) = (self.alpha_x, self.alpha_y);
        match self.distribution {
            Distribution::Ggx => ggx::sample_visible_normal(wo, ax, ay, u),
            Distribution::Beckmann => beckmann::sample_visible_normal(wo, ax, ay, u),
        }
    }

    /// Density of `sample` drawing `h` for the view `wo`.
    pub fn pdf(&self, wo: Vec3, h: Vec3) -> f32 {
        match self.distribution {
            Distribution::Ggx => {
                let wo_h = wo.dot(h);
                if wo.z <= 0.0 || wo_h <= 0.0 {
                    return 0.0;
                }
                self.g1(wo) * self.d(h) * wo_h / wo.z
            }
            // With the exact Λ the sampler draws by (the rational fit is 0.35 % off).
            Distribution::Beckmann => {
                let wo_h = wo.dot(h);
                if wo.z <= 0.0 || wo_h <= 0.0 {
                    return 0.0;
                }
                let projected = (self.alpha_x * self.alpha_x * wo.x * wo.x
                    + self.alpha_y * self.alpha_y * wo.y * wo.y)
                    .sqrt();
                let g1 = match projected {
                    0.0 => 1.0,
                    p => 1.0 / (1.0 + beckmann::lambda(f64::from(wo.z / p))) as f32,
                };
                g1 * self.d(h) * wo_h / wo.z
            }
        }
    }

    /// `d(h) · G₂(wo, wi)` (as `shadowing` has it) and `pdf_reflect(wo, h)`, sharing what
    /// they have in common.
    pub fn reflect_terms(&self, wo: Vec3, wi: Vec3, h: Vec3, shadowing: Shadowing) -> (f32, f32) {
        let separable = shadowing == Shadowing::Separable;
        match (self.distribution, separable) {
            (Distribution::Ggx, _) => {
                ggx::reflect_terms(wo, wi, h, (self.alpha_x, self.alpha_y), separable)
            }
            (Distribution::Beckmann, false) => {
                (self.d(h) * self.g2(wo, wi), self.pdf_reflect(wo, h))
            }
            (Distribution::Beckmann, true) => {
                (self.d(h) * (self.g1(wo) * self.g1(wi)), self.pdf_reflect(wo, h))
            }
        }
    }

    /// Density of the mirror direction about a sampled `h`, seen from `wo`.
    pub fn pdf_reflect(&self, wo: Vec3, h: Vec3) -> f32 {
        match self.distribution {
            Distribution::Ggx => ggx::pdf_reflect(wo, h, self.alpha_x, self.alpha_y),
            Distribution::Beckmann => {
                let wo_h = wo.dot(h);
                if wo.z <= 0.0 || wo_h <= 0.0 {
                    return 0.0;
                }
                self.pdf(wo, h) / (4.0 * wo_h)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Isotropic, and anisotropic both ways round.
    fn distributions() -> Vec<Microfacet> {
        [Distribution::Ggx, Distribution::Beckmann]
            .into_iter()
            .flat_map(|distribution| {
                [(0.1, 0.1), (0.5, 0.5), (0.3, 0.05), (0.08, 0.5)]
                    .map(|(alpha_x, alpha_y)| Microfacet { distribution, alpha_x, alpha_y })
            })
            .collect()
    }

    /// Integrates over the hemisphere by a fine midpoint rule in (cos θ, φ).
    fn hemisphere(f: impl Fn(Vec3) -> f64) -> f64 {
        let n = 2000;
        let mut sum = 0.0;
        for i in 0..n {
            let cos = (i as f64 + 0.5) / n as f64;
            let sin = (1.0 - cos * cos).sqrt();
            for j in 0..64 {
                let phi = (j as f64 + 0.5) / 64.0 * std::f64::consts::TAU;
                let w = Vec3::new((sin * phi.cos()) as f32, (sin * phi.sin()) as f32, cos as f32);
                sum += f(w);
            }
        }
        sum * std::f64::consts::TAU / (n as f64 * 64.0)
    }

    /// Separable shadowing is G₁(wo)·G₁(wi), height-correlated 1 / (1 + Λo + Λi): the
    /// product is never the larger (1 + Λo + Λi ≤ (1 + Λo)(1 + Λi)), and both densities are
    /// the same.
    #[test]
    fn separable_shadowing_is_the_product_of_the_two_g1() {
        // Grazing, where Λ is not negligible (Beckmann's fit is 0 above a = 1.6).
        let (wo, wi) = (Vec3::new(0.96, 0.0, 0.28), Vec3::new(-0.9, 0.3, 0.3162).normalize());
        let h = (wo + wi).normalize();
        let mut checked = 0;
        for m in distributions() {
            if m.d(h) < 1e-6 {
                // A narrow lobe far from h: D underflows towards subnormals.
                continue;
            }
            checked += 1;
            let (correlated, pdf) = m.reflect_terms(wo, wi, h, Shadowing::HeightCorrelated);
            let (separable, same_pdf) = m.reflect_terms(wo, wi, h, Shadowing::Separable);
            let product = m.d(h) * m.g1(wo) * m.g1(wi);
            assert!((separable - product).abs() <= 1e-5 * product, "{m:?}: {separable}, {product}");
            assert!((correlated - m.d(h) * m.g2(wo, wi)).abs() <= 1e-5 * correlated, "{m:?}");
            assert!(separable <= correlated, "{m:?}: {separable} > {correlated}");
            if m.alpha_x.min(m.alpha_y) >= 0.3 {
                // Where Λ is not negligible, strictly darker.
                assert!(separable < 0.999 * correlated, "{m:?}: {separable}, {correlated}");
            }
            assert_eq!(pdf, same_pdf);
        }
        assert!(checked >= 4, "{checked}");
    }

    #[test]
    fn projected_normal_area_is_one() {
        for m in distributions() {
            let area = hemisphere(|h| (m.d(h) * h.z) as f64);
            assert!((area - 1.0).abs() < 2e-3, "{m:?}: ∫D cos = {area}");
        }
    }

    #[test]
    fn visible_normals_project_to_the_view() {
        // ∫ G1(wo) max(0, wo·h) D(h) dh = cos θo: the microsurface's projected area seen from
        // wo equals the macrosurface's (Smith's masking is consistent with D).
        for m in distributions() {
            for cos in [0.9f32, 0.5, 0.2] {
                // Off both axes, so that anisotropic roughness is seen at an angle.
                let sin = (1.0 - cos * cos).sqrt();
                let wo = Vec3::new(sin * 0.8, sin * 0.6, cos);
                let seen = hemisphere(|h| (m.g1(wo) * wo.dot(h).max(0.0) * m.d(h)) as f64);
                let tolerance = if m.distribution == Distribution::Beckmann { 5e-3 } else { 2e-3 };
                assert!((seen / cos as f64 - 1.0).abs() < tolerance, "{m:?} cos {cos}: {seen}");
            }
        }
    }

    #[test]
    fn sampled_normals_follow_the_density() {
        // Chi-square of sampled normals against `pdf`, binned in (cos θ, φ).
        let wo = Vec3::new(0.36, 0.48, 0.8);
        let (bins_theta, bins_phi, n) = (16usize, 8usize, 200_000u64);
        for (seed, m) in distributions().into_iter().enumerate() {
            let mut counts = vec![0u64; bins_theta * bins_phi];
            let mut rng = crate::splitmix::SplitMix64(seed as u64);
            for _ in 0..n {
                let h = m.sample(wo, Vec2::new(rng.unit(), rng.unit()));
                let t = ((1.0 - h.z) * bins_theta as f32) as usize;
                let turn = h.y.atan2(h.x).rem_euclid(std::f32::consts::TAU) / std::f32::consts::TAU;
                let p = (turn * bins_phi as f32) as usize;
                counts[t.min(bins_theta - 1) * bins_phi + p.min(bins_phi - 1)] += 1;
            }
            let expected: Vec<f64> = (0..bins_theta * bins_phi)
                .map(|cell| {
                    let (t, p) = (cell / bins_phi, cell % bins_phi);
                    expected_in_bin(&m, wo, t, p, bins_theta, bins_phi)
                })
                .collect();
            crate::sampling::chi_square::assert_fits(&format!("{m:?}"), &counts, &expected, n);
        }
    }

    /// ∫ pdf over the bin (uniform in cos θ and φ), by a midpoint rule.
    fn expected_in_bin(
        m: &Microfacet,
        wo: Vec3,
        t: usize,
        p: usize,
        bins_theta: usize,
        bins_phi: usize,
    ) -> f64 {
        // The bin at the pole holds the peak of the sharpest lobe: integrate it finely.
        let steps = if t == 0 { 256 } else { 24 };
        let mut sum = 0.0;
        for i in 0..steps {
            let z = 1.0 - (t as f64 + (i as f64 + 0.5) / steps as f64) / bins_theta as f64;
            let sin = (1.0 - z * z).max(0.0).sqrt();
            for j in 0..steps {
                let phi = (p as f64 + (j as f64 + 0.5) / steps as f64) / bins_phi as f64
                    * std::f64::consts::TAU;
                let h = Vec3::new((sin * phi.cos()) as f32, (sin * phi.sin()) as f32, z as f32);
                sum += m.pdf(wo, h) as f64;
            }
        }
        sum / (steps * steps) as f64 * std::f64::consts::TAU / (bins_theta * bins_phi) as f64
    }
}
