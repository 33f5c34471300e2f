//! Isotropic GGX (Trowbridge–Reitz) distribution with roughness α.

use glam::{Vec2, Vec3};
use std::f32::consts::PI;

pub fn d(h: Vec3, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let denom = h.z * h.z * (a2 - 1.0) + 1.0;
    a2 / (PI * denom * denom)
}

pub fn lambda(w: Vec3, alpha: f32) -> f32 {
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
