//! Counter-based random numbers: every value is a hash of (seed, pixel, sample, dimension),
//! so an image does not depend on the thread count or the order of work, and both backends
//! see exactly the same rays.

mod ahead;
pub mod alias;
#[cfg(test)]
pub(crate) mod chi_square;
pub mod filter;
pub mod piecewise;
mod pixel;
mod sobol;
pub mod spherical_rectangle;
#[cfg(test)]
mod spherical_tests;
pub mod spherical_triangle;
mod warps;

use crate::splitmix::mix64;
pub use ahead::{draw_ahead, pixel_positions};
use glam::Vec2;
pub use pixel::pixel_sample;
pub use warps::{
    concentric_disk, cosine_hemisphere, cosine_power_hemisphere, cosine_power_pdf,
    frame_from_normal, uniform_sphere, uniform_triangle,
};

/// Hash of the four counters.
pub fn hash4(seed: u64, pixel: u64, sample: u64, dimension: u64) -> u64 {
    hash_dimension(hash_prefix(seed, pixel, sample), dimension)
}

/// The part of `hash4` that does not depend on the dimension (computed once per stream).
fn hash_prefix(seed: u64, pixel: u64, sample: u64) -> u64 {
    sample_hash(pixel_hash(seed, pixel), sample)
}

/// The part of `hash_prefix` that depends on neither the sample nor the dimension.
#[inline]
fn pixel_hash(seed: u64, pixel: u64) -> u64 {
    mix64(mix64(seed ^ 0x9e37_79b9_7f4a_7c15) ^ pixel)
}

/// `hash_prefix` from the pixel's `pixel_hash`.
#[inline]
fn sample_hash(pixel_hash: u64, sample: u64) -> u64 {
    mix64(pixel_hash ^ sample.wrapping_mul(0x632b_e59b_d9b4_e019))
}

#[inline(always)]
fn hash_dimension(prefix: u64, dimension: u64) -> u64 {
    mix64(prefix ^ dimension.wrapping_mul(0xd6e8_feb8_6659_fd93))
}

/// The scramble of a stream's Sobol draw at dimension `d`, from the stream's
/// `scramble_prefix`: one scrambled sequence per (seed, pixel, draw).
#[inline(always)]
fn sobol_seed(scramble_prefix: u64, d: u64) -> u32 {
    hash_dimension(scramble_prefix, d) as u32
}

/// Uniform float in [0, 1) from the top 24 bits of a hash.
pub fn to_unit_f32(h: u64) -> f32 {
    (h >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
}

/// How a render draws its random numbers. Every kind is a pure function of (seed, pixel,
/// sample, dimension), so images do not depend on threads, order or backend.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SamplerKind {
    /// Owen-scrambled Sobol (Burley 2020, the `sobol_burley` crate): each pixel's samples
    /// are a (0, 2)-sequence in every pair of dimensions, decorrelated between pairs by
    /// seeding ("padding"); hashed numbers beyond its 2¹⁶ samples per pixel.
    #[default]
    Sobol,
    /// Stratified pixel positions (a jittered grid, or Latin-hypercube strata), every other
    /// dimension hashed: embray's sampler before Sobol.
    Stratified,
    /// Every number hashed, pixel positions included.
    Independent,
}

crate::choice::named_choices!(SamplerKind, "sampler", {
    Sobol => "sobol",
    Stratified => "stratified",
    Independent => "independent",
});

/// Samples per pixel the Sobol sequence covers; later samples are hashed.
const SOBOL_SAMPLES: u64 = 1 << 16;

