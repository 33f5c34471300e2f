//! `sobol_burley::sample_4d(index, 0, seed)`, bit for bit, with the Sobol matrix applied
//! by two byte-indexed tables instead of one XOR per set bit of the (scrambled, so about
//! half-full) 16-bit index: one draw is four numbers, and a path makes one or two draws per
//! bounce, so this loop was ~4 % of a Cornell box render's instructions. The crate stays
//! the definition: the tables are built from its `sobol_rev`, and the tests compare.

use sobol_burley::parts::{
    Int4, hash, hash_int4, owen_scramble_int4_rev, owen_scramble_rev, sobol_rev, u32_to_f32_norm,
};
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
    let shuffled_rev = owen_scramble_rev(index.reverse_bits(), hash(seed ^ INDEX_KEY));
    let tables = &*TABLES;
    let sobol_rev = Int4::from(tables.top[(shuffled_rev >> 24) as usize])
        ^ Int4::from(tables.next[((shuffled_rev >> 16) & 0xff) as usize]);
    // Then each dimension is Owen-scrambled with the crate's per-dimension seeds (for
    // dimension set 0), four lanes at once as the crate does.
    let scramble = Int4::from([seed.wrapping_mul(SEED_FACTOR); 4]) ^ Int4::from(DIMENSION_KEYS);
    owen_scramble_int4_rev(sobol_rev, hash_int4(scramble)).reverse_bits().to_f32_norm()
}

/// The crate's keys: of the index shuffle, and of each dimension's scramble (dimension set 0).
const INDEX_KEY: u32 = 0x79c6_8e4a;
const SEED_FACTOR: u32 = 0x9c8f_2d3b;
const DIMENSION_KEYS: [u32; 4] = [0x912f_69ba, 0x174f_18ab, 0x691e_72ca, 0xb40c_c1b8];

/// How many draws `sample_4d_lanes` makes at once.
pub const LANES: usize = 16;

/// `sample_4d(indices[j], seeds[j])` for each lane `j`, as `values[dimension][j]`, bit for bit.
/// Written lane by lane so that the compiler computes the lanes in vector registers: the
/// hashes and scrambles are the same u32 arithmetic as the crate's, only the two table
/// reads go lane by lane.
#[inline(always)]
pub fn sample_4d_lanes(indices: &[u32; LANES], seeds: &[u32; LANES]) -> [[f32; LANES]; 4] {
    // Plain loops, not `array::from_fn`: its closure was called out of line, a lane at a
    // time, where these loops are vectorised.
    let mut shuffled_rev = [0u32; LANES];
    for ((shuffled, &index), &seed) in shuffled_rev.iter_mut().zip(indices).zip(seeds) {
        *shuffled = owen_scramble_rev(index.reverse_bits(), hash(seed ^ INDEX_KEY));
    }
    let tables = &*TABLES;
    let mut sobol_rev = [[0u32; LANES]; 4];
    for (j, &shuffled) in shuffled_rev.iter().enumerate() {
        let top = &tables.top[(shuffled >> 24) as usize];
        let next = &tables.next[((shuffled >> 16) & 0xff) as usize];
        for d in 0..4 {
            sobol_rev[d][j] = top[d] ^ next[d];
        }
    }
    let mut values = [[0.0f32; LANES]; 4];
    for d in 0..4 {
        for (j, &seed) in seeds.iter().enumerate() {
            let scramble = hash(seed.wrapping_mul(SEED_FACTOR) ^ DIMENSION_KEYS[d]);
            values[d][j] =
                u32_to_f32_norm(owen_scramble_rev(sobol_rev[d][j], scramble).reverse_bits());
        }
    }
    values
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

    #[test]
    fn lanes_equal_single_draws_bit_for_bit() {
        let mut seed = 0x9e37_79b9_u32;
        for round in 0..512u32 {
            let indices: [u32; LANES] = std::array::from_fn(|j| {
                seed = hash(seed);
                if j == 0 { round % 3 * 0xffff / 2 } else { seed >> 16 }
            });
            let seeds: [u32; LANES] = std::array::from_fn(|j| {
                seed = hash(seed);
                if j == 1 { [0, u32::MAX][round as usize % 2] } else { seed }
            });
            let lanes = sample_4d_lanes(&indices, &seeds);
            for j in 0..LANES {
                let single = sample_4d(indices[j], seeds[j]).map(f32::to_bits);
                let lane: [u32; 4] = std::array::from_fn(|d| lanes[d][j].to_bits());
                assert_eq!(lane, single, "lane {j}, index {}, seed {:#x}", indices[j], seeds[j]);
            }
        }
    }
}
