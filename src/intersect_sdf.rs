//! The first crossing of a ray with the zero set of one voxel's trilinear function, shared
//! by both backends (Embree calls it from a user-geometry callback), so they agree on what
//! a hit on a signed distance grid is.
//!
//! Along the ray the trilinear function is a cubic in t (Hansson-Söderlund et al. 2022,
//! after Marmitt et al. 2004). Its extrema (roots of the derivative, a quadratic) split the
//! ray's span in the voxel into pieces on which it is monotone; the first piece whose ends
//! differ in sign holds the first root, found by regula falsi (Illinois). Everything is in
//! f64, so a root is found far below f32's resolution of t and both backends, calling this
//! with the same ray, get the same bits.

use glam::{DVec3, Vec3};

/// How many regula falsi steps at most; Illinois halves the interval at least every few
/// steps, so 200 reaches f64's resolution from any start.
const MAX_STEPS: usize = 200;

/// The cubic `c0 + c1 s + c2 s² + c3 s³` of the voxel's function along the ray from `p`
/// (voxel-local) in direction `d`. `f` holds the corner values, corner `c` at
/// (c & 1, c >> 1 & 1, c >> 2 & 1).
fn cubic(f: &[f32; 8], p: DVec3, d: DVec3) -> [f64; 4] {
    let f = f.map(f64::from);
    let a0 = f[0];
    let (ax, ay, az) = (f[1] - f[0], f[2] - f[0], f[4] - f[0]);
    let axy = f[3] - f[1] - f[2] + f[0];
    let axz = f[5] - f[1] - f[4] + f[0];
    let ayz = f[6] - f[2] - f[4] + f[0];
    let axyz = f[7] - f[3] - f[5] - f[6] + f[1] + f[2] + f[4] - f[0];
    let c0 = a0
        + ax * p.x
        + ay * p.y
        + az * p.z
        + axy * p.x * p.y
        + axz * p.x * p.z
        + ayz * p.y * p.z
        + axyz * p.x * p.y * p.z;
    let gx = ax + axy * p.y + axz * p.z + axyz * p.y * p.z;
    let gy = ay + axy * p.x + ayz * p.z + axyz * p.x * p.z;
    let gz = az + axz * p.x + ayz * p.y + axyz * p.x * p.y;
    let c1 = d.x * gx + d.y * gy + d.z * gz;
    let c2 = axy * d.x * d.y
        + axz * d.x * d.z
        + ayz * d.y * d.z
        + axyz * (d.x * d.y * p.z + d.x * p.y * d.z + p.x * d.y * d.z);
    let c3 = axyz * d.x * d.y * d.z;
    [c0, c1, c2, c3]
}

fn eval([c0, c1, c2, c3]: [f64; 4], s: f64) -> f64 {
    ((c3 * s + c2) * s + c1) * s + c0
}

/// The roots of `a s² + b s + c` (none, or two, possibly equal), in increasing order.
fn quadratic_roots(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    if a == 0.0 {
        return (b != 0.0).then(|| (-c / b, -c / b));
    }
    let disc = b * b - 4.0 * a * c;
    if !(disc >= 0.0) {
        return None;
    }
    // The stable form: no cancellation between -b and the root of the discriminant.
    let q = -0.5 * (b + disc.sqrt().copysign(b));
    let (r0, r1) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
    Some((r0.min(r1), r0.max(r1)))
}

/// The root of the cubic in `[a, b]`, where its values `fa`, `fb` have opposite signs.
fn bracketed_root(
    cubic: [f64; 4],
    (mut a, mut b): (f64, f64),
    (mut fa, mut fb): (f64, f64),
) -> f64 {
    let mut kept = 0i8;
    for _ in 0..MAX_STEPS {
        let mut m = (a * fb - b * fa) / (fb - fa);
        if !(m > a && m < b) {
            m = 0.5 * (a + b);
            if !(m > a && m < b) {
                break;
            }
        }
        let fm = eval(cubic, m);
        if fm == 0.0 {
            return m;
        }
        // Illinois: an end kept twice in a row has its value halved, so the other end moves.
        if (fm < 0.0) == (fa < 0.0) {
            (a, fa) = (m, fm);
            if kept == 1 {
                fb *= 0.5;
            }
            kept = 1;
        } else {
            (b, fb) = (m, fm);
            if kept == -1 {
                fa *= 0.5;
            }
            kept = -1;
        }
    }
    0.5 * (a + b)
}