/// The random stream of one camera sample of one pixel. Each call consumes the next
/// dimensions; the integrator asks for dimensions only for effects the scene uses.
///
/// The path tracer's layout: the pixel position, lens point and time come from reserved
/// slots; then per bounce one 4-D draw per light sample (light point 2-D, light choice 2-D)
/// and one for the BSDF (direction 2-D, lobe, Russian roulette). With Sobol each draw is a
/// separately scrambled ("padded") 4-D set whose first two values form a (0, 2)-sequence.
#[derive(Clone, Debug)]
pub struct SampleStream {
    kind: SamplerKind,
    seed: u64,
    pixel: u64,
    sample: u64,
    dimension: u64,
    /// `hash_prefix` of this sample's counters, and of the per-pixel Sobol scrambles (whose
    /// "sample" counter is u64::MAX): each draw then costs one mix.
    sample_prefix: u64,
    scramble_prefix: u64,
    /// The Sobol draws at dimensions `ahead_at` and `ahead_at + 4`, made ahead by
    /// `draw_ahead` for many streams at once (`NOT_AHEAD`: none).
    ahead_at: u64,
    ahead: [[f32; 4]; 2],
}

/// `ahead_at` when no draw was made ahead: no stream reaches this dimension.
const NOT_AHEAD: u64 = 1 << 63;

/// What the streams of one pixel's samples share, hashed once (`stream` then makes each
/// sample's with one mix, not six: a tile's batches made every pixel's anew each sample).
#[derive(Clone, Copy, Debug)]
pub struct PixelStreams {
    kind: SamplerKind,
    seed: u64,
    pixel: u64,
    pixel_hash: u64,
    scramble_prefix: u64,
}

impl PixelStreams {
    pub fn new(kind: SamplerKind, seed: u64, pixel: u64) -> Self {
        let pixel_hash = pixel_hash(seed, pixel);
        let scramble_prefix = sample_hash(pixel_hash, u64::MAX);
        PixelStreams { kind, seed, pixel, pixel_hash, scramble_prefix }
    }

    /// The stream of sample `sample`: `SampleStream::new` of the same counters.
    #[inline]
    pub fn stream(&self, sample: u64) -> SampleStream {
        let PixelStreams { kind, seed, pixel, pixel_hash, scramble_prefix } = *self;
        SampleStream {
            kind,
            seed,
            pixel,
            sample,
            dimension: 0,
            sample_prefix: sample_hash(pixel_hash, sample),
            scramble_prefix,
            ahead_at: NOT_AHEAD,
            ahead: [[0.0; 4]; 2],
        }
    }
}

impl SampleStream {
    pub fn new(kind: SamplerKind, seed: u64, pixel: u64, sample: u64) -> Self {
        PixelStreams::new(kind, seed, pixel).stream(sample)
    }

    /// The first `N` (at most 4) values of the draw that starts at dimension `d`. A Sobol
    /// draw is one padded 4-D set: its first two values form a (0, 2)-sequence, so a draw's
    /// most important pair goes first.
    ///
    /// Inlined up to the draws made ahead, which the batched path tracer's bounces take:
    /// the rest is computed out of line.
    #[inline]
    fn draw<const N: usize>(&self, d: u64) -> [f32; N] {
        // Only Sobol streams have draws made ahead (`draw_ahead`), so those are looked for
        // first: the bounces' draws then cost no test of the stream's kind.
        let values = match d.wrapping_sub(self.ahead_at) {
            0 => self.ahead[0],
            4 => self.ahead[1],
            _ if self.draws_sobol() => self.sobol_draw(d),
            _ => return self.hashed_draw(d),
        };
        std::array::from_fn(|k| values[k])
    }

    #[inline(never)]
    fn sobol_draw(&self, d: u64) -> [f32; 4] {
        sobol::sample_4d(self.sample as u32, sobol_seed(self.scramble_prefix, d))
    }

    #[inline(never)]
    fn hashed_draw<const N: usize>(&self, d: u64) -> [f32; N] {
        std::array::from_fn(|k| to_unit_f32(hash_dimension(self.sample_prefix, d + k as u64)))
    }

    /// Whether this stream's draws are Sobol sets (else hashed numbers).
    fn draws_sobol(&self) -> bool {
        self.kind == SamplerKind::Sobol && self.sample < SOBOL_SAMPLES
    }

    #[inline]
    fn next<const N: usize>(&mut self) -> [f32; N] {
        let values = self.draw::<N>(self.dimension);
        self.dimension += N as u64;
        values
    }

