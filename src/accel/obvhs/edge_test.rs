//! A conservative pre-test for `crate::intersect::intersect_triangle`: rejects most of the
//! triangles a ray passes outside of without the exact test's FMA-based edge functions.

use super::triangle_block::TriangleBlock;
use crate::intersect::intersect_triangle;
use glam::Vec3;
use wide::f32x4;

/// The per-ray part of `geometry::intersect_triangle` (Woop et al.'s permutation, with the
/// axis the direction is largest along, `KZ`, last, and shear), and a conservative version
/// of its edge test.
///
/// `intersect_triangle` returns `None` whenever its three edge functions (computed with FMA,
/// falling back to f64 for zeros) have mixed signs. Each of those is a·b − c·d of the same
/// sheared vertex coordinates computed here (same operations, so the same bits), and its
/// sign is always the sign of the exact a·b − c·d (Kahan's FMA form is exact for a zero and
/// within 2 ulps otherwise; the f64 fallback rounds once). Here a·b − c·d is computed in
/// plain f32 with an error bound: where the estimate exceeds its bound its sign is the exact
/// sign, so two such estimates of opposite signs prove the exact test returns `None`.
/// Only then does [`EdgeTest::may_hit`] say no; `intersect_triangle` decides the rest.
pub(super) struct EdgeTest<const KZ: usize> {
    origin: Vec3,
    shear: (f32, f32),
}

/// [`permute`] of the lanes' coordinates.
#[inline(always)]
fn permute_lanes<const KZ: usize>([x, y, z]: [f32x4; 3]) -> [f32x4; 3] {
    match KZ {
        0 => [y, z, x],
        1 => [z, x, y],
        _ => [x, y, z],
    }
}

/// `intersect_triangle`'s `permute` for `dir.abs().max_position() == KZ`.
#[inline(always)]
fn permute<const KZ: usize>(v: Vec3) -> Vec3 {
    match KZ {
        0 => Vec3::new(v.y, v.z, v.x),
        1 => Vec3::new(v.z, v.x, v.y),
        _ => Vec3::new(v.x, v.y, v.z),
    }
}

impl<const KZ: usize> EdgeTest<KZ> {
    /// As `intersect_triangle` sets up for `dir`, whose largest component is `KZ`.
    #[inline(always)]
    pub(super) fn new(origin: Vec3, dir: Vec3) -> Self {
        let d = permute::<KZ>(dir);
        EdgeTest { origin, shear: (-d.x / d.z, -d.y / d.z) }
    }

    /// False only if `intersect_triangle(origin, dir, .., tri)` certainly returns `None`.
    /// (The reference for [`EdgeTest::may_hit_block`], which the BVH uses.)
    #[cfg(test)]
    fn may_hit(&self, tri: &[Vec3; 3]) -> bool {
        let (sx, sy) = self.shear;
        // `permute(v - origin)`, then `p.x += sx * p.z; p.y += sy * p.z`, as there.
        let sheared = |v: Vec3| {
            let p = permute::<KZ>(v - self.origin);
            (p.x + sx * p.z, p.y + sy * p.z)
        };
        let (p0, p1, p2) = (sheared(tri[0]), sheared(tri[1]), sheared(tri[2]));
        // Sign of a·b − c·d: 1 or -1 where certain, 0 where not.
        let sign = |a: f32, b: f32, c: f32, d: f32| {
            let (ab, cd) = (a * b, c * d);
            let estimate = ab - cd;
            // Two products and a difference, each within half an ulp: 4 ε is twice the
            // bound; the absolute term covers subnormal products.
            let bound = (ab.abs() + cd.abs()) * (4.0 * f32::EPSILON) + 1e-36;
            // NaN and infinities compare false both ways: left to the exact test.
            (estimate > bound, estimate < -bound)
        };
        let e0 = sign(p1.0, p2.1, p1.1, p2.0);
        let e1 = sign(p2.0, p0.1, p2.1, p0.0);
        let e2 = sign(p0.0, p1.1, p0.1, p1.0);
        let positive = e0.0 | e1.0 | e2.0;
        let negative = e0.1 | e1.1 | e2.1;
        !(negative & positive)
    }

