//! `sobol_burley::sample_4d(index, 0, seed)`, bit for bit, with the Sobol matrix applied
//! by two byte-indexed tables instead of one XOR per set bit of the (scrambled, so about
//! half-full) 16-bit index: one draw is four numbers, and a path makes one or two draws per
//! bounce, so this loop was ~4 % of a Cornell box render's instructions. The crate stays
//! the definition: the tables are built from its `sobol_rev`, and the tests compare.

use sobol_burley::parts::{hash, owen_scramble_rev, sobol_rev, u32_to_f32_norm};
use std::sync::LazyLock;

/// The first dimension set's four Sobol dimensions for the top and the next byte of a
/// bit-reversed index (the sequence uses only the top 16 bits: 2¹⁶ samples). The matrix is
/// linear over XOR, so the value of the whole index is the XOR of the two entries.
struct ByteTables {
    top: [[u32; 4]; 256],
    next: [[u32; 4]; 256],
}

static TABLES: LazyLock<ByteTables> = LazyLock::new(|| {
    let row = |index_rev: u32| std::array::from_fn(|d| sobol_rev(index_rev, d as u32));
    ByteTables {
        top: std::array::from_fn(|b| row((b as u32) << 24)),
        next: std::array::from_fn(|b| row((b as u32) << 16)),
    }
});

/// Sample `index` (< 2¹⁶) of the four-dimensional Owen-scrambled Sobol sequence `seed`.
pub fn sample_4d(index: u32, seed: u32) -> [f32; 4] {
    debug_assert!(index < 1 << 16);
    // The index is shuffled per seed (a nested uniform scramble), then the matrix applied.
    let shuffled_rev = owen_scramble_rev(index.reverse_bits(), hash(seed ^ 0x79c6_8e4a));
    let tables = &*TABLES;
    let top = &tables.top[(shuffled_rev >> 24) as usize];
    let next = &tables.next[((shuffled_rev >> 16) & 0xff) as usize];
    // The crate's per-dimension scramble seeds (for dimension set 0).
    const DIMENSION_KEYS: [u32; 4] = [0x912f_69ba, 0x174f_18ab, 0x691e_72ca, 0xb40c_c1b8];
    let seed = seed.wrapping_mul(0x9c8f_2d3b);
    std::array::from_fn(|d| {
        let sobol_rev = top[d] ^ next[d];
        let scrambled = owen_scramble_rev(sobol_rev, hash(seed ^ DIMENSION_KEYS[d]));
        u32_to_f32_norm(scrambled.reverse_bits())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equals_the_crate_bit_for_bit() {
        let mut seed = 0x2545_f491_u32;
        for index in (0..1 << 16).step_by(7).chain([0, 1, 2, 3, 63, 64, 65_535]) {
            seed = hash(seed);
            for s in [seed, 0, u32::MAX, index] {
                assert_eq!(
                    sample_4d(index, s).map(f32::to_bits),
                    sobol_burley::sample_4d(index, 0, s).map(f32::to_bits),
                    "index {index}, seed {s:#x}"
                );
            }
        }
    }
}