    pub fn next_1d(&mut self) -> f32 {
        self.next::<1>()[0]
    }

    pub fn next_2d(&mut self) -> Vec2 {
        Vec2::from_array(self.next::<2>())
    }

    /// Four values drawn together (with Sobol, one 4-D set: the first two are the best
    /// stratified pair).
    #[inline]
    pub fn next_4d(&mut self) -> [f32; 4] {
        self.next::<4>()
    }

    /// A value from a reserved dimension `slot`, outside the sequential stream: effects that
    /// only some scenes use (lens, time) draw from here, so turning them on or off does not
    /// shift the numbers every other decision sees.
    pub fn reserved_1d(&self, slot: u64) -> f32 {
        self.draw::<1>(RESERVED_BASE + slot)[0]
    }

    pub fn reserved_2d(&self, slot: u64) -> Vec2 {
        Vec2::from_array(self.draw::<2>(RESERVED_BASE + slot))
    }

    /// The sample's position inside its pixel (`jitter`: else stratum centres).
    pub fn pixel_position(&mut self, index: u32, count: u32, jitter: bool) -> Vec2 {
        match self.kind {
            SamplerKind::Stratified => {
                let offset = jitter.then(|| self.next_2d());
                pixel_sample(index, count, offset, self.seed, self.pixel)
            }
            _ if !jitter => pixel_sample(index, count, None, self.seed, self.pixel),
            SamplerKind::Sobol | SamplerKind::Independent => self.reserved_2d(SLOT_PIXEL),
        }
    }
}

/// Reserved dimensions start far beyond any path's sequential use.
const RESERVED_BASE: u64 = 1 << 40;
/// Reserved slots: lens position (2 dimensions), time, and the position in the pixel.
pub const SLOT_LENS: u64 = 0;
pub const SLOT_TIME: u64 = 2;
pub const SLOT_PIXEL: u64 = 4;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stream_is_a_pure_function_of_its_counters() {
        let a: Vec<f32> = {
            let mut s = SampleStream::new(SamplerKind::Independent, 3, 10, 2);
            (0..8).map(|_| s.next_1d()).collect()
        };
        let mut s = SampleStream::new(SamplerKind::Independent, 3, 10, 2);
        let b: Vec<f32> = (0..8).map(|_| s.next_1d()).collect();
        assert_eq!(a, b);
        let mean = (0..10_000).map(|i| to_unit_f32(hash4(1, i, 0, 0)) as f64).sum::<f64>() / 1e4;
        assert!((mean - 0.5).abs() < 0.01);
    }

    /// A pixel's streams made from its shared hashes are, field by field, the streams every
    /// image so far was drawn with: prefixes of three chained mixes of all the counters.
    #[test]
    fn pixel_streams_make_the_streams_new_made() {
        let prefix = |seed: u64, pixel: u64, sample: u64| {
            let h = mix64(mix64(seed ^ 0x9e37_79b9_7f4a_7c15) ^ pixel);
            mix64(h ^ sample.wrapping_mul(0x632b_e59b_d9b4_e019))
        };
        for kind in [SamplerKind::Sobol, SamplerKind::Stratified, SamplerKind::Independent] {
            for (seed, pixel) in [(0, 0), (7, 65_535), (u64::MAX, 12)] {
                let shared = PixelStreams::new(kind, seed, pixel);
                for sample in [0, 1, 70_000, u64::MAX - 1] {
                    let made = shared.stream(sample);
                    let old = SampleStream {
                        kind,
                        seed,
                        pixel,
                        sample,
                        dimension: 0,
                        sample_prefix: prefix(seed, pixel, sample),
                        scramble_prefix: prefix(seed, pixel, u64::MAX),
                        ahead_at: NOT_AHEAD,
                        ahead: [[0.0; 4]; 2],
                    };
                    assert_eq!(format!("{made:?}"), format!("{old:?}"));
                }
            }
        }
    }
}
