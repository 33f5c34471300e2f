//! The CENG795 course's reflectance models (Fall 2022 hw6, `<BRDFs>`), evaluated as
//! `f(wi, wo) · cos θi`: the factor that turns the irradiance a light delivers
//! (`intensity / d²` for a point light) into reflected radiance.
//!
//! With `kd` the diffuse and `ks` the specular reflectance, `p` the exponent, `n` the normal,
//! `cos α_r = max(0, wo · reflect(wi))` and `cos α_h = max(0, n · h)` (`h` the half vector):
//!
//! | model | f(wi, wo) |
//! |---|---|
//! | OriginalBlinnPhong (the course's default shading) | `kd + ks cos^p α_h / cos θi` |
//! | OriginalPhong | `kd + ks cos^p α_r / cos θi` |
//! | ModifiedBlinnPhong | `kd + ks cos^p α_h` |
//! | ModifiedBlinnPhong, normalized | `kd/π + ks (p+8)/(8π) cos^p α_h` |
//! | ModifiedPhong | `kd + ks cos^p α_r` |
//! | ModifiedPhong, normalized | `kd/π + ks (p+2)/(2π) cos^p α_r` |
//! | TorranceSparrow | `kd/π + ks D F G / (4 cos θi cos θo)`, `D = (p+2)/(2π) cos^p α_h`, `F` the Fresnel reflectance at `wo · h` (conductor, from the material's refraction and absorption indices), `G = min(1, 2 (n·h)(n·wo)/(wo·h), 2 (n·h)(n·wi)/(wo·h))`; with `kdfresnel` the diffuse term is `(1 − F) kd/π` |
//!
//! The un-normalized models keep the course's units (`kd` not divided by π), so that
//! OriginalBlinnPhong reproduces the shading of the earlier homeworks exactly. Nothing is
//! reflected from a light below the horizon (`cos θi ≤ 0`) or towards a viewer below it.

use super::fresnel::fresnel_conductor;
use crate::scene::CourseBrdf;
use glam::Vec3;
use std::f32::consts::PI;

/// The reflectances and exponent a course BRDF is evaluated with.
#[derive(Clone, Copy, Debug)]
pub struct CourseTerms {
    pub diffuse: Vec3,
    pub specular: Vec3,
    pub exponent: f32,
}

/// `f(wi, wo) · cos θi` for unit vectors `n` (the side being shaded), `wi` (towards the
/// light) and `wo` (towards the viewer).
pub fn cos_weighted(brdf: &CourseBrdf, terms: &CourseTerms, n: Vec3, wi: Vec3, wo: Vec3) -> Vec3 {
    let cos_i = n.dot(wi);
    if cos_i <= 0.0 {
        return Vec3::ZERO;
    }
    let p = terms.exponent;
    let (kd, ks) = (terms.diffuse, terms.specular);
    let half_lobe = || n.dot((wi + wo).normalize_or_zero()).max(0.0).powf(p);
    let mirror_lobe = || {
        let reflected = 2.0 * cos_i * n - wi;
        reflected.dot(wo).max(0.0).powf(p)
    };
    match *brdf {
        CourseBrdf::OriginalBlinnPhong => kd * cos_i + ks * half_lobe(),
        CourseBrdf::OriginalPhong => kd * cos_i + ks * mirror_lobe(),
        CourseBrdf::ModifiedBlinnPhong { normalized: false } => (kd + ks * half_lobe()) * cos_i,
        CourseBrdf::ModifiedBlinnPhong { normalized: true } => {
            (kd / PI + ks * ((p + 8.0) / (8.0 * PI)) * half_lobe()) * cos_i
        }
        CourseBrdf::ModifiedPhong { normalized: false } => (kd + ks * mirror_lobe()) * cos_i,
        CourseBrdf::ModifiedPhong { normalized: true } => {
            (kd / PI + ks * ((p + 2.0) / (2.0 * PI)) * mirror_lobe()) * cos_i
        }
        CourseBrdf::TorranceSparrow { kd_fresnel, eta, k } => {
            let cos_o = n.dot(wo);
            let h = (wi + wo).normalize_or_zero();
            let (n_h, wo_h) = (n.dot(h), wo.dot(h));
            if cos_o <= 0.0 || n_h <= 0.0 || wo_h <= 0.0 {
                return kd / PI * cos_i;
            }
            let distribution = (p + 2.0) / (2.0 * PI) * n_h.powf(p);
            let fresnel = fresnel_conductor(wo_h, eta, k);
            let shadowing = (2.0 * n_h * cos_o / wo_h).min(2.0 * n_h * cos_i / wo_h).min(1.0);
            let diffuse = if kd_fresnel { (Vec3::ONE - fresnel) * kd / PI } else { kd / PI };
            let specular = ks * fresnel * (distribution * shadowing / (4.0 * cos_i * cos_o));
            (diffuse + specular) * cos_i
        }
    }
}

/// Every model, for the tests of evaluation and sampling.
#[cfg(test)]
pub(crate) const MODELS: [CourseBrdf; 7] = [
    CourseBrdf::OriginalBlinnPhong,
    CourseBrdf::OriginalPhong,
    CourseBrdf::ModifiedBlinnPhong { normalized: false },
    CourseBrdf::ModifiedBlinnPhong { normalized: true },
    CourseBrdf::ModifiedPhong { normalized: false },
    CourseBrdf::ModifiedPhong { normalized: true },
    CourseBrdf::TorranceSparrow {
        kd_fresnel: true,
        eta: Vec3::new(0.37, 0.37, 0.37),
        k: Vec3::new(2.82, 2.82, 2.82),
    },
];

