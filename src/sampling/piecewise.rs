//! Piecewise-constant densities over [0, 1) and [0, 1)², sampled by inverting their CDFs:
//! the inversion is monotone, so stratified input numbers stay stratified (an alias table
//! would scramble them). The 2-D one picks a row from the marginal, then a column within it.

/// A density proportional to `weights` on equal cells of [0, 1).
#[derive(Clone, Debug)]
pub struct Piecewise1D {
    /// Each cell's density (weight / mean weight): integrates to 1.
    density: Vec<f32>,
    /// `cdf[i]`: the probability of cells before `i`; `cdf[len] == 1`.
    cdf: Vec<f64>,
    /// The weights' integral over [0, 1) (their mean).
    integral: f64,
    /// Empty, or (`guided`) for each of G equal steps of u (G a power of two), the first
    /// CDF index above the step's start, `guide[G]` the end's: a sample searches only its
    /// step's few indices, not the whole CDF, and finds the same cell.
    guide: Vec<u32>,
}

impl Piecewise1D {
    /// `None` unless some weight is positive; negative and non-finite weights count as 0.
    pub fn new(weights: &[f32]) -> Option<Self> {
        let clean = |w: f32| if w.is_finite() && w > 0.0 { f64::from(w) } else { 0.0 };
        let n = weights.len();
        let mut cdf = Vec::with_capacity(n + 1);
        let mut sum = 0.0f64;
        cdf.push(0.0);
        for &w in weights {
            sum += clean(w);
            cdf.push(sum);
        }
        if !(sum > 0.0) || !sum.is_finite() {
            return None;
        }
        cdf.iter_mut().for_each(|c| *c /= sum);
        let integral = sum / n as f64;
        let density = weights.iter().map(|&w| (clean(w) / integral) as f32).collect();
        Some(Piecewise1D { density, cdf, integral, guide: Vec::new() })
    }

    /// This density with a guide table for its samples (`guide`): one index per cell more
    /// held, for a sampler drawn from at every sample (a pixel filter's), not a large
    /// environment map's.
    pub fn guided(self) -> Self {
        let steps = self.len().next_power_of_two();
        let guide = (0..=steps)
            .map(|k| self.cdf.partition_point(|&c| c <= k as f64 / steps as f64) as u32)
            .collect();
        Piecewise1D { guide, ..self }
    }

    /// The first CDF index above `u` (`cdf.partition_point(|c| c <= u)`), searched in its
    /// guide step where there is a guide: the indices before the step's start are ≤ it ≤ u,
    /// those from its end's on are above its end > u (u·G and k / G are exact, G a power of
    /// two).
    #[inline]
    fn first_above(&self, u: f64) -> usize {
        let steps = self.guide.len().saturating_sub(1);
        if steps > 0 && (0.0..1.0).contains(&u) {
            let k = (u * steps as f64) as usize;
            let (lo, hi) = (self.guide[k] as usize, self.guide[k + 1] as usize);
            return lo + self.cdf[lo..hi].partition_point(|&c| c <= u);
        }
        self.cdf.partition_point(|&c| c <= u)
    }

    pub fn len(&self) -> usize {
        self.density.len()
    }

    pub fn is_empty(&self) -> bool {
        self.density.is_empty()
    }

    pub fn integral(&self) -> f64 {
        self.integral
    }

    /// The cell that holds `x` ∈ [0, 1) (clamped into range).
    fn cell(&self, x: f32) -> usize {
        ((x * self.len() as f32) as usize).min(self.len() - 1)
    }

    /// The density at `x` ∈ [0, 1).
    pub fn pdf(&self, x: f32) -> f32 {
        self.density[self.cell(x)]
    }

    /// The point whose CDF is `u`, its density and its cell. Cells of zero weight are never
    /// returned.
    pub fn sample(&self, u: f32) -> (f32, f32, usize) {
        let u = f64::from(u);
        // The last cell whose start is ≤ u, among cells that can be chosen (cdf rises).
        let mut cell = self.first_above(u).saturating_sub(1);
        cell = cell.min(self.len() - 1);
        while self.density[cell] <= 0.0 {
            // u landed exactly on the end of a run of empty cells (possible only when u is
            // the CDF value there): take the next cell that has weight.
            cell = if cell + 1 < self.len() { cell + 1 } else { self.last_positive() };
        }
        let (start, end) = (self.cdf[cell], self.cdf[cell + 1]);
        let within = ((u - start) / (end - start)).clamp(0.0, 1.0);
        let mut x = ((cell as f64 + within) / self.len() as f64) as f32;
        // Rounding to f32 may cross into a neighbour: step back into the cell, so that
        // `pdf(x)` agrees with the density returned.
        while self.cell(x) > cell {
            x = x.next_down();
        }
        while self.cell(x) < cell {
            x = x.next_up();
        }
        (x, self.density[cell], cell)
    }

    fn last_positive(&self) -> usize {
        self.density.iter().rposition(|&d| d > 0.0).unwrap_or(0)
    }
}

/// A density over [0, 1)² proportional to a `width` × `height` grid of weights (row-major,
/// row 0 at v = 0).
#[derive(Clone, Debug)]
pub struct Piecewise2D {
    rows: Vec<Option<Piecewise1D>>,
    marginal: Piecewise1D,
}

