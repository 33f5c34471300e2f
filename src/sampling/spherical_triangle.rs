//! Directions uniform in the solid angle a triangle subtends (Arvo 1995, "Stratified
//! sampling of spherical triangles"). The arithmetic is in f64: the spherical excess
//! α + β + γ − π cancels badly in f32 for small triangles.

use glam::{DVec3, Vec2, Vec3};

/// Solid angle of triangle `tri` seen from `p` (Van Oosterom & Strackee 1983: one atan2,
/// accurate for tiny and for hemisphere-sized triangles alike).
pub fn solid_angle(tri: &[Vec3; 3], p: Vec3) -> f64 {
    let [a, b, c] = tri.map(|v| v.as_dvec3() - p.as_dvec3());
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let triple = a.dot(b.cross(c)).abs();
    let denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    2.0 * triple.atan2(denominator)
}

/// The angle between unit vectors, accurate near 0 and π (unlike `acos` of the dot).
fn angle_between(u: DVec3, v: DVec3) -> f64 {
    if u.dot(v) < 0.0 {
        std::f64::consts::PI - 2.0 * ((u + v).length() / 2.0).min(1.0).asin()
    } else {
        2.0 * ((v - u).length() / 2.0).min(1.0).asin()
    }
}

/// The part of `v` perpendicular to unit `n`, normalised.
fn perpendicular(v: DVec3, n: DVec3) -> DVec3 {
    (v - v.dot(n) * n).normalize_or_zero()
}

/// Barycentrics (b1, b2) of the point of `tri` in the direction sampled uniformly by solid
/// angle from `p` with `u`, or `None` for a triangle that is degenerate as seen from `p`.
/// `u.x` chooses the sub-triangle's area, `u.y` the point along its far arc, so
/// stratification in `u` carries over to the solid angle.
pub fn sample(tri: &[Vec3; 3], p: Vec3, u: Vec2) -> Option<Vec2> {
    let o = p.as_dvec3();
    let [a, b, c] = tri.map(|v| (v.as_dvec3() - o).normalize_or_zero());
    let normal = |x: DVec3, y: DVec3| x.cross(y).try_normalize();
    let (n_ab, n_bc, n_ca) = (normal(a, b)?, normal(b, c)?, normal(c, a)?);
    // The spherical triangle's interior angles.
    let alpha = angle_between(n_ab, -n_ca);
    let beta = angle_between(n_bc, -n_ab);
    let gamma = angle_between(n_ca, -n_bc);
    let area = alpha + beta + gamma - std::f64::consts::PI;
    if !(area > 0.0) {
        return None;
    }
    // The sub-triangle (a, b, c') with area u.x · area: find c' on the arc from a to c.
    let sub_area = u.x as f64 * area;
    let (sin_alpha, cos_alpha) = alpha.sin_cos();
    let (s, t) = (sub_area - alpha).sin_cos();
    let k_u = t - cos_alpha;
    let k_v = s + sin_alpha * a.dot(b);
    let q = ((k_v * t - k_u * s) * cos_alpha - k_v) / ((k_v * s + k_u * t) * sin_alpha);
    let q = if q.is_finite() { q.clamp(-1.0, 1.0) } else { 1.0 };
    let c_sub = q * a + (1.0 - q * q).max(0.0).sqrt() * perpendicular(c, a);
    // A point on the arc from b to c' with the right density.
    let z = 1.0 - u.y as f64 * (1.0 - c_sub.dot(b));
    let w = z * b + (1.0 - z * z).max(0.0).sqrt() * perpendicular(c_sub, b);
    barycentrics_along(tri, o, w)
}

/// Barycentrics where the ray `o + t w` meets the triangle's plane, clamped into it.
fn barycentrics_along(tri: &[Vec3; 3], o: DVec3, w: DVec3) -> Option<Vec2> {
    let [v0, v1, v2] = tri.map(|v| v.as_dvec3());
    let (e1, e2) = (v1 - v0, v2 - v0);
    let s1 = w.cross(e2);
    let divisor = s1.dot(e1);
    if divisor == 0.0 || !divisor.is_finite() {
        return None;
    }
    let s = o - v0;
    let mut b1 = (s.dot(s1) / divisor).clamp(0.0, 1.0);
    let mut b2 = (w.dot(s.cross(e1)) / divisor).clamp(0.0, 1.0);
    if b1 + b2 > 1.0 {
        let sum = b1 + b2;
        b1 /= sum;
        b2 /= sum;
    }
    Some(Vec2::new(b1 as f32, b2 as f32))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solid_angle_of_an_octant_is_half_pi() {
        let tri = [Vec3::X, Vec3::Y, Vec3::Z];
        let omega = solid_angle(&tri.map(|v| v * 3.0), Vec3::ZERO);
        assert!((omega - std::f64::consts::FRAC_PI_2).abs() < 1e-12, "{omega}");
    }

    #[test]
    fn the_corners_of_the_unit_square_map_to_the_vertices() {
        let tri = [Vec3::new(1.0, 0.0, 2.0), Vec3::new(-1.0, 0.5, 2.0), Vec3::new(0.2, -1.0, 2.5)];
        let point = |b: Vec2| tri[0] + b.x * (tri[1] - tri[0]) + b.y * (tri[2] - tri[0]);
        // u.x = 0 is the degenerate sub-triangle along (a, b); u.y = 0 is vertex b.
        let at_b = point(sample(&tri, Vec3::ZERO, Vec2::new(0.3, 0.0)).unwrap());
        assert!((at_b - tri[1]).length() < 1e-5, "{at_b}");
        let at_c = point(sample(&tri, Vec3::ZERO, Vec2::new(1.0, 1.0)).unwrap());
        assert!((at_c - tri[2]).length() < 1e-4, "{at_c}");
    }
}
