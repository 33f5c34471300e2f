//! Counter-based random numbers: every value is a hash of (seed, pixel, sample, dimension),
//! so an image does not depend on the thread count or the order of work, and both backends
//! see exactly the same rays.

use glam::{Vec2, Vec3};

/// A finaliser with full avalanche (the `splitmix64` output function).
fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Hash of the four counters.
pub fn hash4(seed: u64, pixel: u64, sample: u64, dimension: u64) -> u64 {
    let mut h = mix64(seed ^ 0x9e37_79b9_7f4a_7c15);
    h = mix64(h ^ pixel);
    h = mix64(h ^ sample.wrapping_mul(0x632b_e59b_d9b4_e019));
    mix64(h ^ dimension.wrapping_mul(0xd6e8_feb8_6659_fd93))
}

/// Uniform float in [0, 1) from the top 24 bits of a hash.
pub fn to_unit_f32(h: u64) -> f32 {
    (h >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
}

/// The random stream of one camera sample of one pixel. Each call consumes the next
/// dimension; the integrator asks for dimensions only for effects the scene uses.
#[derive(Clone, Debug)]
pub struct SampleStream {
    seed: u64,
    pixel: u64,
    sample: u64,
    dimension: u64,
}

impl SampleStream {
    pub fn new(seed: u64, pixel: u64, sample: u64) -> Self {
        SampleStream { seed, pixel, sample, dimension: 0 }
    }

    pub fn next_1d(&mut self) -> f32 {
        let h = hash4(self.seed, self.pixel, self.sample, self.dimension);
        self.dimension += 1;
        to_unit_f32(h)
    }

    pub fn next_2d(&mut self) -> Vec2 {
        let x = self.next_1d();
        Vec2::new(x, self.next_1d())
    }

    /// A value from a reserved dimension `slot`, outside the sequential stream: effects that
    /// only some scenes use (lens, time) draw from here, so turning them on or off does not
    /// shift the numbers every other decision sees.
    pub fn reserved_1d(&self, slot: u64) -> f32 {
        to_unit_f32(hash4(self.seed, self.pixel, self.sample, RESERVED_BASE + slot))
    }

    pub fn reserved_2d(&self, slot: u64) -> Vec2 {
        Vec2::new(self.reserved_1d(slot), self.reserved_1d(slot + 1))
    }
}

/// Reserved dimensions start far beyond any path's sequential use.
const RESERVED_BASE: u64 = 1 << 40;
/// Reserved slots: lens position (2 dimensions) and time.
pub const SLOT_LENS: u64 = 0;
pub const SLOT_TIME: u64 = 2;

/// Position of sample `index` of `count` inside the unit pixel square. Perfect squares get a
/// jittered grid; other counts get Latin-hypercube strata (one per row and per column), both
/// unbiased. Without jitter each sample sits at its stratum centre (1 spp: the pixel centre).
pub fn pixel_sample(index: u32, count: u32, jitter: Option<Vec2>, seed: u64, pixel: u64) -> Vec2 {
    let offset = jitter.unwrap_or(Vec2::splat(0.5));
    let side = (count as f64).sqrt().round() as u32;
    if side * side == count {
        let (col, row) = (index % side, index / side);
        return Vec2::new(
            (col as f32 + offset.x) / side as f32,
            (row as f32 + offset.y) / side as f32,
        );
    }
    // Pair column stratum `index` with row stratum perm(index): an affine permutation whose
    // stride is coprime with `count`, chosen per pixel from the hash.
    let h = hash4(seed, pixel, u64::MAX, 0);
    let mut stride = (h % count as u64) as u32 | 1;
    while gcd(stride, count) != 1 {
        stride += 2;
    }
    let shift = ((h >> 32) % count as u64) as u32;
    let row = ((index as u64 * stride as u64 + shift as u64) % count as u64) as u32;
    Vec2::new((index as f32 + offset.x) / count as f32, (row as f32 + offset.y) / count as f32)
}

fn gcd(mut a: u32, mut b: u32) -> u32 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// Cosine-weighted direction about +Z (Malley's method); pdf = cos θ / π.
pub fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = concentric_disk(u);
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    Vec3::new(d.x, d.y, z)
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_cover_every_stratum_once() {
        for count in [1u32, 2, 3, 4, 7, 9, 16, 30] {
            let mut rows = vec![0; count as usize];
            let mut cols = vec![0; count as usize];
            for i in 0..count {
                let p = pixel_sample(i, count, Some(Vec2::splat(0.3)), 7, 1234);
                assert!(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0);
                let side = (count as f64).sqrt().round() as u32;
                if side * side != count {
                    cols[(p.x * count as f32) as usize] += 1;
                    rows[(p.y * count as f32) as usize] += 1;
                }
            }
            let side = (count as f64).sqrt().round() as u32;
            if side * side != count {
                assert!(rows.iter().chain(&cols).all(|&n| n == 1), "count {count}");
            }
        }
    }

    #[test]
    fn one_sample_without_jitter_is_the_pixel_centre() {
        assert_eq!(pixel_sample(0, 1, None, 0, 0), Vec2::splat(0.5));
    }

    #[test]
    fn stream_is_a_pure_function_of_its_counters() {
        let a: Vec<f32> = {
            let mut s = SampleStream::new(3, 10, 2);
            (0..8).map(|_| s.next_1d()).collect()
        };
        let mut s = SampleStream::new(3, 10, 2);
        let b: Vec<f32> = (0..8).map(|_| s.next_1d()).collect();
        assert_eq!(a, b);
        let mean = (0..10_000).map(|i| to_unit_f32(hash4(1, i, 0, 0)) as f64).sum::<f64>() / 1e4;
        assert!((mean - 0.5).abs() < 0.01);
    }
}
