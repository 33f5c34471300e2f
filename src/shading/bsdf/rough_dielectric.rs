//! Rough glass (Walter et al. 2007, as Mitsuba's `roughdielectric`): microfacets that
//! reflect by Fresnel and refract the rest, the lobe chosen by Fresnel at the sampled
//! facet. The local frame's normal faces the incoming light's side, so `eta` is the index
//! of the far side over the near one. Radiance refracted into a denser medium is
//! compressed by 1/η² (undone on leaving; `eta_scale` tells roulette).

use super::BsdfSample;
use crate::shading::coating::refract;
use crate::shading::fresnel::fresnel_dielectric;
use crate::shading::microfacet::Microfacet;
use glam::{Vec2, Vec3};

#[derive(Clone, Copy, Debug)]
pub struct RoughDielectric {
    /// Index of the side the light goes into over the side it comes from.
    eta: f32,
    microfacet: Microfacet,
    /// What scales the reflected and the refracted light.
    reflectance: Vec3,
    transmittance: Vec3,
}

impl RoughDielectric {
    /// Glass of index `ior` met from outside (`front_face`) or inside, its reflection and
    /// refraction scaled by `tints`.
    pub fn new(ior: f32, front_face: bool, microfacet: Microfacet, tints: [Vec3; 2]) -> Self {
        let eta = if front_face { ior } else { 1.0 / ior };
        let [reflectance, transmittance] = tints;
        RoughDielectric { eta, microfacet, reflectance, transmittance }
    }

    /// Separable Smith shadowing (Mitsuba's), each direction on its own side of `h`.
    fn shadowing(&self, wo: Vec3, wi: Vec3, h: Vec3) -> f32 {
        let oriented = |w: Vec3| w.dot(h) * w.z > 0.0;
        if !oriented(wo) || !oriented(wi) {
            return 0.0;
        }
        self.microfacet.g1(wo) * self.microfacet.g1(wi)
    }

    /// f · |cos θi| and its density, in the local frame (wo.z > 0).
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if wo.z <= 0.0 || wi.z == 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let eta = self.eta;
        if wi.z > 0.0 {
            let h = (wo + wi).normalize();
            let fresnel = fresnel_dielectric(wo.dot(h), eta);
            let g = self.shadowing(wo, wi, h);
            let value = fresnel * self.microfacet.d(h) * g / (4.0 * wo.z);
            let pdf = fresnel * self.microfacet.pdf_reflect(wo, h);
            return (value * self.reflectance, pdf);
        }
        // The half vector of a refraction, on the near side.
        let h = (wo + eta * wi).normalize();
        let h = if h.z < 0.0 { -h } else { h };
        let (o_h, i_h) = (wo.dot(h), wi.dot(h));
        if o_h <= 0.0 || i_h >= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let fresnel = fresnel_dielectric(o_h, eta);
        let g = self.shadowing(wo, wi, h);
        let denom = o_h + eta * i_h;
        let denom2 = denom * denom;
        let d = self.microfacet.d(h);
        // (1 − F) D G |o·h| |i·h| / (cos θo (o·h + η i·h)²), with the 1/η² of radiance
        // already cancelling the η² of the Jacobian.
        let value = (1.0 - fresnel) * d * g * o_h * (-i_h) / (wo.z * denom2);
        let jacobian = eta * eta * (-i_h) / denom2;
        let pdf = (1.0 - fresnel) * self.microfacet.pdf(wo, h) * jacobian;
        (value * self.transmittance, pdf)
    }

    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let h = self.microfacet.sample(wo, u);
        let o_h = wo.dot(h);
        if o_h <= 0.0 {
            return None;
        }
        let fresnel = fresnel_dielectric(o_h, self.eta);
        let (wi, transmitted) = if u_lobe < fresnel {
            (2.0 * o_h * h - wo, false)
        } else {
            (refract(wo, h, self.eta)?, true)
        };
        if (wi.z < 0.0) != transmitted || wi.z == 0.0 {
            return None;
        }
        let (value, pdf) = self.eval(wo, wi);
        if !value.is_finite() {
            return None;
        }
        let sample = BsdfSample::smooth(wi, value, pdf)?;
        let eta_scale = if transmitted { self.eta * self.eta } else { 1.0 };
        Some(BsdfSample { eta_scale, transmitted, ..sample })
    }
}
