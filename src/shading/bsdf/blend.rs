//! A mixture of two BSDFs (Mitsuba's `blendbsdf`): `weight` of the second's scattering and
//! the rest of the first's. One part is sampled (chosen with its weight); a smooth sample
//! is then weighted by the whole mixture's value and density, as the light-sampling side
//! evaluates it, so that MIS sees one consistent BSDF.

use super::{Bsdf, BsdfSample};
use glam::{Vec2, Vec3};

#[derive(Clone, Debug)]
pub struct Blend {
    pub(super) parts: [Bsdf; 2],
    /// The second part's share, in [0, 1].
    pub(super) weight: f32,
}

impl Blend {
    fn shares(&self) -> [f32; 2] {
        [1.0 - self.weight, self.weight]
    }

    pub fn has_smooth_lobe(&self) -> bool {
        self.parts.iter().zip(self.shares()).any(|(p, share)| share > 0.0 && p.has_smooth_lobe())
    }

    pub fn transmits(&self) -> bool {
        self.parts.iter().zip(self.shares()).any(|(p, share)| share > 0.0 && p.transmits())
    }

    pub fn albedo_bound(&self, wo: Vec3) -> Vec3 {
        let [a, b] = self.shares();
        a * self.parts[0].albedo_bound(wo) + b * self.parts[1].albedo_bound(wo)
    }

    /// f · |cos θi| and density, both directions in render space.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        let [a, b] = self.shares();
        let (f0, p0) = if a > 0.0 { self.parts[0].eval(wo, wi) } else { (Vec3::ZERO, 0.0) };
        let (f1, p1) = if b > 0.0 { self.parts[1].eval(wo, wi) } else { (Vec3::ZERO, 0.0) };
        (a * f0 + b * f1, a * p0 + b * p1)
    }

    /// Samples the second part where `u_lobe` < `weight` (Mitsuba's choice), else the
    /// first, with `u_lobe` stretched back over [0, 1) for the part's own choices.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let w = self.weight;
        let (chosen, u_lobe) =
            if u_lobe < w { (1, u_lobe / w) } else { (0, (u_lobe - w) / (1.0 - w)) };
        let mut sample = self.parts[chosen].sample(wo, u_lobe.min(1.0 - f32::EPSILON / 2.0), u)?;
        if sample.delta {
            // The delta lobe's share of the mixture is the probability of choosing it: its
            // weight f/pdf is the part's own.
            return Some(sample);
        }
        let (value, pdf) = self.eval(wo, sample.wi);
        if pdf <= 0.0 {
            return None;
        }
        sample.weight = value / pdf;
        sample.pdf = pdf;
        Some(sample)
    }
}
