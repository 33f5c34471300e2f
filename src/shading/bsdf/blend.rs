//! A mixture of BSDFs (Mitsuba's `blendbsdf`, blends of blends flattened into one): each
//! part scatters its share of the light. One part is sampled (chosen with its share); a
//! smooth sample is then weighted by the whole mixture's value and density, as the
//! light-sampling side evaluates it, so that MIS sees one consistent BSDF.

use super::{Bsdf, BsdfSample, Scatter};
use glam::{Vec2, Vec3};

#[derive(Clone, Debug)]
pub struct Blend {
    /// Each part's share (summing to 1) and the part, never itself a blend.
    parts: Vec<(f32, Bsdf)>,
}

impl Blend {
    /// `weight` of `second` and the rest of `first`; a part that is a blend gives its own
    /// parts, their shares scaled (and its mask's opacity folded into theirs: a mask over a
    /// mixture is the mixture of the masked parts).
    pub fn new(first: Bsdf, second: Bsdf, weight: f32) -> Self {
        let mut parts = Vec::with_capacity(2);
        for (share, part) in [(1.0 - weight, first), (weight, second)] {
            match part.scatter {
                Scatter::Blend(inner) => {
                    for (inner_share, mut leaf) in inner.parts {
                        leaf.opacity *= part.opacity;
                        parts.push((share * inner_share, leaf));
                    }
                }
                _ => parts.push((share, part)),
            }
        }
        Blend { parts }
    }

    fn weighted(&self) -> impl Iterator<Item = &(f32, Bsdf)> {
        self.parts.iter().filter(|(share, _)| *share > 0.0)
    }

    // Rare: kept out of the common kinds' inlined code.
    #[cold]
    #[inline(never)]
    pub fn has_smooth_lobe(&self) -> bool {
        self.weighted().any(|(_, p)| p.has_smooth_lobe_at::<true>())
    }

    // Rare: kept out of the common kinds' inlined code.
    #[cold]
    #[inline(never)]
    pub fn transmits(&self) -> bool {
        self.weighted().any(|(_, p)| p.transmits_at::<true>())
    }

    // Rare: kept out of the common kinds' inlined code.
    #[cold]
    #[inline(never)]
    pub fn albedo_bound(&self, wo: Vec3) -> Vec3 {
        self.weighted().map(|(share, p)| *share * p.albedo_bound_at::<true>(wo)).sum()
    }

    /// f · |cos θi| and density, both directions in render space.
    // Rare: kept out of the common kinds' inlined code.
    #[cold]
    #[inline(never)]
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        self.weighted().fold((Vec3::ZERO, 0.0), |(value, pdf), (share, p)| {
            let (f, p) = p.eval_at::<true>(wo, wi);
            (value + *share * f, pdf + *share * p)
        })
    }

    /// Samples the part whose share holds `u_lobe` (the second of two where `u_lobe` <
    /// its weight, Mitsuba's choice), `u_lobe` stretched back over [0, 1) for the part's own
    /// choices.
    // Rare: kept out of the common kinds' inlined code.
    #[cold]
    #[inline(never)]
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        // Mitsuba's order: the last part first.
        let mut start = 0.0;
        let mut chosen = None;
        for (share, part) in self.parts.iter().rev() {
            if *share > 0.0 && u_lobe < start + share {
                chosen = Some(((u_lobe - start) / share, part));
                break;
            }
            start += share;
        }
        let (u_part, part) = match chosen {
            Some(found) => found,
            // Rounding left u_lobe just past the last share: the first part with one.
            None => (0.0, &self.weighted().next()?.1),
        };
        let mut sample = part.sample_at::<true>(wo, u_part.min(1.0 - f32::EPSILON / 2.0), u)?;
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
