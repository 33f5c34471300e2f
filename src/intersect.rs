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

/// Watertight ray-triangle test (Woop, Benthin, Wald 2013) for the inside decision, returning `(t, u, v)` with Embree's barycentric convention (u weights vertex
/// 1, v weights vertex 2). A ray through an edge shared by two triangles hits at least one of
/// them, as with Embree's robust mode. Used by the pure-Rust backend and as the brute-force
/// reference in tests.
pub fn intersect_triangle(
    origin: Vec3,
    dir: Vec3,
    tmin: f32,
    tmax: f32,
    tri: &[Vec3; 3],
) -> Option<(f32, f32, f32)> {
    // Translate to the ray origin and permute so the largest direction component is z.
    let kz = dir.abs().max_position();
    let kx = (kz + 1) % 3;
    let ky = (kx + 1) % 3;
    let permute = |v: Vec3| Vec3::new(v[kx], v[ky], v[kz]);
    let d = permute(dir);
    let mut p0 = permute(tri[0] - origin);
    let mut p1 = permute(tri[1] - origin);
    let mut p2 = permute(tri[2] - origin);
    // Shear so the ray runs along +z.
    let (sx, sy) = (-d.x / d.z, -d.y / d.z);
    for p in [&mut p0, &mut p1, &mut p2] {
        p.x += sx * p.z;
        p.y += sy * p.z;
    }
    let mut e0 = difference_of_products(p1.x, p2.y, p1.y, p2.x);
    let mut e1 = difference_of_products(p2.x, p0.y, p2.y, p0.x);
    let mut e2 = difference_of_products(p0.x, p1.y, p0.y, p1.x);
    if e0 == 0.0 || e1 == 0.0 || e2 == 0.0 {
        // Exactly on an edge in f32: decide in f64 so shared edges are never both missed.
        let f = |a: f32, b: f32, c: f32, d: f32| (a as f64 * b as f64 - c as f64 * d as f64) as f32;
        e0 = f(p1.x, p2.y, p1.y, p2.x);
        e1 = f(p2.x, p0.y, p2.y, p0.x);
        e2 = f(p0.x, p1.y, p0.y, p1.x);
    }
    if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
        return None;
    }
    let det = e0 + e1 + e2;
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv_det = 1.0 / det;
    // Distance along the ray from the triangle's plane rather than from the sheared edge
    // functions: for a huge triangle seen from close by (a ground plane under a camera) the
    // sheared form cancels catastrophically, while the plane equation stays exact for
    // axis-aligned planes. Self-intersection is prevented by the spawn offset, not here.
    let normal = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
    let denom = dir.dot(normal);
    if denom == 0.0 || !denom.is_finite() {
        return None;
    }
    let t = (tri[0] - origin).dot(normal) / denom;
    if !(t > 0.0) || t < tmin || t > tmax {
        return None;
    }
    Some((t, e1 * inv_det, e2 * inv_det))
}

/// a·b − c·d with one rounding (Kahan's algorithm with FMA).
fn difference_of_products(a: f32, b: f32, c: f32, d: f32) -> f32 {
    let cd = c * d;
    let err = (-c).mul_add(d, cd);
    let dop = a.mul_add(b, -cd);
    dop + err
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
        let (t, u, v) =
            intersect_triangle(Vec3::new(0.25, 0.5, 1.0), Vec3::NEG_Z, 0.0, f32::INFINITY, &tri)
                .unwrap();
        assert!((t - 1.0).abs() < 1e-6 && (u - 0.25).abs() < 1e-6 && (v - 0.5).abs() < 1e-6);
    }
}
