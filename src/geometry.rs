//! Ray-primitive intersection routines shared by every backend (Embree calls the sphere test
//! from a user-geometry callback), so both backends agree on what a hit is.

use glam::Vec3;

/// Closest intersection of a ray with a sphere in `[tmin, tmax]`, or `None`.
///
/// Uses the numerically stable form (Hearn–Baker / Ray Tracing Gems ch. 7): the discriminant
/// is computed from the distance of the sphere centre to the ray line rather than
/// `b² - 4ac`, which cancels catastrophically for small spheres or distant rays.
pub fn intersect_sphere(
    origin: Vec3,
    dir: Vec3,
    tmin: f32,
    tmax: f32,
    center: Vec3,
    radius: f32,
) -> Option<f32> {
    let a = dir.length_squared();
    let f = origin - center;
    let b = -f.dot(dir);
    // Perpendicular distance term: |f - (f·d/|d|²) d|² avoids cancellation in b² - ac.
    let perp = f + (b / a) * dir;
    let disc = a * (radius * radius - perp.length_squared());
    if disc < 0.0 {
        return None;
    }
    let sqrt_disc = disc.sqrt();
    let q = if b >= 0.0 { b + sqrt_disc } else { b - sqrt_disc };
    let mut t0 = q / a;
    let mut t1 = if q != 0.0 { (f.length_squared() - radius * radius) / q } else { t0 };
    if t0 > t1 {
        std::mem::swap(&mut t0, &mut t1);
    }
    if t0 >= tmin && t0 <= tmax {
        Some(t0)
    } else if t1 >= tmin && t1 <= tmax {
        Some(t1)
    } else {
        None
    }
}

/// Watertight-enough Möller–Trumbore test returning `(t, u, v)` with Embree's barycentric
/// convention (u weights vertex 1, v weights vertex 2). Used by the pure-Rust backend and
/// as the brute-force reference in tests.
pub fn intersect_triangle(
    origin: Vec3,
    dir: Vec3,
    tmin: f32,
    tmax: f32,
    tri: &[Vec3; 3],
) -> Option<(f32, f32, f32)> {
    let e1 = tri[1] - tri[0];
    let e2 = tri[2] - tri[0];
    let pvec = dir.cross(e2);
    let det = e1.dot(pvec);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv_det = 1.0 / det;
    let tvec = origin - tri[0];
    let u = tvec.dot(pvec) * inv_det;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let qvec = tvec.cross(e1);
    let v = dir.dot(qvec) * inv_det;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(qvec) * inv_det;
    if t >= tmin && t <= tmax { Some((t, u, v)) } else { None }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_hit_from_outside_and_inside() {
        let c = Vec3::new(0.0, 0.0, -5.0);
        let t = intersect_sphere(Vec3::ZERO, Vec3::NEG_Z, 0.0, f32::INFINITY, c, 1.0).unwrap();
        assert!((t - 4.0).abs() < 1e-5);
        let t = intersect_sphere(c, Vec3::X, 0.0, f32::INFINITY, c, 1.0).unwrap();
        assert!((t - 1.0).abs() < 1e-5);
        assert!(intersect_sphere(Vec3::ZERO, Vec3::X, 0.0, f32::INFINITY, c, 1.0).is_none());
    }

    #[test]
    fn small_sphere_far_away_is_hit_stably() {
        let c = Vec3::new(0.0, 0.0, -1.0e4);
        let t = intersect_sphere(Vec3::ZERO, Vec3::NEG_Z, 0.0, f32::INFINITY, c, 0.01).unwrap();
        assert!((t - (1.0e4 - 0.01)).abs() < 2e-3, "t = {t}");
    }

    #[test]
    fn triangle_barycentrics_follow_embree_convention() {
        let tri = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let (t, u, v) = intersect_triangle(
            Vec3::new(0.25, 0.5, 1.0),
            Vec3::NEG_Z,
            0.0,
            f32::INFINITY,
            &tri,
        )
        .unwrap();
        assert!((t - 1.0).abs() < 1e-6 && (u - 0.25).abs() < 1e-6 && (v - 0.5).abs() < 1e-6);
    }
}
