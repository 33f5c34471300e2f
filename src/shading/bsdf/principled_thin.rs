//! Mitsuba 3's `principledthin` BSDF (Burley 2015's thin-surface model): a two-sided sheet
//! without interior. Its diffuse part (retro-reflection, fake subsurface, sheen) reflects
//! `1 − diff_trans` and scatters the rest through as a Lambertian; its specular part
//! (`spec_trans` of it) reflects by GGX with tinted Fresnel and lets the rest through
//! unbent, by a GGX lobe mirrored to the other side whose roughness is scaled by η.
//! Symmetric: evaluated as seen from the side of the view.

use super::BsdfSample;
use super::principled_terms::{
    diffuse_shape, distribution, fresnel, oriented_g1, r0_from_eta, reflect, schlick, sheen, tint,
};
use crate::shading::microfacet::Microfacet;
use crate::shading::principled::PrincipledParams;
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

#[derive(Clone, Copy, Debug)]
pub struct PrincipledThin {
    p: PrincipledParams,
    reflection: Microfacet,
    /// The mirrored lobe that passes through, roughened by η (Burley 2015, figure 15).
    transmission: Microfacet,
}

/// The lobes' sampling probabilities, normalised.
struct LobeProbabilities {
    specular_reflection: f32,
    specular_transmission: f32,
    diffuse_reflection: f32,
    diffuse_transmission: f32,
}

impl PrincipledThin {
    pub fn new(p: &PrincipledParams) -> Self {
        let reflection = distribution(p.roughness, p.anisotropic);
        let scaled = (0.65 * p.eta - 0.35) * p.roughness;
        let transmission = distribution(scaled, p.anisotropic);
        PrincipledThin { p: *p, reflection, transmission }
    }

    pub fn base_color(&self) -> Vec3 {
        self.p.base_color
    }

    pub fn transmits(&self) -> bool {
        self.p.spec_trans > 0.0 || self.p.diff_trans > 0.0
    }

    fn probabilities(&self) -> Option<LobeProbabilities> {
        let (p, rates) = (&self.p, &self.p.rates);
        let (specular, diffuse) = (p.spec_trans, 1.0 - p.spec_trans);
        let specular_reflection = specular * rates.specular_reflectance / 2.0;
        let specular_transmission = specular * rates.specular_transmittance / 2.0;
        let diffuse_reflection = diffuse * (1.0 - p.diff_trans) * rates.diffuse_reflectance;
        let diffuse_transmission = diffuse * p.diff_trans * rates.diffuse_transmittance;
        let total =
            specular_reflection + specular_transmission + diffuse_reflection + diffuse_transmission;
        (total > 0.0).then(|| LobeProbabilities {
            specular_reflection: specular_reflection / total,
            specular_transmission: specular_transmission / total,
            diffuse_reflection: diffuse_reflection / total,
            diffuse_transmission: diffuse_transmission / total,
        })
    }

    /// f · |cos θi| and its density, in the local frame.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if wo.z == 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        // Seen from the view's side.
        let side = wo.z.signum();
        let (wo, wi) = (wo * side, wi * side);
        let p = &self.p;
        let reflects = wi.z > 0.0;
        let refracts = wi.z < 0.0;
        // Light passing through is the reflection about a facet mirrored to the other side.
        let mirrored = Vec3::new(wi.x, wi.y, wi.z.abs());
        let h = (wo + mirrored).normalize_or_zero();
        let (o_h, i_h) = (wo.dot(h), wi.dot(h));
        let specular_ok = p.spec_trans > 0.0 && h != Vec3::ZERO && o_h > 0.0;
        let reflect_ok = specular_ok && reflects && i_h > 0.0;
        let refract_ok = specular_ok && refracts && i_h < 0.0;
        let (cos_o, cos_i) = (wo.z, wi.z);
        let diffuse = (1.0 - p.spec_trans) * FRAC_1_PI;

        let mut value = Vec3::ZERO;
        let f = fresnel(o_h, p.eta);
        if reflect_ok {
            let tinted = schlick(tint(p.base_color) * r0_from_eta(p.eta), o_h, p.eta);
            let fresnel = Vec3::splat(f) + (tinted - Vec3::splat(f)) * p.spec_tint;
            let m = &self.reflection;
            let dg = m.d(h) * oriented_g1(m, wo, h) * oriented_g1(m, wi, h);
            value += fresnel * (p.spec_trans * dg / (4.0 * cos_o));
        }
        if refract_ok {
            let m = &self.transmission;
            let dg = m.d(h) * oriented_g1(m, wo, h) * oriented_g1(m, wi, h);
            value += p.base_color * (p.spec_trans * (1.0 - f) * dg / (4.0 * cos_o));
        }
        if reflects && p.spec_trans < 1.0 && p.diff_trans < 1.0 {
            let cos_d = h.dot(wi);
            let shape = diffuse_shape(p, cos_o, cos_i, cos_d);
            let kept = (1.0 - p.spec_trans) * (1.0 - p.diff_trans) * cos_i;
            value += p.base_color * (kept * FRAC_1_PI * shape);
            if p.sheen > 0.0 {
                value += sheen(p, cos_d) * kept;
            }
        }
        if refracts && p.spec_trans < 1.0 && p.diff_trans > 0.0 {
            value += p.base_color * (diffuse * p.diff_trans * -cos_i);
        }

        let Some(prob) = self.probabilities() else { return (value, 0.0) };
        let jacobian = 1.0 / (4.0 * mirrored.dot(h)).abs();
        let mut pdf = 0.0;
        if reflect_ok {
            pdf += prob.specular_reflection * self.reflection.pdf(wo, h) * jacobian;
        }
        if refract_ok {
            pdf += prob.specular_transmission * self.transmission.pdf(wo, h) * jacobian;
        }
        if reflects {
            pdf += prob.diffuse_reflection * cos_i * FRAC_1_PI;
        }
        if refracts {
            pdf += prob.diffuse_transmission * -cos_i * FRAC_1_PI;
        }
        (value, pdf)
    }

    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let side = wo.z.signum();
        let view = wo * side;
        let prob = self.probabilities()?;
        let specular = prob.specular_reflection + prob.specular_transmission;
        let (wi, transmitted) = if u_lobe < prob.specular_reflection {
            let m = self.reflection.sample(view, u);
            let wi = reflect(view, m);
            (view.dot(m) > 0.0 && wi.dot(m) > 0.0).then_some((wi, false))?
        } else if u_lobe < specular {
            let m = self.transmission.sample(view, u);
            let r = reflect(view, m);
            let wi = Vec3::new(r.x, r.y, -r.z);
            (view.dot(m) > 0.0 && wi.dot(m) < 0.0).then_some((wi, true))?
        } else if u_lobe < specular + prob.diffuse_reflection {
            (crate::sampling::cosine_hemisphere(u), false)
        } else {
            (-crate::sampling::cosine_hemisphere(u), true)
        };
        if (wi.z < 0.0) != transmitted || wi.z == 0.0 {
            return None;
        }
        let wi = wi * side;
        let (value, pdf) = self.eval(wo, wi);
        if !value.is_finite() || !(pdf > 0.0) {
            return None;
        }
        let sample = BsdfSample::smooth(wi, value, pdf)?;
        Some(BsdfSample { transmitted, ..sample })
    }
}