    /// [`EdgeTest::may_hit`] for every triangle of `block` at once (the same operations per
    /// lane, so the same answers): bit i set unless triangle i certainly misses.
    #[inline(always)]
    pub(super) fn may_hit_block(&self, block: &TriangleBlock) -> u32 {
        let (sx, sy) = (f32x4::splat(self.shear.0), f32x4::splat(self.shear.1));
        let origin = self.origin.to_array().map(f32x4::splat);
        let sheared = |v: &[f32x4; 3]| {
            let p = permute_lanes::<KZ>([v[0] - origin[0], v[1] - origin[1], v[2] - origin[2]]);
            (p[0] + sx * p[2], p[1] + sy * p[2])
        };
        let [p0, p1, p2] = block.vertices.each_ref().map(sheared);
        let sign = |a: f32x4, b: f32x4, c: f32x4, d: f32x4| {
            let (ab, cd) = (a * b, c * d);
            let estimate = ab - cd;
            let bound =
                (ab.abs() + cd.abs()) * f32x4::splat(4.0 * f32::EPSILON) + f32x4::splat(1e-36);
            (estimate.simd_gt(bound), estimate.simd_lt(-bound))
        };
        let e0 = sign(p1.0, p2.1, p1.1, p2.0);
        let e1 = sign(p2.0, p0.1, p2.1, p0.0);
        let e2 = sign(p0.0, p1.1, p0.1, p1.0);
        let positive = (e0.0 | e1.0 | e2.0).to_bitmask();
        let negative = (e0.1 | e1.1 | e2.1).to_bitmask();
        !(negative & positive) & block.lane_mask()
    }

    /// False only if `intersect_triangle(origin, dir, tmin, tmax, tri)` certainly returns
    /// `None` because its `t` lies outside `[tmin, tmax]` (or it has no `t`): computes `t`
    /// exactly as it does (same operations, same bits) and applies its own test.
    #[inline(always)]
    pub(super) fn in_range(&self, dir: Vec3, tmin: f32, tmax: f32, tri: &[Vec3; 3]) -> bool {
        let normal = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
        let denom = dir.dot(normal);
        let t = (tri[0] - self.origin).dot(normal) / denom;
        // `intersect_triangle` refuses a zero or non-finite `denom` too; the `t` this gives
        // then is NaN or infinite, or is refused by the exact test anyway.
        t > 0.0 && t >= tmin && t <= tmax
    }

    /// Exactly `intersect_triangle(origin, dir, tmin, tmax, tri)` for a triangle
    /// [`EdgeTest::may_hit`] (or `may_hit_block`) let through.
    #[inline(always)]
    pub(super) fn intersect_candidate(
        &self,
        dir: Vec3,
        tmin: f32,
        tmax: f32,
        tri: &[Vec3; 3],
    ) -> Option<(f32, f32, f32)> {
        if !self.in_range(dir, tmin, tmax, tri) {
            return None;
        }
        intersect_triangle(self.origin, dir, tmin, tmax, tri)
    }

