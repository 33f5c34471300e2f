//! Where the samples of a pixel fall inside it: stratified, unbiased for any count.

use super::hash4;
use glam::Vec2;

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_cover_every_stratum_once() {
        for count in [1u32, 2, 3, 4, 7, 9, 16, 30] {
            let side = (count as f64).sqrt().round() as u32;
            let square = side * side == count;
            // Square counts: each grid cell once; others: each row and column stratum once.
            let mut cells = vec![0; count as usize];
            let mut rows = vec![0; count as usize];
            let mut cols = vec![0; count as usize];
            for i in 0..count {
                let p = pixel_sample(i, count, Some(Vec2::splat(0.3)), 7, 1234);
                assert!(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0);
                if square {
                    let (cx, cy) = ((p.x * side as f32) as u32, (p.y * side as f32) as u32);
                    cells[(cy * side + cx) as usize] += 1;
                } else {
                    cols[(p.x * count as f32) as usize] += 1;
                    rows[(p.y * count as f32) as usize] += 1;
                }
            }
            let covered = if square {
                cells.iter().all(|&n| n == 1)
            } else {
                rows.iter().chain(&cols).all(|&n| n == 1)
            };
            assert!(covered, "count {count}: cells {cells:?} rows {rows:?} cols {cols:?}");
        }
    }

    #[test]
    fn one_sample_without_jitter_is_the_pixel_centre() {
        assert_eq!(pixel_sample(0, 1, None, 0, 0), Vec2::splat(0.5));
    }
}
