//! A dielectric coating over a Lambertian base (Mitsuba's `plastic` and `roughplastic`):
//! the coating reflects by Fresnel (a mirror, or microfacets), the light it lets in is
//! diffused by the base, reflected inside by the coating over and over (the geometric
//! series 1/(1 − R_int), per channel with `nonlinear`) and leaves through it again, its
//! radiance expanded by 1/η². Lobes are chosen by their expected energy, as Mitsuba does.

use super::BsdfSample;
use crate::shading::coating::Coating;
use crate::shading::fresnel::fresnel_dielectric;
use crate::shading::microfacet::Microfacet;
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

#[derive(Clone, Copy, Debug)]
pub struct Plastic {
    /// The base's reflectance after the internal bounces and the 1/η² of leaving.
    diffuse: Vec3,
    eta: f32,
    /// None: a smooth coating (a delta reflection).
    microfacet: Option<Microfacet>,
    coating: Coating,
    /// The specular lobe's share before Fresnel: s/(d + s), s = 1, d = the base's mean.
    specular_weight: f32,
}

impl Plastic {
    pub fn new(
        base: Vec3,
        eta: f32,
        nonlinear: bool,
        microfacet: Option<Microfacet>,
        coating: Coating,
    ) -> Self {
        let base = base.clamp(Vec3::ZERO, Vec3::ONE);
        let internal = coating.internal_reflectance;
        let kept =
            if nonlinear { Vec3::ONE - base * internal } else { Vec3::splat(1.0 - internal) };
        let diffuse = base / kept / (eta * eta);
        let mean = (base.x + base.y + base.z) / 3.0;
        Plastic { diffuse, eta, microfacet, coating, specular_weight: 1.0 / (mean + 1.0) }
    }

    /// At most what arrives: the coating's reflection plus what it lets in and out.
    pub fn albedo_bound(&self) -> Vec3 {
        Vec3::ONE
    }

    /// Probability of sampling the coating's reflection for a view through which the
    /// coating lets `entering` of the light in.
    fn p_specular(&self, entering: f32) -> f32 {
        let reflected = 1.0 - entering;
        let specular = reflected * self.specular_weight;
        let diffuse = (1.0 - reflected) * (1.0 - self.specular_weight);
        if specular + diffuse > 0.0 { specular / (specular + diffuse) } else { 0.0 }
    }

    /// f · cos θi and its density, in the local frame.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let entering = self.coating.transmittance(wo.z);
        let p_specular = self.p_specular(entering);
        let through = entering * self.coating.transmittance(wi.z);
        let mut value = self.diffuse * (through * wi.z * FRAC_1_PI);
        let mut pdf = (1.0 - p_specular) * wi.z * FRAC_1_PI;
        if let Some(microfacet) = &self.microfacet {
            let h = (wo + wi).normalize();
            let fresnel = fresnel_dielectric(wo.dot(h), self.eta);
            // Mitsuba's shadowing: separable Smith, each side oriented.
            let shadowing = microfacet.g1(wo) * microfacet.g1(wi);
            let facing = wo.dot(h) > 0.0 && wi.dot(h) > 0.0;
            if facing {
                value += Vec3::splat(fresnel * microfacet.d(h) * shadowing / (4.0 * wo.z));
                pdf += p_specular * microfacet.pdf_reflect(wo, h);
            }
        }
        (value, pdf)
    }

    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let p_specular = self.p_specular(self.coating.transmittance(wo.z));
        let wi = if u_lobe < p_specular {
            let Some(microfacet) = &self.microfacet else {
                let fresnel = fresnel_dielectric(wo.z, self.eta);
                return Some(BsdfSample {
                    wi: Vec3::new(-wo.x, -wo.y, wo.z),
                    weight: Vec3::splat(fresnel / p_specular),
                    eta_scale: 1.0,
                    pdf: 0.0,
                    delta: true,
                    transmitted: false,
                    passes: false,
                });
            };
            let h = microfacet.sample(wo, u);
            2.0 * wo.dot(h) * h - wo
        } else {
            crate::sampling::cosine_hemisphere(u)
        };
        let (value, pdf) = self.eval(wo, wi);
        BsdfSample::smooth(wi, value, pdf)
    }
}