#[cfg(test)]
mod tests {
    use super::*;

    fn direction(theta: f32, phi: f32) -> Vec3 {
        Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
    }

    /// ∫ f(wi, wo) cos θi dwi over the hemisphere, by the midpoint rule in (cos θ, φ).
    fn albedo(brdf: &CourseBrdf, terms: &CourseTerms, wo: Vec3) -> Vec3 {
        let (rings, sectors) = (2000, 360);
        let mut sum = Vec3::ZERO;
        for i in 0..rings {
            let cos_theta = (i as f32 + 0.5) / rings as f32;
            for j in 0..sectors {
                let phi = 2.0 * PI * (j as f32 + 0.5) / sectors as f32;
                let wi = direction(cos_theta.acos(), phi);
                sum += cos_weighted(brdf, terms, Vec3::Z, wi, wo);
            }
        }
        sum * (2.0 * PI / (rings * sectors) as f32)
    }

    #[test]
    fn normalized_models_reflect_at_most_what_arrives() {
        // A white furnace: unit diffuse or unit specular reflectance, every viewing angle.
        // Blinn-Phong's (p+8)/(8π) is the usual approximation of its normalization, not an
        // exact one: viewed along the normal it reflects (p+8)/4 ∫ cos^p(θ/2) cos θ sin θ dθ,
        // which is 1.024 at p = 1, 1.0748 at p = 10 (the worst), 1.018 at p = 100.
        for (brdf, bound) in [
            (CourseBrdf::ModifiedBlinnPhong { normalized: true }, 1.0748),
            (CourseBrdf::ModifiedPhong { normalized: true }, 1.0),
            (MODELS[6], 1.0),
        ] {
            for (kd, ks) in [(1.0, 0.0), (0.0, 1.0)] {
                for p in [1.0, 10.0, 100.0] {
                    let terms = CourseTerms {
                        diffuse: Vec3::splat(kd),
                        specular: Vec3::splat(ks),
                        exponent: p,
                    };
                    for theta_o in [0.0f32, 0.5, 1.0, 1.4] {
                        let a = albedo(&brdf, &terms, direction(theta_o, 0.3)).x;
                        assert!(
                            a <= bound + 2e-3,
                            "{brdf:?} kd {kd} ks {ks} p {p} θo {theta_o}: {a}"
                        );
                        if kd == 1.0 && !matches!(brdf, CourseBrdf::TorranceSparrow { .. }) {
                            // Lambert's kd/π integrates to exactly kd.
                            assert!((a - 1.0).abs() < 2e-3, "{brdf:?} diffuse: {a}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn the_normalized_phong_lobe_reflects_all_at_normal_incidence() {
        // Viewed along the normal, (p+2)/(2π) cos^p α_r integrates (with cos θi = cos α_r)
        // to exactly 1 whatever p: the normalization's definition.
        let brdf = CourseBrdf::ModifiedPhong { normalized: true };
        for p in [1.0, 20.0, 200.0] {
            let terms = CourseTerms { diffuse: Vec3::ZERO, specular: Vec3::ONE, exponent: p };
            let a = albedo(&brdf, &terms, Vec3::Z).x;
            assert!((a - 1.0).abs() < 5e-3, "p {p}: {a}");
        }
    }

    #[test]
    fn every_model_is_reciprocal_where_the_course_defines_it_so() {
        // The modified models and Torrance-Sparrow are symmetric in wi and wo; the
        // original ones divide by cos θi and are not.
        let terms =
            CourseTerms { diffuse: Vec3::splat(0.3), specular: Vec3::splat(0.6), exponent: 12.0 };
        let mut rng = crate::splitmix::SplitMix64(3);
        for brdf in &MODELS[2..] {
            for _ in 0..200 {
                let a = direction(rng.range(0.0, 1.5), rng.range(0.0, 2.0 * PI));
                let b = direction(rng.range(0.0, 1.5), rng.range(0.0, 2.0 * PI));
                let f_ab = cos_weighted(brdf, &terms, Vec3::Z, a, b) / a.z;
                let f_ba = cos_weighted(brdf, &terms, Vec3::Z, b, a) / b.z;
                assert!(
                    (f_ab - f_ba).abs().max_element() <= 1e-4 * f_ab.max_element().max(1.0),
                    "{brdf:?}"
                );
            }
        }
    }

    #[test]
    fn the_default_model_is_the_earlier_homeworks_shading() {
        let terms =
            CourseTerms { diffuse: Vec3::new(0.5, 0.4, 0.3), specular: Vec3::ONE, exponent: 50.0 };
        let n = Vec3::new(0.2, 0.3, 0.9).normalize();
        let (wi, wo) =
            (Vec3::new(0.3, 0.1, 0.9).normalize(), Vec3::new(-0.2, 0.2, 0.95).normalize());
        let expected =
            terms.diffuse * n.dot(wi) + Vec3::ONE * n.dot((wi + wo).normalize()).powf(50.0);
        let got = cos_weighted(&CourseBrdf::OriginalBlinnPhong, &terms, n, wi, wo);
        assert!((got - expected).abs().max_element() < 1e-6, "{got} vs {expected}");
        // Nothing from below the horizon, for every model.
        for brdf in &MODELS {
            assert_eq!(cos_weighted(brdf, &terms, Vec3::Z, -wi, wo), Vec3::ZERO, "{brdf:?}");
        }
    }
}
