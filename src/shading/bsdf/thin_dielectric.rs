//! A thin sheet of glass (Mitsuba's `thindielectric`): its two faces and every internal
//! reflection between them reflect R' = R + T²R / (1 − R²) = 2R / (1 + R) of the light
//! (R the Fresnel reflectance of one face), and the rest passes straight through, unbent
//! and without entering a medium. Both are delta lobes, chosen by R'; `reflectance` and
//! `transmittance` scale them. Symmetric: the same from either side.

use super::BsdfSample;
use crate::shading::fresnel::fresnel_dielectric;
use glam::Vec3;

#[derive(Clone, Copy, Debug)]
pub struct ThinDielectric {
    /// The sheet's index over the index around it.
    ior: f32,
    reflectance: Vec3,
    transmittance: Vec3,
}

impl ThinDielectric {
    pub fn new(ior: f32, reflectance: Vec3, transmittance: Vec3) -> Self {
        ThinDielectric { ior, reflectance, transmittance }
    }

    /// R' of a view at cosine `cos` (either side).
    fn reflected_fraction(&self, cos: f32) -> f32 {
        let r = fresnel_dielectric(cos.abs(), self.ior);
        2.0 * r / (1.0 + r)
    }

    /// What leaves of the light arriving from local `wo`, per channel.
    pub fn albedo(&self, wo: Vec3) -> Vec3 {
        let r = self.reflected_fraction(wo.z);
        r * self.reflectance + (1.0 - r) * self.transmittance
    }

    /// Reflection with probability R', else straight on (local directions).
    pub fn sample(&self, wo: Vec3, u_lobe: f32) -> BsdfSample {
        let reflected = u_lobe < self.reflected_fraction(wo.z);
        BsdfSample {
            wi: if reflected { Vec3::new(-wo.x, -wo.y, wo.z) } else { -wo },
            weight: if reflected { self.reflectance } else { self.transmittance },
            eta_scale: 1.0,
            pdf: 0.0,
            delta: true,
            transmitted: !reflected,
            // No medium is entered: the light goes on as beside the sheet.
            passes: !reflected,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reflected_fraction_sums_the_internal_reflections() {
        let sheet = ThinDielectric::new(1.5, Vec3::ONE, Vec3::ONE);
        // At normal incidence R = ((1.5 − 1) / (1.5 + 1))² = 0.04.
        let r = 0.04_f32;
        let series: f32 = r + (0..50).map(|k| (1.0 - r).powi(2) * r.powi(2 * k + 1)).sum::<f32>();
        assert!((sheet.reflected_fraction(1.0) - series).abs() < 1e-6);
        assert!((sheet.reflected_fraction(-1.0) - 2.0 * r / (1.0 + r)).abs() < 1e-6);
        // Grazing: everything is reflected.
        assert!(sheet.reflected_fraction(1e-6) > 0.999);
    }

    #[test]
    fn lobes_are_chosen_by_the_reflected_fraction() {
        let sheet = ThinDielectric::new(1.5, Vec3::splat(0.5), Vec3::new(0.2, 0.4, 0.6));
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let r = sheet.reflected_fraction(0.8);
        let n = 10_000;
        let mut mean = Vec3::ZERO;
        for i in 0..n {
            let s = sheet.sample(wo, (i as f32 + 0.5) / n as f32);
            if s.transmitted {
                assert!(s.wi == -wo && s.passes && s.delta);
            } else {
                assert!(s.wi == Vec3::new(-0.6, 0.0, 0.8) && !s.passes);
            }
            mean += s.weight / n as f32;
        }
        // The estimator's mean is the albedo: R'·reflectance + (1 − R')·transmittance.
        assert!((mean - sheet.albedo(wo)).abs().max_element() < 2e-4, "{mean} vs {r}");
    }
}
