//! `sobol_burley::sample_4d(index, 0, seed)`, bit for bit, with the Sobol matrix applied
//! by two byte-indexed tables instead of one XOR per set bit of the (scrambled, so about
//! half-full) 16-bit index: one draw is four numbers, and a path makes one or two draws per
//! bounce, so this loop was ~4 % of a Cornell box render's instructions. The crate stays
//! the definition: the tables are built from its `sobol_rev`, and the tests compare.

use sobol_burley::parts::{
    Int4, hash, hash_int4, owen_scramble_int4_rev, owen_scramble_rev, sobol_rev,
};
use std::sync::LazyLock;

/// The first dimension set's four Sobol dimensions for the top and the next byte of a
/// bit-reversed index (the sequence uses only the top 16 bits: 2¹⁶ samples). The matrix is
/// linear over XOR, so the value of the whole index is the XOR of the two entries.
struct ByteTables {
    top: [Int4; 256],
    next: [Int4; 256],
}

static TABLES: LazyLock<ByteTables> = LazyLock::new(|| {
    let row = |index_rev: u32| {
        Int4::from(std::array::from_fn::<u32, 4, _>(|d| sobol_rev(index_rev, d as u32)))
    };
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
    let sobol_rev = tables.top[(shuffled_rev >> 24) as usize]
        ^ tables.next[((shuffled_rev >> 16) & 0xff) as usize];
    // Then each dimension is Owen-scrambled with the crate's per-dimension seeds (for
    // dimension set 0), four lanes at once as the crate does.
    let dimension_keys = Int4::from([0x912f_69ba, 0x174f_18ab, 0x691e_72ca, 0xb40c_c1b8]);
    let scramble = Int4::from([seed.wrapping_mul(0x9c8f_2d3b); 4]) ^ dimension_keys;
    owen_scramble_int4_rev(sobol_rev, hash_int4(scramble)).reverse_bits().to_f32_norm()
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