/// The first `t` in `[tmin, tmax]` at which the ray `origin + t dir` (grid units) meets the
/// zero set of voxel `voxel`'s trilinear function (corner values `f`), within the voxel.
pub fn intersect_voxel(
    origin: Vec3,
    dir: Vec3,
    tmin: f32,
    tmax: f32,
    voxel: [u32; 3],
    f: &[f32; 8],
) -> Option<f32> {
    // NaN or crossed bounds (as a NaN `tmin` from a callback) bound nothing.
    if !(tmin <= tmax) {
        return None;
    }
    let (o, d) = (origin.as_dvec3(), dir.as_dvec3());
    let lo = DVec3::from_array(voxel.map(f64::from));
    let (mut t0, mut t1) = (f64::from(tmin), f64::from(tmax));
    for axis in 0..3 {
        if d[axis] == 0.0 {
            if o[axis] < lo[axis] || o[axis] > lo[axis] + 1.0 {
                return None;
            }
            continue;
        }
        let near = (lo[axis] - o[axis]) / d[axis];
        let far = (lo[axis] + 1.0 - o[axis]) / d[axis];
        t0 = t0.max(near.min(far));
        t1 = t1.min(near.max(far));
    }
    // A span with an infinite end (a ray with no finite `tmax` along an axis it does not
    // cross) or NaN ends (a NaN ray) has no voxel-sized piece to search.
    if !(t0 <= t1) || !t0.is_finite() || !t1.is_finite() {
        return None;
    }
    // Measured from where the ray enters, so the coefficients stay of the voxel's size.
    let p = o + t0 * d - lo;
    let poly = cubic(f, p, d);
    let span = t1 - t0;
    let mut ends = [0.0, span, span, span];
    if let Some((r0, r1)) = quadratic_roots(3.0 * poly[3], 2.0 * poly[2], poly[1]) {
        // `max`/`min`, not `clamp`: this runs in Embree's `extern "C"` callbacks, where a
        // panic (clamp's, on a NaN bound) would abort.
        ends[1] = r0.max(0.0).min(span);
        ends[2] = r1.max(0.0).min(span);
    }
    let mut found = None;
    for piece in ends.windows(2) {
        let (a, b) = (piece[0], piece[1]);
        let (fa, fb) = (eval(poly, a), eval(poly, b));
        if fa == 0.0 {
            found = Some(a);
        } else if fb == 0.0 {
            found = Some(b);
        } else if (fa < 0.0) != (fb < 0.0) {
            found = Some(bracketed_root(poly, (a, b), (fa, fb)));
        }
        if found.is_some() {
            break;
        }
    }
    let t = (t0 + found?) as f32;
    Some(t.max(tmin).min(tmax))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::splitmix::SplitMix64;

    /// The trilinear function of corner values `f` at voxel-local `p`.
    fn trilinear(f: &[f32; 8], p: DVec3) -> f64 {
        (0..8)
            .map(|c| {
                let w = |bit: usize, t: f64| if c >> bit & 1 == 1 { t } else { 1.0 - t };
                f64::from(f[c]) * w(0, p.x) * w(1, p.y) * w(2, p.z)
            })
            .sum()
    }

    /// The first sign change (or zero) of the function along the ray, marched in `steps`
    /// steps over the ray's span in the voxel at `voxel`.
    fn marched(f: &[f32; 8], o: DVec3, d: DVec3, span: (f64, f64), steps: usize) -> Option<f64> {
        let value = |t: f64| trilinear(f, o + t * d);
        let mut previous = value(span.0);
        if previous == 0.0 {
            return Some(span.0);
        }
        for i in 1..=steps {
            let t = span.0 + (span.1 - span.0) * i as f64 / steps as f64;
            let now = value(t);
            if now == 0.0 || (now < 0.0) != (previous < 0.0) {
                return Some(t);
            }
            previous = now;
        }
        None
    }

    /// Random rays through random voxels: the first root agrees with a fine march, except
    /// where the march cannot see two roots closer than its step (counted, and rare).
    #[test]
    fn first_root_matches_a_fine_march() {
        let mut rng = SplitMix64(7);
        let mut unit = || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        let (mut hits, mut disagreements) = (0, 0);
        for _ in 0..4000 {
            let f: [f32; 8] = std::array::from_fn(|_| (unit() * 2.0 - 1.0) as f32);
            let voxel = [3, 5, 2];
            let lo = DVec3::new(3.0, 5.0, 2.0);
            let target = lo + DVec3::new(unit(), unit(), unit());
            let origin = lo + DVec3::new(unit(), unit(), unit()) * 6.0 - 2.5;
            let d = (target - origin).normalize() * (0.5 + unit());
            let (o32, d32) = (origin.as_vec3(), d.as_vec3());
            let (o, d) = (o32.as_dvec3(), d32.as_dvec3());
            // The ray's span in the voxel, as the marcher sees it.
            let (mut t0, mut t1) = (0.0f64, 1e30f64);
            for axis in 0..3 {
                let a = (lo[axis] - o[axis]) / d[axis];
                let b = (lo[axis] + 1.0 - o[axis]) / d[axis];
                t0 = t0.max(a.min(b));
                t1 = t1.min(a.max(b));
            }
            let found = intersect_voxel(o32, d32, 0.0, f32::INFINITY, voxel, &f);
            if t0 >= t1 {
                assert_eq!(found, None);
                continue;
            }
            let step = (t1 - t0) / 20000.0;
            let expected = marched(&f, o - lo, d, (t0, t1), 20000);
            match (found, expected) {
                (Some(t), Some(e)) => {
                    hits += 1;
                    if (f64::from(t) - e).abs() > step * 1.01 + 1e-5 {
                        disagreements += 1;
                    } else {
                        let v = trilinear(&f, o + f64::from(t) * d - lo);
                        assert!(v.abs() < 1e-4, "value {v} at the root");
                    }
                }
                (None, None) => {}
                _ => disagreements += 1,
            }
        }
        assert!(hits > 500, "{hits} hits");
        assert!(disagreements <= hits / 200, "{disagreements} of {hits}");
    }

    #[test]
    fn a_plane_is_hit_where_it_is() {
        // f = x - 0.25 in voxel (0, 0, 0): the plane x = 0.25.
        let f = [-0.25, 0.75, -0.25, 0.75, -0.25, 0.75, -0.25, 0.75];
        let t = intersect_voxel(Vec3::new(-1.0, 0.5, 0.5), Vec3::X, 0.0, 10.0, [0, 0, 0], &f);
        assert_eq!(t, Some(1.25));
        // Beyond tmax, behind tmin, or outside the voxel: no hit.
        assert_eq!(
            intersect_voxel(Vec3::new(-1.0, 0.5, 0.5), Vec3::X, 0.0, 1.0, [0, 0, 0], &f),
            None
        );
        assert_eq!(
            intersect_voxel(Vec3::new(-1.0, 0.5, 0.5), Vec3::X, 1.5, 9.0, [0, 0, 0], &f),
            None
        );
        assert_eq!(
            intersect_voxel(Vec3::new(-1.0, 1.5, 0.5), Vec3::X, 0.0, 9.0, [0, 0, 0], &f),
            None
        );
    }

    /// Rays with infinite or NaN parts find nothing, and do not panic (Embree's callbacks
    /// call this, and a panic there would abort).
    #[test]
    fn infinite_and_nan_rays_are_misses() {
        let f = [-0.25, 0.75, -0.25, 0.75, -0.25, 0.75, -0.25, 0.75];
        let (inf, nan) = (f32::INFINITY, f32::NAN);
        let cases = [
            // Along an axis the voxel spans, from infinitely far: t0 = t1 = -inf.
            (Vec3::new(-inf, 0.5, 0.5), Vec3::X, 0.0, inf),
            (Vec3::new(-inf, 0.5, 0.5), Vec3::X, -inf, inf),
            (Vec3::new(-1.0, 0.5, 0.5), Vec3::X, -inf, -inf),
            (Vec3::new(-1.0, 0.5, 0.5), Vec3::X, inf, inf),
            (Vec3::new(-1.0, 0.5, 0.5), Vec3::X, nan, 10.0),
            (Vec3::new(-1.0, 0.5, 0.5), Vec3::X, 0.0, nan),
            (Vec3::new(nan, 0.5, 0.5), Vec3::X, 0.0, inf),
            (Vec3::new(-1.0, 0.5, 0.5), Vec3::new(nan, 0.0, 0.0), 0.0, 10.0),
            (Vec3::new(-1.0, 0.5, 0.5), Vec3::new(inf, 0.0, 0.0), 0.0, 10.0),
        ];
        for (origin, dir, tmin, tmax) in cases {
            let t = intersect_voxel(origin, dir, tmin, tmax, [0, 0, 0], &f);
            assert_eq!(t, None, "{origin} {dir} [{tmin}, {tmax}]");
        }
    }
}
