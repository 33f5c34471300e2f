//! Walker's alias method: picks index i with probability wᵢ / Σw in O(1), built in f64 so
//! that a million tiny weights keep their probabilities (a cumulative table in f32 cannot
//! even represent steps of 1e-6 near 1).

/// An alias table over non-negative weights.
#[derive(Clone, Debug, Default)]
pub struct AliasTable {
    /// Per bucket: the probability of keeping the bucket's own index.
    keep: Vec<f64>,
    /// Per bucket: the index chosen otherwise.
    alias: Vec<u32>,
    /// Per index: its probability, wᵢ / Σw.
    pmf: Vec<f64>,
}

/// 2⁻²⁴: two 24-bit uniform floats combined into one 48-bit uniform number.
const LOW_BITS: f64 = 1.0 / (1u64 << 24) as f64;

impl AliasTable {
    /// A table over `weights`; `None` if no weight is positive and finite. Other weights
    /// (zero, negative, NaN, infinite) get probability 0.
    pub fn new(weights: impl IntoIterator<Item = f64>) -> Option<Self> {
        let weights: Vec<f64> =
            weights.into_iter().map(|w| if w.is_finite() && w > 0.0 { w } else { 0.0 }).collect();
        let total: f64 = weights.iter().sum();
        if !(total > 0.0) || u32::try_from(weights.len()).is_err() {
            return None;
        }
        let n = weights.len();
        let pmf: Vec<f64> = weights.iter().map(|w| w / total).collect();
        // Vose's construction: buckets scaled so the mean is 1, small ones filled from large.
        let mut scaled: Vec<f64> = pmf.iter().map(|p| p * n as f64).collect();
        let mut keep = vec![1.0; n];
        let mut alias: Vec<u32> = (0..n as u32).collect();
        let (mut small, mut large): (Vec<usize>, Vec<usize>) =
            (0..n).partition(|&i| scaled[i] < 1.0);
        while let (Some(&s), Some(&l)) = (small.last(), large.last()) {
            small.pop();
            keep[s] = scaled[s];
            alias[s] = l as u32;
            scaled[l] -= 1.0 - scaled[s];
            if scaled[l] < 1.0 {
                large.pop();
                small.push(l);
            }
        }
        // What is left is 1 up to rounding.
        for i in small.into_iter().chain(large) {
            keep[i] = 1.0;
        }
        Some(AliasTable { keep, alias, pmf })
    }

    pub fn len(&self) -> usize {
        self.pmf.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pmf.is_empty()
    }

    /// The probability of index `i`.
    pub fn pmf(&self, i: usize) -> f64 {
        self.pmf[i]
    }

    /// An index drawn with `pick`, two uniform numbers in [0, 1) combined into one of 48
    /// bits (so even a million buckets are each hit in proportion to their width).
    pub fn sample(&self, pick: [f32; 2]) -> usize {
        // One entry (a scene's single light): its bucket and its alias are itself.
        if self.keep.len() == 1 {
            return 0;
        }
        let u = (pick[0] as f64 + pick[1] as f64 * LOW_BITS).clamp(0.0, 1.0);
        let x = u * self.keep.len() as f64;
        let bucket = (x as usize).min(self.keep.len() - 1);
        if x - (bucket as f64) < self.keep[bucket] { bucket } else { self.alias[bucket] as usize }
    }

    /// The probability of each index implied by the table's buckets (for tests): equals
    /// `pmf` up to rounding when the table is right.
    pub fn implied_probabilities(&self) -> Vec<f64> {
        let n = self.keep.len() as f64;
        let mut p: Vec<f64> = self.keep.iter().map(|k| k / n).collect();
        for (bucket, &other) in self.alias.iter().enumerate() {
            p[other as usize] += (1.0 - self.keep[bucket]) / n;
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::splitmix::SplitMix64;

    /// Pearson's chi-square statistic of `counts` against `expected` probabilities.
    fn chi_square(counts: &[u64], expected: &[f64], samples: u64) -> f64 {
        counts
            .iter()
            .zip(expected)
            .filter(|(_, p)| **p > 0.0)
            .map(|(&c, &p)| {
                let e = p * samples as f64;
                (c as f64 - e).powi(2) / e
            })
            .sum()
    }

    #[test]
    fn sampling_frequencies_pass_a_chi_square_test() {
        let mut rng = SplitMix64(11);
        let weights: Vec<f64> =
            (0..100).map(|i| if i % 7 == 0 { 0.0 } else { rng.range(0.01, 5.0) as f64 }).collect();
        let table = AliasTable::new(weights.iter().copied()).unwrap();
        let samples = 400_000u64;
        let mut counts = vec![0u64; weights.len()];
        for _ in 0..samples {
            counts[table.sample([rng.unit(), rng.unit()])] += 1;
        }
        for (i, w) in weights.iter().enumerate() {
            if *w == 0.0 {
                assert_eq!(counts[i], 0, "a zero weight was picked");
            }
        }
        let pmf: Vec<f64> = (0..weights.len()).map(|i| table.pmf(i)).collect();
        let statistic = chi_square(&counts, &pmf, samples);
        // 85 non-zero cells, 84 degrees of freedom: P(χ² > 140) ≈ 1e-4.
        println!("chi-square {statistic:.1} over 84 degrees of freedom");
        assert!(statistic < 140.0, "{statistic}");
    }

    #[test]
    fn a_million_emitters_keep_their_probabilities() {
        let mut rng = SplitMix64(3);
        let weights: Vec<f64> =
            (0..1_000_000).map(|_| rng.range(0.0, 1.0).powi(4) as f64).collect();
        let table = AliasTable::new(weights.iter().copied()).unwrap();
        let total: f64 = weights.iter().sum();
        let implied = table.implied_probabilities();
        // Errors measured against the mean probability 1/n: an f32 cumulative table read
        // with a 24-bit pick is off by up to 2⁻²⁴ · n ≈ 6 % here.
        let n = weights.len() as f64;
        let worst = weights
            .iter()
            .zip(&implied)
            .map(|(w, p)| (p - w / total).abs() * n)
            .fold(0.0f64, f64::max);
        println!("worst error of an implied probability, relative to 1/n: {worst:e}");
        assert!(worst < 1e-7, "{worst}");
        // And the sampler reaches them: 1000 groups of 1000 neighbours, 2M samples.
        let samples = 2_000_000u64;
        let mut counts = vec![0u64; 1000];
        for _ in 0..samples {
            counts[table.sample([rng.unit(), rng.unit()]) / 1000] += 1;
        }
        let groups: Vec<f64> =
            weights.chunks(1000).map(|c| c.iter().sum::<f64>() / total).collect();
        let statistic = chi_square(&counts, &groups, samples);
        // 999 degrees of freedom: P(χ² > 1180) ≈ 1e-4.
        println!("grouped chi-square {statistic:.1} over 999 degrees of freedom");
        assert!(statistic < 1180.0, "{statistic}");
    }

    #[test]
    fn no_positive_weight_is_no_table() {
        assert!(AliasTable::new([0.0, -1.0, f64::NAN, f64::INFINITY]).is_none());
        assert!(AliasTable::new(std::iter::empty()).is_none());
        let one = AliasTable::new([0.0, 2.0]).unwrap();
        assert_eq!(one.sample([0.0, 0.0]), 1);
        assert_eq!(one.sample([0.999_999_94, 0.999_999_94]), 1);
    }
}
