//! GGX (Trowbridge–Reitz) distribution of roughness αx along the frame's tangent and αy
//! along its bitangent. The isotropic case (αx = αy) keeps its own, older arithmetic, so
//! isotropic renders are bit for bit what they were.

use glam::{Vec2, Vec3};
use std::f32::consts::PI;

pub fn d(h: Vec3, ax: f32, ay: f32) -> f32 {
    if ax == ay {
        let a2 = ax * ax;
        let denom = h.z * h.z * (a2 - 1.0) + 1.0;
        return a2 / (PI * denom * denom);
    }
    let (x, y) = (h.x / ax, h.y / ay);
    let denom = x * x + y * y + h.z * h.z;
    1.0 / (PI * ax * ay * denom * denom)
}

/// α² tan²θ of direction `w` under the (possibly anisotropic) roughness: the projected
/// roughness squared, times tan²θ.
fn alpha2_tan2(w: Vec3, ax: f32, ay: f32, cos2: f32) -> f32 {
    if ax == ay {
        ax * ax * ((1.0 - cos2).max(0.0) / cos2)
    } else {
        (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / cos2
    }
}

pub fn lambda(w: Vec3, ax: f32, ay: f32) -> f32 {
    let cos2 = w.z * w.z;
    if cos2 <= 0.0 {
        return f32::INFINITY;
    }
    0.5 * (-1.0 + (1.0 + alpha2_tan2(w, ax, ay, cos2)).sqrt())
}

pub fn g1(w: Vec3, ax: f32, ay: f32) -> f32 {
    1.0 / (1.0 + lambda(w, ax, ay))
}

pub fn g2(wo: Vec3, wi: Vec3, ax: f32, ay: f32) -> f32 {
    1.0 / (1.0 + lambda(wo, ax, ay) + lambda(wi, ax, ay))
}

/// Visible-normal sampling (Heitz 2018): the view stretched to the unit-roughness
/// configuration, a point on the projected hemisphere, the normal stretched back.
pub fn sample_visible_normal(wo: Vec3, ax: f32, ay: f32, u: Vec2) -> Vec3 {
    let vh = Vec3::new(ax * wo.x, ay * wo.y, wo.z).normalize();
    let len2 = vh.x * vh.x + vh.y * vh.y;
    let t1 = if len2 > 0.0 { Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt() } else { Vec3::X };
    let t2 = vh.cross(t1);
    let r = u.x.sqrt();
    let phi = 2.0 * PI * u.y;
    let p1 = r * phi.cos();
    let s = 0.5 * (1.0 + vh.z);
    let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * phi.sin();
    let nh = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * vh;
    Vec3::new(ax * nh.x, ay * nh.y, nh.z.max(1e-6)).normalize()
}

/// `d(h)·G₂(wo, wi)` and `pdf_reflect(wo, h)` together, D and Λ(wo) computed once for both
/// (the same numbers, bit for bit: each is the same expression of them); G₂ height-correlated
/// (`g2`), or with `separable` the product of the two G₁.
pub fn reflect_terms(
    wo: Vec3,
    wi: Vec3,
    h: Vec3,
    (ax, ay): (f32, f32),
    separable: bool,
) -> (f32, f32) {
    let d = d(h, ax, ay);
    let lambda_o = lambda(wo, ax, ay);
    let lambda_i = lambda(wi, ax, ay);
    let d_g2 = match separable {
        false => d * (1.0 / (1.0 + lambda_o + lambda_i)),
        true => d * (1.0 / (1.0 + lambda_o) * (1.0 / (1.0 + lambda_i))),
    };
    let pdf = if wo.z <= 0.0 || wo.dot(h) <= 0.0 {
        0.0
    } else {
        1.0 / (1.0 + lambda_o) * d / (4.0 * wo.z)
    };
    (d_g2, pdf)
}

/// Density of reflected direction `wi` when sampling visible normals from `wo`.
pub fn pdf_reflect(wo: Vec3, h: Vec3, ax: f32, ay: f32) -> f32 {
    let wo_h = wo.dot(h);
    if wo.z <= 0.0 || wo_h <= 0.0 {
        return 0.0;
    }
    g1(wo, ax, ay) * d(h, ax, ay) / (4.0 * wo.z)
}
