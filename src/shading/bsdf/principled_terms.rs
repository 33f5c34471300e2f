//! The pieces both principled models share, as Mitsuba 3's `principledhelpers.h` defines
//! them: Schlick's Fresnel weights, the roughness-to-α map, Burley's diffuse with
//! retro-reflection and fake subsurface, the sheen, the clearcoat's GTR1 distribution
//! and its separable shadowing.

use crate::scene::Distribution;
use crate::shading::fresnel::fresnel_dielectric;
use crate::shading::microfacet::Microfacet;
use crate::shading::principled::PrincipledParams;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// (1 − cos)⁵, clamped.
pub(super) fn schlick_weight(cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// Schlick's approximation with reflectance `r0` at normal incidence, for light meeting a
/// facet at cosine `cos` (negative: from inside) of an interface of index `eta`: from the
/// denser side the angle of the transmitted ray is used.
pub(super) fn schlick(r0: Vec3, cos: f32, eta: f32) -> Vec3 {
    let outside = cos >= 0.0;
    let (eta_it, eta_ti) = if outside { (eta, 1.0 / eta) } else { (1.0 / eta, eta) };
    let weight = if eta_it > 1.0 {
        schlick_weight(cos.abs())
    } else {
        let cos_t2 = 1.0 - (1.0 - cos * cos) * eta_ti * eta_ti;
        schlick_weight(cos_t2.max(0.0).sqrt())
    };
    r0 + (Vec3::ONE - r0) * weight
}

/// Reflectance at normal incidence of an interface of index `eta`.
pub(super) fn r0_from_eta(eta: f32) -> f32 {
    let r = (eta - 1.0) / (eta + 1.0);
    r * r
}

/// Dielectric Fresnel reflectance at a facet met at cosine `cos` (negative: from inside an
/// object of index `eta`).
pub(super) fn fresnel(cos: f32, eta: f32) -> f32 {
    if cos >= 0.0 { fresnel_dielectric(cos, eta) } else { fresnel_dielectric(-cos, 1.0 / eta) }
}

/// `color` over its luminance (Mitsuba's Rec. 709 weights), or white if it has none: the
/// hue that `spec_tint` and `sheen_tint` tint towards.
pub(super) fn tint(color: Vec3) -> Vec3 {
    let luminance = color.dot(Vec3::new(0.212_671, 0.715_160, 0.072_169));
    if luminance > 0.0 { color / luminance } else { Vec3::ONE }
}

/// The GGX distribution of a `roughness` (α = roughness², at least 0.001) stretched by
/// `anisotropic` along the tangent (Burley 2012).
pub(super) fn distribution(roughness: f32, anisotropic: f32) -> Microfacet {
    let alpha = roughness * roughness;
    let aspect = (1.0 - 0.9 * anisotropic).sqrt();
    Microfacet {
        distribution: Distribution::Ggx,
        alpha_x: (alpha / aspect).max(0.001),
        alpha_y: (alpha * aspect).max(0.001),
    }
}

/// Smith's masking of `w` by facets of normal `h`, none where `w` sees their back.
pub(super) fn oriented_g1(microfacet: &Microfacet, w: Vec3, h: Vec3) -> f32 {
    if w.dot(h) * w.z <= 0.0 { 0.0 } else { microfacet.g1(w) }
}

/// Burley's diffuse shape (without base colour and 1/π) for a view and a light at
/// |cosines| `cos_view`, `cos_light`, `cos_d` between the light and the half vector:
/// Schlick-weighted retro-reflection, blended by `flatness` towards the Hanrahan–Krueger
/// fake subsurface.
pub(super) fn diffuse_shape(
    p: &PrincipledParams,
    cos_view: f32,
    cos_light: f32,
    cos_d: f32,
) -> f32 {
    let (f_light, f_view) = (schlick_weight(cos_light), schlick_weight(cos_view));
    let lambert = (1.0 - 0.5 * f_view) * (1.0 - 0.5 * f_light);
    let rr = 2.0 * p.roughness * cos_d * cos_d;
    let retro = rr * (f_light + f_view + f_light * f_view * (rr - 1.0));
    if p.flatness == 0.0 {
        return lambert + retro;
    }
    let fss90 = rr / 2.0;
    let fss = (1.0 + (fss90 - 1.0) * f_light) * (1.0 + (fss90 - 1.0) * f_view);
    let subsurface = 1.25 * (fss * (1.0 / (cos_light + cos_view) - 0.5) + 0.5);
    let smooth = lambert + retro;
    smooth + (subsurface - smooth) * p.flatness
}

/// The sheen's colour at grazing light (without the lobe's weights or the cosine): white
/// tinted by `sheen_tint` towards the base colour's hue.
pub(super) fn sheen(p: &PrincipledParams, cos_d: f32) -> Vec3 {
    let color = Vec3::ONE + (tint(p.base_color) - Vec3::ONE) * p.sheen_tint;
    p.sheen * schlick_weight(cos_d.abs()) * color
}

/// The clearcoat's isotropic GTR1 distribution (Burley 2012), roughness α.
pub(super) struct Gtr1 {
    alpha: f32,
}

impl Gtr1 {
    /// Of a `clearcoat_gloss`: α from 0.1 (gloss 0) to 0.001 (gloss 1).
    pub fn from_gloss(gloss: f32) -> Self {
        Gtr1 { alpha: 0.1 + (0.001 - 0.1) * gloss }
    }

    pub fn d(&self, h: Vec3) -> f32 {
        let a2 = self.alpha * self.alpha;
        let d = (a2 - 1.0) / (PI * a2.ln() * (1.0 + (a2 - 1.0) * h.z * h.z));
        if d * h.z > 1e-20 { d } else { 0.0 }
    }

    /// Density of `sample` drawing `h`: D cos θ.
    pub fn pdf(&self, h: Vec3) -> f32 {
        if h.z < 0.0 { 0.0 } else { h.z * self.d(h) }
    }

    pub fn sample(&self, u: Vec2) -> Vec3 {
        let (sin_phi, cos_phi) = (2.0 * PI * u.x).sin_cos();
        let a2 = self.alpha * self.alpha;
        let cos2 = (1.0 - a2.powf(1.0 - u.y)) / (1.0 - a2);
        let sin = (1.0 - cos2).max(0.0).sqrt();
        Vec3::new(cos_phi * sin, sin_phi * sin, cos2.max(0.0).sqrt())
    }
}

/// The clearcoat's separable shadowing: GGX masking of α 0.25 for each direction.
pub(super) fn clearcoat_g(wo: Vec3, wi: Vec3, h: Vec3) -> f32 {
    let g1 = |w: Vec3| {
        if w.dot(h) * w.z <= 0.0 {
            return 0.0;
        }
        if w.z == 1.0 {
            return 1.0;
        }
        let cos2 = w.z * w.z;
        let tan2 = (1.0 - cos2) / cos2;
        2.0 / (1.0 + (1.0 + 0.0625 * tan2).sqrt())
    };
    g1(wo) * g1(wi)
}

/// `w` mirrored about `m`.
pub(super) fn reflect(w: Vec3, m: Vec3) -> Vec3 {
    2.0 * w.dot(m) * m - w
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gtr1_samples_normals_with_unit_projected_area() {
        // ∫ D cos dω = 1 (a normalised distribution), by a midpoint rule in cos θ.
        // (Glossier than 0.9 the peak is too narrow for the rule's steps.)
        for gloss in [0.0, 0.5, 0.9] {
            let gtr1 = Gtr1::from_gloss(gloss);
            let n = 200_000;
            let area: f64 = (0..n)
                .map(|i| {
                    let z = (i as f64 + 0.5) / n as f64;
                    let h = Vec3::new((1.0 - z * z).sqrt() as f32, 0.0, z as f32);
                    f64::from(gtr1.pdf(h)) * 2.0 * std::f64::consts::PI / n as f64
                })
                .sum();
            assert!((area - 1.0).abs() < 2e-3, "gloss {gloss}: {area}");
        }
    }

    #[test]
    fn schlick_meets_the_normal_reflectance_and_one_at_grazing() {
        let r0 = Vec3::splat(r0_from_eta(1.5));
        assert!((schlick(r0, 1.0, 1.5) - r0).abs().max_element() < 1e-6);
        assert!((schlick(r0, 1e-6, 1.5) - Vec3::ONE).abs().max_element() < 1e-4);
        // From inside, past the critical angle the transmitted cosine is 0: total reflection.
        assert!((schlick(r0, -0.3, 1.5) - Vec3::ONE).abs().max_element() < 1e-6);
        assert!((fresnel(0.8, 1.5) - fresnel_dielectric(0.8, 1.5)).abs() < 1e-7);
        assert_eq!(fresnel(-0.3, 1.5), 1.0);
    }
}
