//! Mitsuba 3's `principled` BSDF (Burley 2012, 2015): a diffuse lobe with retro-reflection
//! and fake subsurface, sheen, a GGX specular lobe whose Fresnel blends the dielectric one
//! with Schlick's tinted and metallic ones, a GTR1 clearcoat, and rough specular
//! transmission. Evaluated as Mitsuba evaluates it, in Mitsuba's frame: +Z is the
//! surface's outward normal, so a view from inside has wo.z < 0 and sees only the
//! specular lobes. Lobes are sampled with Mitsuba's probabilities, whose sum does not
//! depend on the sampled facet, so the density `eval` reports is exact.

use super::BsdfSample;
use super::principled_terms::{
    Gtr1, clearcoat_g, diffuse_shape, fresnel, oriented_g1, r0_from_eta, reflect, schlick, sheen,
    tint,
};
use crate::shading::coating::refract;
use crate::shading::microfacet::Microfacet;
use crate::shading::principled::PrincipledParams;
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

#[derive(Clone, Copy, Debug)]
pub struct Principled {
    p: PrincipledParams,
    /// Embray's local frame, whose normal faces the view, is Mitsuba's (whose normal points
    /// outwards): the view is outside, or the material is opaque and two-sided. Else
    /// Mitsuba's is embray's turned over.
    mitsuba_frame: bool,
    specular: Microfacet,
}

impl Principled {
    pub fn new(p: &PrincipledParams, mitsuba_frame: bool) -> Self {
        let specular = super::principled_terms::distribution(p.roughness, p.anisotropic);
        Principled { p: *p, mitsuba_frame, specular }
    }

    pub fn base_color(&self) -> Vec3 {
        self.p.base_color
    }

    /// Some light passes through into the other side.
    pub fn transmits(&self) -> bool {
        self.transmission_weight() > 0.0
    }

    /// The weight of the diffuse lobe (the opaque dielectric part).
    fn diffuse_weight(&self) -> f32 {
        (1.0 - self.p.metallic) * (1.0 - self.p.spec_trans)
    }

    /// The weight of the transmitting dielectric part.
    fn transmission_weight(&self) -> f32 {
        (1.0 - self.p.metallic) * self.p.spec_trans
    }

    /// A local direction in Mitsuba's frame, or back.
    fn oriented(&self, w: Vec3) -> Vec3 {
        if self.mitsuba_frame { w } else { Vec3::new(w.x, w.y, -w.z) }
    }

