//! Counter-based random numbers: every value is a hash of (seed, pixel, sample, dimension),
//! so an image does not depend on the thread count or the order of work, and both backends
//! see exactly the same rays.

pub mod alias;
mod pixel;
mod warps;

use crate::splitmix::mix64;
use glam::Vec2;
pub use pixel::pixel_sample;
pub use warps::{concentric_disk, cosine_hemisphere, uniform_triangle};

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

#[cfg(test)]
mod tests {
    use super::*;

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