impl Piecewise2D {
    /// `None` unless some weight is positive.
    pub fn new(weights: &[f32], width: usize, height: usize) -> Option<Self> {
        assert_eq!(weights.len(), width * height, "a weight per cell");
        let rows: Vec<Option<Piecewise1D>> =
            weights.chunks_exact(width).map(Piecewise1D::new).collect();
        let row_weights: Vec<f32> =
            rows.iter().map(|r| r.as_ref().map_or(0.0, |r| r.integral() as f32)).collect();
        let marginal = Piecewise1D::new(&row_weights)?;
        Some(Piecewise2D { rows, marginal })
    }

    /// A point of [0, 1)² (x along a row, y across rows) and its density.
    pub fn sample(&self, u: glam::Vec2) -> (glam::Vec2, f32) {
        let (y, pdf_y, row) = self.marginal.sample(u.y);
        let conditional = self.rows[row].as_ref().expect("rows of zero weight are never chosen");
        let (x, pdf_x, _) = conditional.sample(u.x);
        (glam::Vec2::new(x, y), pdf_x * pdf_y)
    }

    /// The density at `p` ∈ [0, 1)².
    pub fn pdf(&self, p: glam::Vec2) -> f32 {
        let row = self.marginal.cell(p.y);
        match &self.rows[row] {
            Some(conditional) => self.marginal.pdf(p.y) * conditional.pdf(p.x),
            None => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::chi_square::assert_fits;
    use glam::Vec2;

    #[test]
    fn one_dimension_integrates_to_one_and_skips_empty_cells() {
        let d = Piecewise1D::new(&[0.0, 2.0, 0.0, 0.0, 6.0, -1.0, f32::NAN]).unwrap();
        let n = d.len() as f32;
        let total: f32 = (0..d.len()).map(|i| d.pdf((i as f32 + 0.5) / n) / n).sum();
        assert!((total - 1.0).abs() < 1e-6, "{total}");
        for k in 0..=1000 {
            let u = (k as f32 / 1000.0).min(0.999_999_9);
            let (x, pdf, cell) = d.sample(u);
            assert!(cell == 1 || cell == 4, "u {u} gave cell {cell}");
            assert!((0.0..1.0).contains(&x) && pdf > 0.0);
            assert_eq!(d.pdf(x), pdf, "the density at the sample is the one returned");
        }
        // The CDF's boundaries: exactly at the end of cell 1's mass.
        let (_, _, cell) = d.sample(0.25);
        assert_eq!(cell, 4);
        assert!(Piecewise1D::new(&[0.0, -2.0, f32::INFINITY]).is_none());
    }

    /// A guided density gives every sample the unguided one gives, bit for bit, at the
    /// CDF's own values and their neighbours too.
    #[test]
    fn the_guide_changes_no_sample() {
        for weights in [
            vec![0.0, 2.0, 0.0, 0.0, 6.0, -1.0, 1e-30],
            (0..256).map(|i| (-((i as f32 - 127.5) / 40.0).powi(2)).exp()).collect(),
            vec![1.0; 3],
        ] {
            let plain = Piecewise1D::new(&weights).unwrap();
            let guided = plain.clone().guided();
            assert_eq!(guided.guide.len(), weights.len().next_power_of_two() + 1);
            let at_cdf = plain.cdf.iter().flat_map(|&c| {
                let c = c as f32;
                [c.next_down(), c, c.next_up()]
            });
            let grid = (0..=65_536).map(|k| k as f32 / 65_536.0);
            for u in at_cdf.chain(grid).filter(|u| (0.0..1.0).contains(u)) {
                let (a, b) = (plain.sample(u), guided.sample(u));
                assert_eq!(
                    (a.0.to_bits(), a.1.to_bits(), a.2),
                    (b.0.to_bits(), b.1.to_bits(), b.2)
                );
            }
        }
    }

    #[test]
    fn sampling_is_monotone_in_u() {
        let d = Piecewise1D::new(&[1.0, 0.0, 3.0, 0.5, 2.0]).unwrap();
        let mut last = -1.0;
        for k in 0..10_000 {
            let (x, _, _) = d.sample(k as f32 / 10_000.0);
            assert!(x >= last, "monotone");
            last = x;
        }
    }

    #[test]
    fn two_dimensional_samples_follow_the_weights() {
        let (w, h) = (7, 5);
        let weights: Vec<f32> = (0..w * h)
            .map(|i| if i % 6 == 0 { 0.0 } else { 1.0 + ((i * 37) % 11) as f32 })
            .collect();
        let d = Piecewise2D::new(&weights, w, h).unwrap();
        let sum: f64 = weights.iter().map(|&x| f64::from(x)).sum();
        let expected: Vec<f64> = weights.iter().map(|&x| f64::from(x) / sum).collect();
        let samples = 200_000u64;
        let mut counts = vec![0u64; w * h];
        let mut rng = crate::splitmix::SplitMix64(0x1234_5678_9abc_def0);
        for _ in 0..samples {
            let u = Vec2::new(rng.unit(), rng.unit());
            let (p, pdf) = d.sample(u);
            let (col, row) = ((p.x * w as f32) as usize, (p.y * h as f32) as usize);
            assert!(weights[row * w + col] > 0.0, "an empty cell was sampled");
            // The density returned equals the pdf and the weight normalised over the area.
            let want = weights[row * w + col] as f64 / sum * (w * h) as f64;
            assert!((f64::from(pdf) - want).abs() < 1e-4 * want, "{pdf} vs {want}");
            assert!((d.pdf(p) - pdf).abs() <= 1e-6 * pdf);
            counts[row * w + col] += 1;
        }
        assert_fits("piecewise 2-D", &counts, &expected, samples);
    }
}
