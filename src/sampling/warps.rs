//! Warps from the unit square to the domains lights and BSDFs sample.

use glam::{Mat3, Vec2, Vec3};

/// Cosine-weighted direction about +Z (Malley's method); pdf = cos θ / π.
pub fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = concentric_disk(u);
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    Vec3::new(d.x, d.y, z)
}

/// Direction about +Z with density ∝ cos^p θ over the hemisphere (Phong lobes): pdf =
/// (p + 1)/(2π) cos^p θ (`cosine_power_pdf`).
pub fn cosine_power_hemisphere(u: Vec2, exponent: f32) -> Vec3 {
    let cos_theta = u.x.powf(1.0 / (exponent + 1.0));
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let (sin_phi, cos_phi) = (2.0 * std::f32::consts::PI * u.y).sin_cos();
    Vec3::new(sin_theta * cos_phi, sin_theta * sin_phi, cos_theta)
}

/// The density of `cosine_power_hemisphere` at a direction `cos_theta` from +Z.
pub fn cosine_power_pdf(cos_theta: f32, exponent: f32) -> f32 {
    if cos_theta <= 0.0 {
        return 0.0;
    }
    (exponent + 1.0) / (2.0 * std::f32::consts::PI) * cos_theta.powf(exponent)
}

/// Uniform point on the unit disk (Shirley–Chiu concentric map).
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    if o == Vec2::ZERO {
        return Vec2::ZERO;
    }
    let (r, theta) = if o.x.abs() > o.y.abs() {
        (o.x, std::f32::consts::FRAC_PI_4 * (o.y / o.x))
    } else {
        (o.y, std::f32::consts::FRAC_PI_2 - std::f32::consts::FRAC_PI_4 * (o.x / o.y))
    };
    r * Vec2::new(theta.cos(), theta.sin())
}

/// Uniform barycentrics (b1, b2) on a triangle.
pub fn uniform_triangle(u: Vec2) -> Vec2 {
    // Heitz 2019 low-distortion mapping keeps stratification.
    if u.y > u.x {
        let b0 = u.x / 2.0;
        Vec2::new(b0, u.y - b0)
    } else {
        let b1 = u.y / 2.0;
        Vec2::new(u.x - b1, b1)
    }
}

/// Orthonormal basis whose Z axis is `n` (Duff et al. 2017, branchless).
pub fn frame_from_normal(n: Vec3) -> Mat3 {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    Mat3::from_cols(
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
        n,
    )
}
