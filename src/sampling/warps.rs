//! Warps from the unit square to the domains lights and BSDFs sample.

use glam::{Mat3, Vec2, Vec3};

/// Cosine-weighted direction about +Z (Malley's method); pdf = cos θ / π.
pub fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let (d, r) = concentric_disk_with_radius(u);
    // From the radius the map gives, not the point's length: no cancellation near the rim
    // (1 − r is exact there), and no wait for the sine and cosine.
    let z = ((1.0 - r) * (1.0 + r)).max(0.0).sqrt();
    Vec3::new(d.x, d.y, z)
}

/// A direction uniform over the unit sphere; pdf = 1 / 4π.
pub fn uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (sin_phi, cos_phi) = (2.0 * std::f32::consts::PI * u.y).sin_cos();
    Vec3::new(r * cos_phi, r * sin_phi, z)
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
    concentric_disk_with_radius(u).0
}

/// `concentric_disk`'s point and its distance from the centre as the map defines it.
fn concentric_disk_with_radius(u: Vec2) -> (Vec2, f32) {
    let o = 2.0 * u - Vec2::ONE;
    if o == Vec2::ZERO {
        return (Vec2::ZERO, 0.0);
    }
    // The angle is π/4 times a ratio in [-1, 1] from the x axis, or π/2 minus one from
    // the y axis, whose cosine and sine are the other's sine and cosine: only angles in
    // [-π/4, π/4] are ever needed, where short polynomials are exact to an ulp or two.
    if o.x.abs() > o.y.abs() {
        let (sin, cos) = sin_cos_quarter(std::f32::consts::FRAC_PI_4 * (o.y / o.x));
        (o.x * Vec2::new(cos, sin), o.x.abs())
    } else {
        let (sin, cos) = sin_cos_quarter(std::f32::consts::FRAC_PI_4 * (o.x / o.y));
        (o.y * Vec2::new(sin, cos), o.y.abs())
    }
}

/// Sine and cosine of `x` in [-π/4, π/4] (Cephes' `sinf`/`cosf` kernels: minimax
/// polynomials within about an ulp there): no range reduction, no call into libm, and the
/// same bits on every machine (no fused multiply-adds).
fn sin_cos_quarter(x: f32) -> (f32, f32) {
    let z = x * x;
    let sin = x + x * z * (-1.666_665_5e-1 + z * (8.332_161e-3 + z * -1.951_529_6e-4));
    let cos = 1.0 - 0.5 * z + z * z * (4.166_664_6e-2 + z * (-1.388_731_6e-3 + z * 2.443_315_7e-5));
    (sin, cos)
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarter_sine_and_cosine_are_within_one_and_a_half_ulps() {
        let quarter = std::f64::consts::FRAC_PI_4;
        let steps = 200_000;
        let mut worst = 0.0f64;
        for i in 0..=steps {
            let x = (-quarter + 2.0 * quarter * i as f64 / steps as f64) as f32;
            let (sin, cos) = sin_cos_quarter(x);
            let (exact_sin, exact_cos) = (x as f64).sin_cos();
            // In units of the f32 spacing at the exact value.
            let ulps = |got: f32, exact: f64| {
                let at = (exact as f32).abs();
                let ulp = (f32::from_bits(at.to_bits() + 1) - at) as f64;
                (got as f64 - exact).abs() / ulp
            };
            worst = worst.max(ulps(sin, exact_sin)).max(ulps(cos, exact_cos));
        }
        assert!(worst <= 1.5, "worst error {worst} ulps");
    }

    #[test]
    fn the_concentric_disk_keeps_points_in_the_disk_and_its_axes() {
        let mut rng = crate::splitmix::SplitMix64(3);
        for _ in 0..100_000 {
            let d = concentric_disk(Vec2::new(rng.unit(), rng.unit()));
            assert!(d.length_squared() <= 1.0 + 1e-6, "{d}");
        }
        // The square's centre lines map onto the disk's axes, its edges onto the circle.
        assert_eq!(concentric_disk(Vec2::new(1.0, 0.5)), Vec2::new(1.0, 0.0));
        assert_eq!(concentric_disk(Vec2::new(0.5, 1.0)), Vec2::new(0.0, 1.0));
        assert!((concentric_disk(Vec2::new(1.0, 1.0)).length() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn cosine_directions_are_unit() {
        let mut rng = crate::splitmix::SplitMix64(9);
        for _ in 0..100_000 {
            let w = cosine_hemisphere(Vec2::new(rng.unit(), rng.unit()));
            assert!((w.length() - 1.0).abs() < 1e-6 && w.z >= 0.0, "{w}");
        }
    }
}
