//! Scattering at a surface: a Lambertian lobe plus at most one specular lobe (mirror,
//! conductor with Fresnel, or glass), GGX microfacets for rough mirrors and metals.
//! Directions are in render space; `frame` maps the local shading frame (normal = +Z) to it.

use crate::color::luminance;
use crate::scene::Specular;
use crate::shading::material::Material;
use glam::{Mat3, Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI};

/// Unpolarised Fresnel reflectance of a dielectric interface; `eta` = n_transmitted /
/// n_incident, `cos_i` ≥ 0 on the incident side.
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0; // total internal reflection
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    0.5 * (r_parl * r_parl + r_perp * r_perp)
}

/// Fresnel reflectance of a conductor with complex index `eta + i·k`, per channel.
pub fn fresnel_conductor(cos_i: f32, eta: Vec3, k: Vec3) -> Vec3 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let cos2 = cos_i * cos_i;
    let sin2 = 1.0 - cos2;
    let eta2 = eta * eta;
    let k2 = k * k;
    let t0 = eta2 - k2 - Vec3::splat(sin2);
    let a2b2 = (t0 * t0 + 4.0 * eta2 * k2).max(Vec3::ZERO);
    let a2b2 = Vec3::new(a2b2.x.sqrt(), a2b2.y.sqrt(), a2b2.z.sqrt());
    let t1 = a2b2 + Vec3::splat(cos2);
    let a = ((a2b2 + t0) * 0.5).max(Vec3::ZERO);
    let a = Vec3::new(a.x.sqrt(), a.y.sqrt(), a.z.sqrt());
    let t2 = 2.0 * cos_i * a;
    let rs = (t1 - t2) / (t1 + t2);
    let t3 = cos2 * a2b2 + Vec3::splat(sin2 * sin2);
    let t4 = t2 * sin2;
    let rp = rs * (t3 - t4) / (t3 + t4);
    ((rp + rs) * 0.5).clamp(Vec3::ZERO, Vec3::ONE)
}

/// Isotropic GGX (Trowbridge–Reitz) distribution with roughness α.
mod ggx {
    use super::*;

    pub fn d(h: Vec3, alpha: f32) -> f32 {
        let a2 = alpha * alpha;
        let denom = h.z * h.z * (a2 - 1.0) + 1.0;
        a2 / (PI * denom * denom)
    }

    fn lambda(w: Vec3, alpha: f32) -> f32 {
        let cos2 = w.z * w.z;
        if cos2 <= 0.0 {
            return f32::INFINITY;
        }
        let tan2 = (1.0 - cos2).max(0.0) / cos2;
        0.5 * (-1.0 + (1.0 + alpha * alpha * tan2).sqrt())
    }

    pub fn g1(w: Vec3, alpha: f32) -> f32 {
        1.0 / (1.0 + lambda(w, alpha))
    }

    pub fn g2(wo: Vec3, wi: Vec3, alpha: f32) -> f32 {
        1.0 / (1.0 + lambda(wo, alpha) + lambda(wi, alpha))
    }

    /// Visible-normal sampling (Heitz 2018).
    pub fn sample_visible_normal(wo: Vec3, alpha: f32, u: Vec2) -> Vec3 {
        let vh = Vec3::new(alpha * wo.x, alpha * wo.y, wo.z).normalize();
        let len2 = vh.x * vh.x + vh.y * vh.y;
        let t1 = if len2 > 0.0 { Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt() } else { Vec3::X };
        let t2 = vh.cross(t1);
        let r = u.x.sqrt();
        let phi = 2.0 * PI * u.y;
        let p1 = r * phi.cos();
        let s = 0.5 * (1.0 + vh.z);
        let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * phi.sin();
        let nh = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * vh;
        Vec3::new(alpha * nh.x, alpha * nh.y, nh.z.max(1e-6)).normalize()
    }

    /// Density of reflected direction `wi` when sampling visible normals from `wo`.
    pub fn pdf_reflect(wo: Vec3, h: Vec3, alpha: f32) -> f32 {
        let wo_h = wo.dot(h);
        if wo.z <= 0.0 || wo_h <= 0.0 {
            return 0.0;
        }
        g1(wo, alpha) * d(h, alpha) / (4.0 * wo.z)
    }
}

