//! Fresnel reflectance of dielectric and conductor interfaces.

use glam::{Vec3, Vec3A};

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

/// Fresnel reflectance of a conductor with complex index `eta + i·k`, per channel (the
/// three channels in one SIMD register: each division is one instruction, not three).
pub fn fresnel_conductor(cos_i: f32, eta: Vec3, k: Vec3) -> Vec3 {
    let (eta, k) = (Vec3A::from(eta), Vec3A::from(k));
    let cos_i = cos_i.clamp(0.0, 1.0);
    let cos2 = cos_i * cos_i;
    let sin2 = 1.0 - cos2;
    let eta2 = eta * eta;
    let k2 = k * k;
    let t0 = eta2 - k2 - Vec3A::splat(sin2);
    let a2b2 = (t0 * t0 + 4.0 * eta2 * k2).max(Vec3A::ZERO).sqrt();
    let t1 = a2b2 + Vec3A::splat(cos2);
    let a = ((a2b2 + t0) * 0.5).max(Vec3A::ZERO).sqrt();
    let t2 = 2.0 * cos_i * a;
    let rs = (t1 - t2) / (t1 + t2);
    let t3 = cos2 * a2b2 + Vec3A::splat(sin2 * sin2);
    let t4 = t2 * sin2;
    let rp = rs * (t3 - t4) / (t3 + t4);
    Vec3::from(((rp + rs) * 0.5).clamp(Vec3A::ZERO, Vec3A::ONE))
}
