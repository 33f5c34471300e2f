//! The mixture of lobes most materials are: a Lambertian lobe plus at most one specular lobe (mirror,
//! conductor with Fresnel, or glass), GGX microfacets for rough mirrors and metals, plus the
//! specular term of a course material's reflectance model (`phong.specular` with its
//! `CourseBrdf`), which the course adds on top of the rest, glass included (the rest then
//! gives up what the lobe may take, so that no material reflects more than it receives).
//! Directions are in render space; `frame` maps the local shading frame (normal = +Z) to it.

use super::BsdfSample;
use super::coupling::{Coupling, Energy};
use crate::color::luminance;
use crate::scene::{CourseBrdf, Shadowing, Specular};
use crate::shading::course_brdf::{CourseTerms, cos_weighted};
use crate::shading::course_lobe;
use crate::shading::fresnel::{fresnel_conductor, fresnel_dielectric};
use crate::shading::material::Material;
use crate::shading::microfacet::Microfacet;
use glam::{Mat3, Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// The most the Lambertian part `diffuse` and the specular lobe reflect or transmit
/// together, per channel (Fresnel ≤ 1; glass passes everything on).
fn rest_albedo(diffuse: Vec3, specular: Specular) -> Vec3 {
    diffuse
        + match specular {
            // A plastic is not a mixture (`plastic`).
            Specular::None | Specular::Plastic { .. } => Vec3::ZERO,
            Specular::Mirror { reflectance } | Specular::Conductor { reflectance, .. } => {
                reflectance.clamp(Vec3::ZERO, Vec3::ONE)
            }
            Specular::Dielectric { .. } | Specular::ThinDielectric { .. } => Vec3::ONE,
        }
}

/// Lambertian + one specular lobe + the course's lobe, at one shading point.
#[derive(Clone, Copy, Debug)]
pub struct Mixture {
    /// Local (tangent, bitangent, normal) → render space.
    frame: Mat3,
    /// Lambertian reflectance, after the energy coupling of `Bsdf::new`.
    diffuse: Vec3,
    specular: Specular,
    /// How the course's lobe and the other lobes share what arrives (`coupling`).
    coupling: Option<Coupling>,
    microfacet: Microfacet,
    shadowing: Shadowing,
    delta_specular: bool,
    /// Whether the incoming ray arrived on the side the surface normal points to.
    front_face: bool,
    /// Probability of choosing the specular lobe (among the lobes other than `course`).
    p_specular: f32,
    /// The course model's specular term, sampled by its lobe (`course_lobe`) with
    /// probability `p_course`.
    pub(super) course: Option<(CourseBrdf, CourseTerms)>,
    p_course: f32,
}

impl Mixture {
    /// The mixture of `material` with Lambertian reflectance `albedo` (its texture's value
    /// here), the course model's specular reflectance `course_specular` (a
    /// `specular_texture`'s value, or `phong.specular`) and the `energy` model.
    pub fn with_reflectances(
        material: &Material,
        albedo: Vec3,
        course_specular: Vec3,
        microfacet: Microfacet,
        frame: Mat3,
        front_face: bool,
        energy: Energy,
    ) -> Self {
        let conserving = energy == Energy::Conserving;
        let albedo = energy.lambertian(albedo);
        let diffuse = match material.specular {
            Specular::None | Specular::Plastic { .. } => albedo,
            Specular::Mirror { reflectance } | Specular::Conductor { reflectance, .. } => {
                if conserving {
                    albedo * (Vec3::ONE - reflectance.clamp(Vec3::ZERO, Vec3::ONE))
                } else {
                    albedo
                }
            }
            Specular::Dielectric { .. } | Specular::ThinDielectric { .. } => Vec3::ZERO,
        };
        let course_lobe = material
            .phong
            .as_ref()
            .filter(|_| course_specular.max_element() > 0.0 && course_specular.is_finite());
        let coupling = course_lobe.filter(|_| conserving).map(|p| {
            // Tabulated once per material (`Material::with_phong`); a material built
            // without it pays for the table here.
            let albedo = material
                .course_lobe_albedo
                .unwrap_or_else(|| course_lobe::LobeAlbedo::new(&p.brdf, p.exponent));
            let rest = rest_albedo(diffuse, material.specular);
            Coupling::new(rest, course_specular.max(Vec3::ZERO), albedo)
        });
        let specular_weight = match material.specular {
            Specular::None | Specular::Plastic { .. } => 0.0,
            Specular::Mirror { reflectance } => luminance(reflectance),
            Specular::Conductor { eta, k, reflectance } => {
                luminance(fresnel_conductor(1.0, eta, k) * reflectance)
            }
            Specular::Dielectric { .. } | Specular::ThinDielectric { .. } => f32::INFINITY,
        };
        let diffuse_weight = luminance(diffuse);
        let p_specular = if specular_weight.is_infinite() {
            1.0
        } else if specular_weight + diffuse_weight > 0.0 {
            specular_weight / (specular_weight + diffuse_weight)
        } else {
            0.0
        };
        let course = course_lobe.map(|p| {
            let specular = coupling.map_or(course_specular.max(Vec3::ZERO), |c| c.ks());
            (p.brdf, CourseTerms { diffuse: Vec3::ZERO, specular, exponent: p.exponent })
        });
        let p_course = match &course {
            None => 0.0,
            Some((_, terms)) => {
                let others = if specular_weight.is_infinite() {
                    1.0
                } else {
                    (specular_weight + diffuse_weight).min(1.0)
                };
                let weight = luminance(terms.specular).max(1e-3);
                weight / (weight + others)
            }
        };
        Mixture {
            frame,
            diffuse,
            specular: material.specular,
            coupling,
            microfacet,
            shadowing: material.shadowing,
            delta_specular: material.specular_is_delta(),
            front_face,
            p_specular,
            course,
            p_course,
        }
    }

    /// True if light sampling can contribute (some lobe is not a delta distribution).
    pub fn has_smooth_lobe(&self) -> bool {
        self.p_course > 0.0 || self.p_specular < 1.0 || !self.delta_specular
    }

    fn local_from_render(&self, w: Vec3) -> Vec3 {
        self.frame.transpose() * w
    }

    fn specular_tint(&self, cos: f32) -> Vec3 {
        match self.specular {
            Specular::Mirror { reflectance } => reflectance,
            Specular::Conductor { eta, k, reflectance } => {
                fresnel_conductor(cos, eta, k) * reflectance
            }
            _ => Vec3::ZERO,
        }
    }

    /// The factor on the lobes other than the course's for a view at `cos_o`
    /// (`coupling`).
    fn rest_scale(&self, cos_o: f32) -> Vec3 {
        self.coupling.as_ref().map_or(Vec3::ONE, |c| c.rest_scale(cos_o))
    }

    /// An upper bound of the fraction of energy arriving from `wo` (render space) that this
    /// BSDF reflects or transmits, per channel: at most 1 by construction.
    pub fn albedo_bound(&self, wo: Vec3) -> Vec3 {
        let cos_o = self.local_from_render(wo).z;
        let rest = rest_albedo(self.diffuse, self.specular);
        self.coupling.as_ref().map_or(rest, |c| c.total_albedo(cos_o))
    }

    /// f · |cos θi| and the density of sampling `wi`, for the non-delta lobes.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        self.eval_local(self.local_from_render(wo), self.local_from_render(wi))
    }

    /// `eval` of directions in the local frame.
    fn eval_local(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let p_diffuse = 1.0 - self.p_specular;
        let rest_scale = self.rest_scale(wo.z);
        let mut value = self.diffuse * rest_scale * FRAC_1_PI * wi.z;
        let mut pdf = p_diffuse * wi.z * FRAC_1_PI;
        if self.p_specular > 0.0 && !self.delta_specular {
            let h = (wo + wi).normalize();
            let (d_g2, pdf_reflect) = self.microfacet.reflect_terms(wo, wi, h, self.shadowing);
            let f = self.specular_tint(wo.dot(h)) * rest_scale;
            value += f * (d_g2 / (4.0 * wo.z));
            pdf += self.p_specular * pdf_reflect;
        }
        if let Some((brdf, terms)) = &self.course {
            value += cos_weighted(brdf, terms, Vec3::Z, wi, wo);
            let lobe = course_lobe::pdf(brdf, terms.exponent, wo, wi);
            pdf = self.p_course * lobe + (1.0 - self.p_course) * pdf;
        }
        (value, pdf)
    }

    /// Samples an incident direction for outgoing `wo` (both render space).
    pub fn sample(&self, wo_render: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let wo = self.local_from_render(wo_render);
        if wo.z <= 0.0 {
            return None;
        }
        if let (Some((brdf, terms)), true) = (&self.course, u_lobe < self.p_course) {
            let wi = course_lobe::sample(brdf, terms.exponent, wo, u)?;
            return self.mixture_sample(wo, wi);
        }
        // The rest of [0, 1) chooses among the other lobes; a delta lobe's weight counts the
        // probability of not having chosen the course lobe.
        let u_lobe = (u_lobe - self.p_course) / (1.0 - self.p_course);
        let not_course = 1.0 - self.p_course;
        if u_lobe < self.p_specular {
            if let Specular::Dielectric { ior, reflectance, transmittance, .. } = self.specular {
                let mut sample = self.sample_dielectric(wo, ior, [reflectance, transmittance], u.x);
                sample.weight = sample.weight * self.rest_scale(wo.z) / not_course;
                return Some(sample);
            }
            if self.delta_specular {
                let wi = Vec3::new(-wo.x, -wo.y, wo.z);
                return Some(BsdfSample {
                    wi: self.frame * wi,
                    weight: self.specular_tint(wo.z) * self.rest_scale(wo.z)
                        / (self.p_specular * not_course),
                    eta_scale: 1.0,
                    pdf: 0.0,
                    delta: true,
                    transmitted: false,
                    passes: false,
                });
            }
            let h = self.microfacet.sample(wo, u);
            let wi = 2.0 * wo.dot(h) * h - wo;
            if wi.z <= 0.0 {
                return None;
            }
            return self.mixture_sample(wo, wi);
        }
        let wi = crate::sampling::cosine_hemisphere(u);
        if wi.z <= 0.0 {
            return None;
        }
        if self.p_specular == 0.0 && self.course.is_none() && self.coupling.is_none() {
            // A Lambertian lobe alone, sampled by its own cosine density: f·cos/pdf is its
            // reflectance exactly (`eval` would divide (ρ/π)·cos by cos/π, and round).
            let pdf = wi.z * FRAC_1_PI;
            return (pdf > 0.0)
                .then(|| BsdfSample::smooth_weighted(self.frame * wi, self.diffuse, pdf));
        }
        self.mixture_sample(wo, wi)
    }

    /// A non-delta sample weighted by the whole mixture (needed for MIS to be consistent),
    /// of local direction `wi` from local `wo`: evaluated where it was drawn, not after a
    /// round trip through render space.
    fn mixture_sample(&self, wo: Vec3, wi: Vec3) -> Option<BsdfSample> {
        let (value, pdf) = self.eval_local(wo, wi);
        BsdfSample::smooth(self.frame * wi, value, pdf)
    }

    /// Smooth glass: reflection by Fresnel, else refraction, tinted by `tints`
    /// (reflectance, transmittance).
    fn sample_dielectric(&self, wo: Vec3, ior: f32, tints: [Vec3; 2], u: f32) -> BsdfSample {
        // Relative index across the interface in the direction of travel.
        let eta = if self.front_face { ior } else { 1.0 / ior };
        let reflectance = fresnel_dielectric(wo.z, eta);
        if u < reflectance {
            let wi = Vec3::new(-wo.x, -wo.y, wo.z);
            return BsdfSample {
                wi: self.frame * wi,
                weight: tints[0],
                eta_scale: 1.0,
                pdf: 0.0,
                delta: true,
                transmitted: false,
                passes: false,
            };
        }
        let cos_i = wo.z;
        let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
        let cos_t = (1.0 - sin2_t).max(0.0).sqrt();
        let wi = -wo / eta + (cos_i / eta - cos_t) * Vec3::Z;
        BsdfSample {
            wi: self.frame * wi.normalize(),
            // Radiance is compressed entering a denser medium: (η_i/η_t)².
            weight: tints[1] / (eta * eta),
            eta_scale: eta * eta,
            pdf: 0.0,
            delta: true,
            transmitted: true,
            passes: false,
        }
    }
}