/// A sampled scattering direction.
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    pub wi: Vec3,
    /// f · |cos θ| / pdf.
    pub weight: Vec3,
    /// Density of `wi` (0 for a delta lobe).
    pub pdf: f32,
    pub delta: bool,
    /// The direction passes through the surface (refraction).
    pub transmitted: bool,
}

/// The scattering function at one shading point.
#[derive(Clone, Copy, Debug)]
pub struct Bsdf {
    /// Local (tangent, bitangent, normal) → render space.
    frame: Mat3,
    albedo: Vec3,
    specular: Specular,
    alpha: f32,
    delta_specular: bool,
    /// Whether the incoming ray arrived on the side the surface normal points to.
    front_face: bool,
    /// Probability of choosing the specular lobe.
    p_specular: f32,
}

impl Bsdf {
    pub fn new(material: &Material, albedo: Vec3, frame: Mat3, front_face: bool) -> Self {
        let specular_weight = match material.specular {
            Specular::None => 0.0,
            Specular::Mirror { reflectance } => luminance(reflectance),
            Specular::Conductor { eta, k, reflectance } => {
                luminance(fresnel_conductor(1.0, eta, k) * reflectance)
            }
            Specular::Dielectric { .. } => f32::INFINITY,
        };
        let diffuse_weight =
            if material.is_dielectric() { 0.0 } else { luminance(albedo.max(Vec3::ZERO)) };
        let p_specular = if specular_weight.is_infinite() {
            1.0
        } else if specular_weight + diffuse_weight > 0.0 {
            specular_weight / (specular_weight + diffuse_weight)
        } else {
            0.0
        };
        Bsdf {
            frame,
            albedo: if material.is_dielectric() { Vec3::ZERO } else { albedo },
            specular: material.specular,
            alpha: material.ggx_alpha.max(1e-4),
            delta_specular: material.specular_is_delta(),
            front_face,
            p_specular,
        }
    }

    /// True if light sampling can contribute (some lobe is not a delta distribution).
    pub fn has_smooth_lobe(&self) -> bool {
        self.p_specular < 1.0 || !self.delta_specular
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

    /// f · |cos θi| and the density of sampling `wi`, for the non-delta lobes.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        let (wo, wi) = (self.local_from_render(wo), self.local_from_render(wi));
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let p_diffuse = 1.0 - self.p_specular;
        let mut value = self.albedo * FRAC_1_PI * wi.z;
        let mut pdf = p_diffuse * wi.z * FRAC_1_PI;
        if self.p_specular > 0.0 && !self.delta_specular {
            let h = (wo + wi).normalize();
            let d = ggx::d(h, self.alpha);
            let f = self.specular_tint(wo.dot(h));
            value += f * (d * ggx::g2(wo, wi, self.alpha) / (4.0 * wo.z));
            pdf += self.p_specular * ggx::pdf_reflect(wo, h, self.alpha);
        }
        (value, pdf)
    }

    /// Samples an incident direction for outgoing `wo` (both render space).
    pub fn sample(&self, wo_render: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let wo = self.local_from_render(wo_render);
        if wo.z <= 0.0 {
            return None;
        }
        if u_lobe < self.p_specular {
            if let Specular::Dielectric { ior, .. } = self.specular {
                return Some(self.sample_dielectric(wo, ior, u.x));
            }
            if self.delta_specular {
                let wi = Vec3::new(-wo.x, -wo.y, wo.z);
                return Some(BsdfSample {
                    wi: self.frame * wi,
                    weight: self.specular_tint(wo.z) / self.p_specular,
                    pdf: 0.0,
                    delta: true,
                    transmitted: false,
                });
            }
            let h = ggx::sample_visible_normal(wo, self.alpha, u);
            let wi = 2.0 * wo.dot(h) * h - wo;
            if wi.z <= 0.0 {
                return None;
            }
            return self.mixture_sample(wo_render, self.frame * wi);
        }
        let wi = crate::sampling::cosine_hemisphere(u);
        if wi.z <= 0.0 {
            return None;
        }
        self.mixture_sample(wo_render, self.frame * wi)
    }

