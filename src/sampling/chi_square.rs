//! Pearson's chi-square test of sample counts against expected probabilities, for the
//! tests of every sampler (BSDFs, lights, spherical polygons).

/// Wilson–Hilferty: the χ² value exceeded with probability 1e-4 at `dof` degrees of freedom.
pub fn limit(dof: usize) -> f64 {
    let k = dof as f64;
    let z = 3.719; // the normal quantile of 1 − 1e-4
    k * (1.0 - 2.0 / (9.0 * k) + z * (2.0 / (9.0 * k)).sqrt()).powi(3)
}

/// The statistic and its degrees of freedom for `counts` out of `samples` against the
/// probabilities `expected`; cells expecting fewer than 5 samples are pooled into one (the
/// usual rule).
pub fn statistic(counts: &[u64], expected: &[f64], samples: u64) -> (f64, usize) {
    let (mut statistic, mut cells) = (0.0f64, 0usize);
    let (mut pooled_count, mut pooled_expected) = (0u64, 0.0f64);
    for (&count, &p) in counts.iter().zip(expected) {
        let e = p * samples as f64;
        if e < 5.0 {
            pooled_count += count;
            pooled_expected += e;
        } else {
            statistic += (count as f64 - e).powi(2) / e;
            cells += 1;
        }
    }
    if pooled_expected > 0.0 || pooled_count > 0 {
        statistic += (pooled_count as f64 - pooled_expected).powi(2) / pooled_expected.max(1.0);
        cells += 1;
    }
    (statistic, cells.saturating_sub(1))
}

/// Asserts that `counts` fit `expected` (at the 1e-4 level) and prints the figures.
pub fn assert_fits(name: &str, counts: &[u64], expected: &[f64], samples: u64) {
    let (value, dof) = statistic(counts, expected, samples);
    let bound = limit(dof);
    println!("{name}: χ² {value:.1} over {dof} dof (limit {bound:.1})");
    assert!(value < bound, "{name}: χ² {value} ≥ {bound}");
}
