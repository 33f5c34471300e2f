//! Sobol draws made ahead for many streams at once. A bounce of the batched path tracer
//! draws a light sample's four numbers and then its BSDF's: made one path at a time, each
//! draw is a chain of dependent multiplies the CPU waits on; made for 8 paths' two draws
//! together, the same u32 arithmetic fills vector registers.

use super::SampleStream;
use super::sobol::{self, LANES};

/// Makes, for each stream of `streams` listed by `which`, its next two 4-D draws (at its
/// next dimension and four after) and keeps them in the stream. `next_4d` and the rest
/// then return them instead of computing them: the same values, bit for bit, whichever
/// draws a path ends up making. Streams that do not draw Sobol sets are left alone.
pub fn draw_ahead(streams: &mut [SampleStream], which: impl Iterator<Item = u32>) {
    pulp::Arch::new().dispatch(DrawAhead { streams, which });
}

/// Streams per call of the lane kernel: two draws each.
const STREAMS: usize = LANES / 2;

struct DrawAhead<'a, Which> {
    streams: &'a mut [SampleStream],
    which: Which,
}

impl<Which: Iterator<Item = u32>> pulp::WithSimd for DrawAhead<'_, Which> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let mut chosen = [0u32; STREAMS];
        let mut count = 0;
        for i in self.which {
            if self.streams[i as usize].draws_sobol() {
                chosen[count] = i;
                count += 1;
                if count == STREAMS {
                    draw_for(self.streams, &chosen);
                    count = 0;
                }
            }
        }
        if count > 0 {
            draw_for(self.streams, &chosen[..count]);
        }
    }
}

/// The two draws of each of `chosen` (at most `STREAMS`; a short list's last stream fills
/// the spare lanes, whose values are not kept).
#[inline(always)]
fn draw_for(streams: &mut [SampleStream], chosen: &[u32]) {
    // Each stream is read once, for both of its lanes.
    let (mut indices, mut prefixes, mut dimensions) = ([0u32; LANES], [0u64; LANES], [0u64; LANES]);
    for k in 0..STREAMS {
        let stream = &streams[chosen[k.min(chosen.len() - 1)] as usize];
        for half in 0..2 {
            indices[2 * k + half] = stream.sample as u32;
            prefixes[2 * k + half] = stream.scramble_prefix;
            dimensions[2 * k + half] = stream.dimension + 4 * half as u64;
        }
    }
    // A plain loop, not `array::from_fn` (see `sample_4d_lanes`).
    let mut seeds = [0u32; LANES];
    for ((seed, &prefix), &dimension) in seeds.iter_mut().zip(&prefixes).zip(&dimensions) {
        *seed = super::sobol_seed(prefix, dimension);
    }
    let values = sobol::sample_4d_lanes(&indices, &seeds);
    for (k, &i) in chosen.iter().enumerate() {
        let stream = &mut streams[i as usize];
        stream.ahead_at = stream.dimension;
        stream.ahead = [0, 1].map(|half| std::array::from_fn(|d| values[d][2 * k + half]));
    }
}

/// `stream.pixel_position(index, count, jitter)` of every stream of `streams`, in order,
/// into `positions`: the Sobol streams' draws made 16 at a time, as `draw_ahead` makes a
/// bounce's (one at a time, this draw was 1.6 % of a Cornell box render's time).
pub fn pixel_positions(
    streams: &mut [SampleStream],
    (index, count, jitter): (u32, u32, bool),
    positions: &mut Vec<glam::Vec2>,
) {
    positions.clear();
    pulp::Arch::new().dispatch(PixelDraws { streams, index, count, jitter, positions });
}

struct PixelDraws<'a> {
    streams: &'a mut [SampleStream],
    index: u32,
    count: u32,
    jitter: bool,
    positions: &'a mut Vec<glam::Vec2>,
}