    /// A non-delta sample weighted by the whole mixture (needed for MIS to be consistent).
    fn mixture_sample(&self, wo: Vec3, wi: Vec3) -> Option<BsdfSample> {
        let (value, pdf) = self.eval(wo, wi);
        (pdf > 0.0).then(|| BsdfSample {
            wi,
            weight: value / pdf,
            pdf,
            delta: false,
            transmitted: false,
        })
    }

    fn sample_dielectric(&self, wo: Vec3, ior: f32, u: f32) -> BsdfSample {
        // Relative index across the interface in the direction of travel.
        let eta = if self.front_face { ior } else { 1.0 / ior };
        let reflectance = fresnel_dielectric(wo.z, eta);
        if u < reflectance {
            let wi = Vec3::new(-wo.x, -wo.y, wo.z);
            return BsdfSample {
                wi: self.frame * wi,
                weight: Vec3::ONE,
                pdf: 0.0,
                delta: true,
                transmitted: false,
            };
        }
        let cos_i = wo.z;
        let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
        let cos_t = (1.0 - sin2_t).max(0.0).sqrt();
        let wi = -wo / eta + (cos_i / eta - cos_t) * Vec3::Z;
        BsdfSample {
            wi: self.frame * wi.normalize(),
            // Radiance is compressed entering a denser medium: (η_i/η_t)².
            weight: Vec3::splat(1.0 / (eta * eta)),
            pdf: 0.0,
            delta: true,
            transmitted: true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::{hash4, to_unit_f32};

    fn u(i: u64, d: u64) -> f32 {
        to_unit_f32(hash4(1, i, 0, d))
    }

    #[test]
    fn fresnel_limits() {
        assert!((fresnel_dielectric(1.0, 1.5) - 0.04).abs() < 1e-3);
        assert_eq!(fresnel_dielectric(0.1, 1.0 / 1.5), 1.0);
        let gold =
            fresnel_conductor(1.0, Vec3::new(0.143, 0.374, 1.442), Vec3::new(3.98, 2.38, 1.60));
        assert!(gold.x > gold.z && gold.x > 0.9);
    }

    #[test]
    fn ggx_sampling_matches_its_density() {
        // ∫ pdf dω over the whole sphere ≈ 1 (some reflected directions fall below the
        // horizon; the sampler rejects those), estimated with uniform directions.
        let alpha = 0.3;
        let wo = Vec3::new(0.4, 0.1, 0.9).normalize();
        let n = 200_000;
        let mut integral = 0.0f64;
        for i in 0..n {
            let z = 2.0 * u(i, 0) - 1.0;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = 2.0 * PI * u(i, 1);
            let wi = Vec3::new(r * phi.cos(), r * phi.sin(), z);
            let h = (wo + wi).normalize();
            integral += ggx::pdf_reflect(wo, h, alpha) as f64 * 4.0 * std::f64::consts::PI;
        }
        let integral = integral / n as f64;
        assert!((integral - 1.0).abs() < 0.03, "∫pdf = {integral}");
    }

    #[test]
    fn white_mirror_and_glass_conserve_energy() {
        let frame = Mat3::IDENTITY;
        let wo = Vec3::new(0.3, 0.2, 0.93).normalize();
        for material in [
            Material {
                specular: Specular::Mirror { reflectance: Vec3::ONE },
                albedo: Vec3::ZERO,
                ..Default::default()
            },
            Material {
                specular: Specular::Dielectric { ior: 1.5, absorption: Vec3::ZERO },
                ..Default::default()
            },
        ] {
            let bsdf = Bsdf::new(&material, material.albedo, frame, true);
            let mut total = 0.0;
            for i in 0..10_000 {
                let s = bsdf.sample(wo, u(i, 2), Vec2::new(u(i, 3), u(i, 4))).unwrap();
                // Count radiance-weight without the η² compression, i.e. energy.
                total += if s.transmitted { 1.0 } else { s.weight.x };
                assert!(s.weight.is_finite());
            }
            assert!((total / 10_000.0 - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn lambertian_sample_weight_is_the_albedo() {
        let material = Material::diffuse(Vec3::new(0.5, 0.6, 0.7));
        let bsdf = Bsdf::new(&material, material.albedo, Mat3::IDENTITY, true);
        let s = bsdf.sample(Vec3::Z, 0.5, Vec2::new(0.3, 0.7)).unwrap();
        assert!((s.weight - material.albedo).abs().max_element() < 1e-5);
    }
}