    /// f · |cos θi| and its density, in the local frame.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        self.eval_oriented(self.oriented(wo), self.oriented(wi))
    }

    /// The specular lobes' probability, and each other lobe's (diffuse, clearcoat), before
    /// they are normalised by their sum.
    fn lobe_rates(&self, outside: bool) -> (f32, f32, f32) {
        let rates = &self.p.rates;
        if !outside {
            return (1.0, 0.0, 0.0);
        }
        let clearcoat =
            if self.p.clearcoat > 0.0 { 0.25 * self.p.clearcoat * rates.clearcoat } else { 0.0 };
        (rates.specular_reflectance, self.diffuse_weight() * rates.diffuse_reflectance, clearcoat)
    }

    /// The share of the specular lobes' probability that reflects, where the dielectric
    /// Fresnel reflectance at the facet is `fresnel`.
    fn reflected_share(&self, outside: bool, fresnel: f32) -> f32 {
        if !self.p.spec_trans_somewhere {
            1.0
        } else if outside {
            1.0 - self.transmission_weight() * (1.0 - fresnel)
        } else {
            fresnel
        }
    }

    fn eval_oriented(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        let p = &self.p;
        let (cos_o, cos_i) = (wo.z, wi.z);
        let reflects = cos_o * cos_i > 0.0;
        let refracts = cos_o * cos_i < 0.0;
        if !reflects && !refracts {
            return (Vec3::ZERO, 0.0);
        }
        let outside = cos_o > 0.0;
        if !outside && self.transmission_weight() <= 0.0 {
            // Nothing gets in, so nothing is seen from inside, and nothing is sampled there
            // (Mitsuba's pdf reports its facets' density all the same).
            return (Vec3::ZERO, 0.0);
        }
        let eta_path = if outside { p.eta } else { 1.0 / p.eta };
        let h = (wo + wi * if reflects { 1.0 } else { eta_path }).normalize_or_zero();
        if h == Vec3::ZERO {
            return (Vec3::ZERO, 0.0);
        }
        let h = if h.z < 0.0 { -h } else { h };
        let (o_h, i_h) = (wo.dot(h), wi.dot(h));
        let f = fresnel(o_h, p.eta);
        // The facet as seen from the view's side.
        let facing = o_h * cos_o.signum() > 0.0;
        let reflect_ok = reflects && facing && i_h * cos_o.signum() > 0.0;
        let refract_ok = refracts && facing && i_h * cos_o.signum() < 0.0;
        let d = self.specular.d(h);
        let g = oriented_g1(&self.specular, wo, h) * oriented_g1(&self.specular, wi, h);
        let (diffuse, transmission) = (self.diffuse_weight(), self.transmission_weight());

        let mut value = Vec3::ZERO;
        if reflect_ok && f > 0.0 {
            let fresnel =
                if outside { self.fresnel_outside(f, o_h) } else { Vec3::splat(transmission * f) };
            value += fresnel * (d * g / (4.0 * cos_o.abs()));
        }
        if refract_ok && transmission > 0.0 && f < 1.0 {
            // Radiance is compressed by 1/η² entering a denser medium, which cancels the
            // η² of the half vector's Jacobian.
            let denom = o_h + eta_path * i_h;
            let t = ((1.0 - f) * d * g * o_h * i_h / (cos_o * denom * denom)).abs();
            value += p.base_color.map(f32::sqrt) * (transmission * t);
        }
        let clearcoat = Gtr1::from_gloss(p.clearcoat_gloss);
        if p.clearcoat > 0.0 && reflect_ok && outside {
            let fresnel = schlick(Vec3::splat(0.04), o_h, p.eta).x;
            let term = fresnel * clearcoat.d(h) * clearcoat_g(wo, wi, h);
            // As Mitsuba has it: no 1/(4 cos θo cos θi), and times cos θi.
            value += Vec3::splat(0.25 * p.clearcoat * term * cos_i.abs());
        }
        if reflects && outside {
            let cos_d = h.dot(wi);
            if diffuse > 0.0 {
                let shape = diffuse_shape(p, cos_o.abs(), cos_i.abs(), cos_d);
                value += p.base_color * (diffuse * cos_i.abs() * FRAC_1_PI * shape);
            }
            // Whether or not the diffuse lobe is on, as Mitsuba's masks say and its vectorised
            // variants do (its scalar ones skip the sheen with the diffuse lobe's block).
            if p.sheen > 0.0 && p.metallic < 1.0 {
                value += sheen(p, cos_d) * ((1.0 - p.metallic) * cos_i.abs());
            }
        }

        let (specular_rate, diffuse_rate, clearcoat_rate) = self.lobe_rates(outside);
        let total = specular_rate + diffuse_rate + clearcoat_rate;
        if !(total > 0.0) {
            return (value, 0.0);
        }
        let reflected = self.reflected_share(outside, f);
        let jacobian = if reflects {
            1.0 / (4.0 * i_h).abs()
        } else {
            let denom = o_h + eta_path * i_h;
            (eta_path * eta_path * i_h / (denom * denom)).abs()
        };
        let facet_pdf = self.specular.pdf(wo * cos_o.signum(), h) * jacobian;
        let mut pdf = 0.0;
        if reflect_ok {
            pdf += specular_rate * reflected * facet_pdf
                + clearcoat_rate * clearcoat.pdf(h) * jacobian;
        }
        if reflects {
            pdf += diffuse_rate * cos_i.abs() * FRAC_1_PI;
        }
        if refract_ok {
            pdf += specular_rate * (1.0 - reflected) * facet_pdf;
        }
        (value, pdf / total)
    }

    /// The Fresnel factor of the specular reflection seen from outside: dielectric, blended
    /// with Schlick's metallic (tinted by the base colour) and `spec_tint` (by its hue)
    /// ones, per channel.
    fn fresnel_outside(&self, dielectric: f32, cos: f32) -> Vec3 {
        let p = &self.p;
        let metal = p.metallic * schlick(p.base_color, cos, p.eta);
        let eta_it = if cos >= 0.0 { p.eta } else { 1.0 / p.eta };
        let tinted = tint(p.base_color) * r0_from_eta(eta_it);
        let tinted = (1.0 - p.metallic) * p.spec_tint * schlick(tinted, cos, p.eta);
        Vec3::splat((1.0 - p.metallic) * (1.0 - p.spec_tint) * dielectric) + metal + tinted
    }

    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let wo = self.oriented(wo);
        let outside = wo.z > 0.0;
        if wo.z == 0.0 || !outside && self.transmission_weight() <= 0.0 {
            return None;
        }
        let (specular_rate, diffuse_rate, clearcoat_rate) = self.lobe_rates(outside);
        let total = specular_rate + diffuse_rate + clearcoat_rate;
        if !(total > 0.0) {
            return None;
        }
        let chosen = u_lobe * total;
        let side = wo.z.signum();
        // A facet's direction must be seen from the view's side and leave on the side the
        // lobe sends it to (Mitsuba's test): others are not in the lobe's density.
        let (wi, transmitted) = if chosen < diffuse_rate {
            (crate::sampling::cosine_hemisphere(u), false)
        } else if chosen < diffuse_rate + clearcoat_rate {
            let m = Gtr1::from_gloss(self.p.clearcoat_gloss).sample(u);
            let wi = reflect(wo, m);
            (wo.dot(m) * side > 0.0 && wi.dot(m) * side > 0.0).then_some((wi, false))?
        } else {
            let m = self.specular.sample(wo * side, u);
            let o_m = wo.dot(m);
            if o_m * side <= 0.0 {
                return None;
            }
            let reflected = self.reflected_share(outside, fresnel(o_m, self.p.eta));
            if (chosen - diffuse_rate - clearcoat_rate) / specular_rate < reflected {
                (reflect(wo, m), false)
            } else {
                let wi = if o_m >= 0.0 {
                    refract(wo, m, self.p.eta)?
                } else {
                    refract(wo, -m, 1.0 / self.p.eta)?
                };
                (wi.dot(m) * side < 0.0).then_some((wi, true))?
            }
        };
        let on_view_side = wi.z * side > 0.0;
        if on_view_side == transmitted || wi.z == 0.0 {
            return None;
        }
        let (value, pdf) = self.eval_oriented(wo, wi);
        if !value.is_finite() || !(pdf > 0.0) {
            return None;
        }
        let sample = BsdfSample::smooth(self.oriented(wi), value, pdf)?;
        let eta_scale = match (transmitted, outside) {
            (false, _) => 1.0,
            (true, true) => self.p.eta * self.p.eta,
            (true, false) => 1.0 / (self.p.eta * self.p.eta),
        };
        Some(BsdfSample { eta_scale, transmitted, ..sample })
    }
}