impl pulp::WithSimd for PixelDraws<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let d = super::RESERVED_BASE + super::SLOT_PIXEL;
        for chunk in self.streams.chunks_mut(LANES) {
            // Other samplers, unjittered positions and samples past the Sobol range draw
            // one at a time, as `pixel_position` does: no lanes computed for nothing.
            if !(self.jitter && chunk.iter().any(SampleStream::draws_sobol)) {
                let (index, count, jitter) = (self.index, self.count, self.jitter);
                let draw = |s: &mut SampleStream| s.pixel_position(index, count, jitter);
                self.positions.extend(chunk.iter_mut().map(draw));
                continue;
            }
            // A short chunk's spare lanes repeat its last stream; their values are not kept.
            let stream = |j: usize| &chunk[j.min(chunk.len() - 1)];
            let indices: [u32; LANES] = std::array::from_fn(|j| stream(j).sample as u32);
            let seeds: [u32; LANES] =
                std::array::from_fn(|j| super::sobol_seed(stream(j).scramble_prefix, d));
            let values = sobol::sample_4d_lanes(&indices, &seeds);
            for (j, stream) in chunk.iter_mut().enumerate() {
                // As `pixel_position` draws it: its reserved Sobol pair, where it has one.
                self.positions.push(if self.jitter && stream.draws_sobol() {
                    glam::Vec2::new(values[0][j], values[1][j])
                } else {
                    stream.pixel_position(self.index, self.count, self.jitter)
                });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::SamplerKind;
    use super::*;

    /// Streams at assorted samples and dimensions, Sobol and not, drawn ahead in a batch
    /// then by the usual calls, against fresh streams that only make the usual calls.
    #[test]
    fn draws_made_ahead_are_the_draws_made_in_turn() {
        let kinds = [SamplerKind::Sobol, SamplerKind::Independent, SamplerKind::Stratified];
        let fresh = |i: u64| {
            let kind = kinds[(i % 7 % 3) as usize];
            let sample = if i.is_multiple_of(11) { (1 << 16) + i } else { i * 37 % 4096 };
            let mut stream = SampleStream::new(kind, 5, i * 131, sample);
            for _ in 0..i % 5 {
                stream.next_4d();
            }
            stream.next_1d();
            stream
        };
        let mut ahead: Vec<SampleStream> = (0..40).map(fresh).collect();
        let which: Vec<u32> = (0..40).filter(|i| i % 4 != 3).collect();
        draw_ahead(&mut ahead, which.iter().copied());
        let drawn_ahead: Vec<usize> =
            (0..40).filter(|&i| ahead[i].ahead_at != super::super::NOT_AHEAD).collect();
        let sobol: Vec<usize> = which
            .iter()
            .map(|&i| i as usize)
            .filter(|&i| ahead[i].kind == SamplerKind::Sobol && ahead[i].sample < 1 << 16)
            .collect();
        assert_eq!(drawn_ahead, sobol);
        assert!(sobol.len() > STREAMS, "a full and a partial batch");
        // Three 4-D draws (two made ahead, one not) and a 1-D one, as bits.
        let draws = |stream: &mut SampleStream| -> Vec<u32> {
            let sets = [stream.next_4d(), stream.next_4d(), stream.next_4d()];
            sets.concat().into_iter().chain([stream.next_1d()]).map(f32::to_bits).collect()
        };
        for (i, stream) in ahead.iter_mut().enumerate() {
            let (made, expected) = (draws(stream), draws(&mut fresh(i as u64)));
            assert_eq!(made, expected, "stream {i}");
        }
    }

    /// Pixel positions drawn 16 at a time are each stream's own, for every sampler, with
    /// and without jitter, in full and short chunks.
    #[test]
    fn pixel_positions_are_each_streams_own() {
        for kind in [SamplerKind::Sobol, SamplerKind::Independent, SamplerKind::Stratified] {
            for jitter in [true, false] {
                for (sample, count) in [(0, 1), (5, 16), (70_000, 80_000)] {
                    let fresh = |pixel: u64| SampleStream::new(kind, 3, pixel, sample);
                    let mut streams: Vec<SampleStream> = (0..37).map(fresh).collect();
                    let mut positions = Vec::new();
                    let (index, key) = (sample as u32, (kind, jitter, sample));
                    pixel_positions(&mut streams, (index, count, jitter), &mut positions);
                    assert_eq!(positions.len(), 37);
                    for (pixel, (position, stream)) in positions.iter().zip(&streams).enumerate() {
                        let mut alone = fresh(pixel as u64);
                        let expected = alone.pixel_position(index, count, jitter);
                        assert_eq!(
                            position.to_array().map(f32::to_bits),
                            expected.to_array().map(f32::to_bits),
                            "{key:?}"
                        );
                        // The stream goes on from where `pixel_position` leaves it.
                        assert_eq!(stream.clone().next_4d(), alone.next_4d(), "{key:?}");
                    }
                }
            }
        }
    }

    /// A stream drawn ahead and then asked for numbers at other offsets (a 2-D draw first)
    /// computes them as usual.
    #[test]
    fn other_draw_patterns_are_unaffected() {
        let mut ahead = vec![SampleStream::new(SamplerKind::Sobol, 9, 4, 17)];
        draw_ahead(&mut ahead, [0].into_iter());
        let mut usual = SampleStream::new(SamplerKind::Sobol, 9, 4, 17);
        for _ in 0..4 {
            assert_eq!(ahead[0].next_2d(), usual.next_2d());
            assert_eq!(ahead[0].next_1d(), usual.next_1d());
        }
    }
}