    /// Both pre-tests: false only if the exact test certainly misses.
    #[cfg(test)]
    fn passes(&self, dir: Vec3, tmin: f32, tmax: f32, tri: &[Vec3; 3]) -> bool {
        self.may_hit(tri) && self.in_range(dir, tmin, tmax, tri)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::splitmix::SplitMix64 as Rng;

    /// Both pre-tests alone ([`EdgeTest::may_hit`] and [`EdgeTest::in_range`]) for the
    /// ray's axis.
    fn passes(origin: Vec3, dir: Vec3, tmin: f32, tmax: f32, tri: &[Vec3; 3]) -> bool {
        match dir.abs().max_position() {
            0 => EdgeTest::<0>::new(origin, dir).passes(dir, tmin, tmax, tri),
            1 => EdgeTest::<1>::new(origin, dir).passes(dir, tmin, tmax, tri),
            _ => EdgeTest::<2>::new(origin, dir).passes(dir, tmin, tmax, tri),
        }
    }

    /// The pre-tests never reject a triangle `intersect_triangle` hits: on random rays, on
    /// rays through vertices, edge points and shared edges, axis-aligned rays, and at scales
    /// from 1e-6 to 1e6; and they reject most misses.
    #[test]
    fn pre_tests_only_reject_what_the_exact_test_misses() {
        let mut rng = Rng(5);
        let (mut hits, mut misses, mut rejected) = (0, 0, 0);
        for k in 0..200_000 {
            let scale = [1e-6, 1e-3, 1.0, 1e3, 1e6][k % 5];
            let (lo, hi) = (-0.5 * scale, 0.5 * scale);
            let tri = [rng.vec3(lo, hi), rng.vec3(lo, hi), rng.vec3(lo, hi)];
            let origin = rng.vec3(4.0 * lo, 4.0 * hi) + Vec3::splat(scale * [0.0, 1e3][k / 5 % 2]);
            // Aim at a vertex, an edge point, the centre, or anywhere.
            let (a, b) = (rng.unit(), rng.unit());
            let target = match k / 10 % 4 {
                0 => tri[k % 3],
                1 => tri[k % 3] + (tri[(k + 1) % 3] - tri[k % 3]) * a,
                2 => (tri[0] + tri[1] + tri[2]) / 3.0,
                _ => tri[0] + (tri[1] - tri[0]) * a + (tri[2] - tri[0]) * b,
            };
            let mut dir = target - origin;
            if k % 7 == 0 {
                // Axis-aligned: ties in the permutation, zero shear.
                let axis = dir.abs().max_position();
                dir = Vec3::ZERO;
                dir[axis] = 1.0;
            }
            if dir == Vec3::ZERO || !dir.is_finite() {
                continue;
            }
            let tmax = if k % 3 == 0 { f32::INFINITY } else { rng.unit() * 2.0 };
            let tmin = if k % 4 == 0 { rng.unit() * 0.5 } else { 0.0 };
            let exact = intersect_triangle(origin, dir, tmin, tmax, &tri);
            let candidate = passes(origin, dir, tmin, tmax, &tri);
            match exact {
                Some(_) => {
                    hits += 1;
                    assert!(candidate, "ray {k}: {origin} {dir} [{tmin}, {tmax}] {tri:?}");
                }
                None => {
                    misses += 1;
                    rejected += usize::from(!candidate);
                }
            }
        }
        println!("{hits} hits, {misses} misses, {rejected} rejected by the pre-tests");
        assert!(hits > 20_000 && rejected * 10 > misses * 8, "{hits} {misses} {rejected}");
    }

    /// The block pre-test answers exactly what the one-triangle test does, lane by lane, for
    /// blocks of one to four triangles, near and far from the origin.
    #[test]
    fn block_pre_test_is_the_single_pre_test_per_lane() {
        fn check<const KZ: usize>(origin: Vec3, dir: Vec3, triangles: &[[Vec3; 3]]) -> usize {
            let edges = EdgeTest::<KZ>::new(origin, dir);
            let block = TriangleBlock::new(triangles, 0..triangles.len() as u32);
            let mask = edges.may_hit_block(&block);
            for (lane, tri) in triangles.iter().enumerate() {
                assert_eq!(mask & (1 << lane) != 0, edges.may_hit(tri), "{origin} {dir} {tri:?}");
            }
            assert_eq!(mask >> triangles.len(), 0, "unused lanes must stay clear");
            mask.count_ones() as usize
        }
        let mut rng = Rng(9);
        let mut passed = 0;
        for k in 0..20_000 {
            let scale = [1e-3, 1.0, 1e3, 1e6][k % 4];
            let centre = Vec3::splat(scale * [0.0, 10.0][k / 4 % 2]);
            let count = 1 + k % 4;
            let triangles: Vec<[Vec3; 3]> = (0..count)
                .map(|_| std::array::from_fn(|_| centre + rng.vec3(-scale, scale)))
                .collect();
            let origin = centre + rng.vec3(-4.0 * scale, 4.0 * scale);
            let target = (triangles[0][0] + triangles[0][1] + triangles[0][2]) / 3.0;
            let dir = (target - origin + rng.vec3(-0.3 * scale, 0.3 * scale)).normalize_or(Vec3::Z);
            passed += match dir.abs().max_position() {
                0 => check::<0>(origin, dir, &triangles),
                1 => check::<1>(origin, dir, &triangles),
                _ => check::<2>(origin, dir, &triangles),
            };
        }
        assert!(passed > 5_000, "only {passed} lanes passed: too few to test");
    }
}
