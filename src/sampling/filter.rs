//! Pixel reconstruction filters by filter importance sampling: each sample's position in
//! its pixel is drawn from the filter (by inverting a tabulated CDF per axis, so stratified
//! numbers stay stratified) and its radiance weighted by filter / density, so a pixel's
//! mean estimates ∫ f(x − p) L(x) dx / ∫ f, the image a splatting renderer (Mitsuba, with
//! its Gaussian default) converges to, while every sample still lands in one pixel only
//! (renders stay exact sums, bit-identical for any split). The box filter is the pixel itself
//! and costs nothing. Filters with negative lobes (Mitchell–Netravali, Catmull–Rom,
//! Lanczos) are sampled by |f|, their samples weighted by f's sign.

use super::piecewise::Piecewise1D;
use glam::Vec2;

/// A separable reconstruction filter, in pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum PixelFilter {
    /// Each pixel averages the samples inside it.
    #[default]
    Box,
    /// exp(−x²/2σ²) − exp(−r²/2σ²) for |x| < r = 4σ (Mitsuba's `gaussian`, σ = 0.5 there).
    Gaussian { stddev: f32 },
    /// 1 − |x|/r for |x| < r (Mitsuba's `tent`, r = 1 there).
    Tent { radius: f32 },
    /// The Mitchell–Netravali cubic of parameters B and C, radius 2 (Mitsuba's `mitchell`:
    /// B = C = ⅓; its `catmullrom`: B = 0, C = ½).
    Mitchell { b: f32, c: f32 },
    /// sinc(x) · sinc(x / lobes) for |x| < lobes (Mitsuba's `lanczos`, 3 lobes).
    Lanczos { lobes: f32 },
}

/// The sizes a filter may take (a Gaussian's σ, a tent's radius, Lanczos' lobes), in
/// pixels: below a thousandth of a pixel a filter is the pixel's centre alone (and its
/// tabulated density underflows in f32), above 16 it blurs the image away.
pub const FILTER_SIZES: std::ops::RangeInclusive<f64> = 1e-3..=16.0;

/// `FILTER_SIZES` in words, for messages.
pub fn filter_sizes_text() -> String {
    format!("in [{}, {}] pixels", FILTER_SIZES.start(), FILTER_SIZES.end())
}

impl PixelFilter {
    /// Why this filter cannot reconstruct an image, if it cannot: one not positive at its
    /// centre (a Mitchell–Netravali cubic with B ≥ 3) would weigh every sample by its sign.
    pub fn problem(&self) -> Option<String> {
        match self.eval(0.0) > 0.0 {
            true => None,
            false => Some(format!("{self:?} is not positive at its centre (B must be below 3)")),
        }
    }

    /// How far from the pixel centre it reaches.
    pub fn radius(&self) -> f32 {
        match *self {
            PixelFilter::Box => 0.5,
            PixelFilter::Gaussian { stddev } => 4.0 * stddev,
            PixelFilter::Tent { radius } => radius,
            PixelFilter::Mitchell { .. } => 2.0,
            PixelFilter::Lanczos { lobes } => lobes,
        }
    }

    /// The filter's value at offset `x` along one axis.
    pub fn eval(&self, x: f32) -> f32 {
        self.eval_lowered(x, self.floor())
    }

    /// What the Gaussian is lowered by, its bell's value at the radius (so that it ends at
    /// 0 there); 0 for the others. Computed once by a sampler: an exponential a sample.
    fn floor(&self) -> f32 {
        match *self {
            PixelFilter::Gaussian { stddev } => bell(stddev, self.radius()),
            _ => 0.0,
        }
    }

    /// `eval`, given `floor()`.
    #[inline]
    fn eval_lowered(&self, x: f32, floor: f32) -> f32 {
        let r = self.radius();
        if !(x.abs() < r) {
            return 0.0;
        }
        match *self {
            PixelFilter::Box => 1.0,
            PixelFilter::Gaussian { stddev } => (bell(stddev, x) - floor).max(0.0),
            PixelFilter::Tent { radius } => 1.0 - x.abs() / radius,
            PixelFilter::Mitchell { b, c } => {
                let x = x.abs();
                let cubic = if x < 1.0 {
                    (12.0 - 9.0 * b - 6.0 * c) * x * x * x
                        + (-18.0 + 12.0 * b + 6.0 * c) * x * x
                        + (6.0 - 2.0 * b)
                } else {
                    (-b - 6.0 * c) * x * x * x
                        + (6.0 * b + 30.0 * c) * x * x
                        + (-12.0 * b - 48.0 * c) * x
                        + (8.0 * b + 24.0 * c)
                };
                cubic / 6.0
            }
            PixelFilter::Lanczos { lobes } => {
                let sinc = |t: f32| {
                    let pt = std::f32::consts::PI * t;
                    if pt.abs() < 1e-5 { 1.0 } else { pt.sin() / pt }
                };
                sinc(x) * sinc(x / lobes)
            }
        }
    }
}

/// The Gaussian bell of standard deviation `stddev` at `x`, 1 at 0.
#[inline]
fn bell(stddev: f32, x: f32) -> f32 {
    (-x * x / (2.0 * stddev * stddev)).exp()
}

/// Cells of the tabulated density per axis.
const CELLS: usize = 1024;

/// The filter's density over offsets in [lo, hi] (the part of it over the image): |f|
/// interpolated linearly across each cell, so that a sample's weight f / p is 1 to about
/// 1e-4 (a Gaussian's, in its far tail; 2e-5 at a pixel's distance). With a density
/// constant over each cell, the weights varied by 1.3 % over a pixel: a flat region, whose
/// every sample a splatting renderer (Mitsuba) weighs alike, was noisy. A cell across a
/// zero of f (a negative lobe's edge), where |f| is no line, keeps its mean |f| throughout.
#[derive(Clone, Debug)]
struct Window {
    lo: f32,
    hi: f32,
    /// Each cell's density at its two ends (unnormalised).
    ends: Vec<(f32, f32)>,
    /// Chooses a cell by its mass (the mean of its ends' values).
    table: Piecewise1D,
    /// What the weights are normalised by: ∫ f over [lo, hi], or over the whole filter
    /// (`FilterEdges::Cut`).
    integral: f64,
    /// `PixelFilter::floor`.
    floor: f32,
}

impl Window {
    fn new(filter: PixelFilter, lo: f32, hi: f32) -> Self {
        let (lo64, width) = (f64::from(lo), f64::from(hi - lo));
        let at = |t: f64| f64::from(filter.eval((lo64 + width * t) as f32));
        // Sampled by |f| (a negative lobe's samples carry negative weights).
        let nodes: Vec<f64> = (0..=CELLS).map(|k| at(k as f64 / CELLS as f64)).collect();
        let ends: Vec<(f32, f32)> = (0..CELLS)
            .map(|i| {
                let (a, b) = (nodes[i], nodes[i + 1]);
                if a * b >= 0.0 {
                    return (a.abs() as f32, b.abs() as f32);
                }
                const SUBCELLS: usize = 8;
                let sub = |k: usize| (i as f64 + (k as f64 + 0.5) / SUBCELLS as f64) / CELLS as f64;
                let mean = (0..SUBCELLS).map(|k| at(sub(k)).abs()).sum::<f64>() / SUBCELLS as f64;
                (mean as f32, mean as f32)
            })
            .collect();
        let masses: Vec<f32> = ends.iter().map(|&(a, b)| 0.5 * (a + b)).collect();
        // Simpson's rule, fine enough that the weights' mean is 1 to ~1e-9.
        let n = 1 << 16;
        let h = 1.0 / n as f64;
        let sum: f64 = (0..=n)
            .map(|i| {
                let w = if i == 0 || i == n {
                    1.0
                } else if i % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                w * at(i as f64 * h)
            })
            .sum();
        let table = Piecewise1D::new(&masses).expect("a filter is positive at its centre");
        // Drawn from at every sample of the image.
        let table = table.guided();
        Window { lo, hi, ends, table, integral: sum * h / 3.0 * width, floor: filter.floor() }
    }

    /// An offset from the pixel centre and its weight f / (p · ∫f).
    fn sample(&self, filter: PixelFilter, u: f32) -> (f32, f64) {
        let (t, _, cell) = self.table.sample(u);
        let within = (t * CELLS as f32 - cell as f32).clamp(0.0, 1.0);
        let (a, b) = self.ends[cell];
        let s = sample_linear(within, a, b);
        let at = |s: f32| self.lo + (self.hi - self.lo) * ((cell as f32 + s) / CELLS as f32);
        let x = at(s);
        let value = a + (b - a) * s;
        // Where the density is 0 (only at a cell's end where |f| is, such as the Gaussian's
        // radius, drawn by u = 0 exactly), f / p is 0 / 0: the sample takes the weight
        // its cell's middle has, which the weights near it approach. (A weight of 0 lost
        // one sample's light: a pixel of a flat sky 5e-4 too dark at 1953 spp.)
        let (weighed_at, value) = match value > 0.0 {
            true => (x, value),
            false => (at(0.5), 0.5 * (a + b)),
        };
        let per_offset = f64::from(value) / (self.table.integral() * f64::from(self.hi - self.lo));
        let f = filter.eval_lowered(weighed_at, self.floor);
        (x, f64::from(f) / (per_offset * self.integral))
    }
}

/// The point of [0, 1) whose CDF is `u` under the density that runs linearly from `a` to
/// `b` (pbrt's `SampleLinear`, in the form that is stable where a ≈ b).
fn sample_linear(u: f32, a: f32, b: f32) -> f32 {
    if u == 0.0 && a == 0.0 {
        return 0.0;
    }
    let x = u * (a + b) / (a + (a * a + (b * b - a * a) * u).max(0.0).sqrt());
    x.min(1.0f32.next_down())
}

/// One axis of the image: the filter's windows for the pixels near its ends (where the
/// filter reaches past the image, which has no samples there, as in Mitsuba's film) and the
/// whole filter for the rest.
#[derive(Clone, Debug)]
struct Axis {
    size: u32,
    /// Pixels within `reach` of an end use `ends[i]` (from the start) or `ends[reach + i]`
    /// (from the end); a pixel within reach of both ends has its own window in `small`.
    reach: u32,
    whole: Window,
    ends: Vec<Window>,
    small: Vec<Window>,
}

impl Axis {
    fn new(filter: PixelFilter, size: u32, edges: FilterEdges) -> Self {
        let r = filter.radius();
        let whole = Window::new(filter, -r, r);
        let window = |pixel: u32| {
            let lo = (-r).max(-(pixel as f32 + 0.5));
            let hi = r.min(size as f32 - pixel as f32 - 0.5);
            let window = Window::new(filter, lo, hi);
            match edges {
                FilterEdges::Renormalised => window,
                FilterEdges::Cut => Window { integral: whole.integral, ..window },
            }
        };
        let reach = ((r - 0.5).max(0.0).ceil() as u32).min(size);
        if 2 * reach >= size {
            let small = (0..size).map(window).collect();
            return Axis { size, reach, whole, ends: Vec::new(), small };
        }
        let ends = (0..reach).chain((size - reach..size).rev()).map(window).collect();
        Axis { size, reach, whole, ends, small: Vec::new() }
    }

    fn window(&self, pixel: u32) -> &Window {
        if !self.small.is_empty() {
            return &self.small[pixel.min(self.size - 1) as usize];
        }
        if pixel < self.reach {
            &self.ends[pixel as usize]
        } else if pixel >= self.size - self.reach {
            &self.ends[(self.reach + (self.size - 1 - pixel)) as usize]
        } else {
            &self.whole
        }
    }
}

/// What becomes of the part of a pixel's filter beyond the image's edges, which has no
/// samples.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FilterEdges {
    /// The rest of the filter is normalised to 1, as Mitsuba's film does (its path tracers'
    /// images): an edge pixel is the mean of what the image holds under its filter.
    #[default]
    Renormalised,
    /// The part beyond is lost: an edge pixel is ∫ f·L over the image / ∫ f, darker by the
    /// part of the filter it lacks. Mitsuba's light tracer (`ptracer`) splats its samples so,
    /// with no weights to divide by.
    Cut,
}

/// Draws positions in a pixel from a filter.
#[derive(Clone, Debug)]
pub struct FilterSampler {
    filter: PixelFilter,
    /// The x and y axes (`None` for the box).
    axes: Option<[Axis; 2]>,
}

impl FilterSampler {
    /// For an image of `width` × `height` pixels, its edges as `edges` says.
    pub fn new(filter: PixelFilter, width: u32, height: u32, edges: FilterEdges) -> Self {
        let axis = |size: u32| Axis::new(filter, size.max(1), edges);
        let axes = (filter != PixelFilter::Box).then(|| [axis(width), axis(height)]);
        FilterSampler { filter, axes }
    }

    pub fn filter(&self) -> PixelFilter {
        self.filter
    }

    /// The position in pixel (`x`, `y`) (from its top-left corner; beyond [0, 1) where the
    /// filter reaches) for the uniform numbers `u`, and the sample's weight.
    #[inline]
    pub fn sample(&self, pixel: (u32, u32), u: Vec2) -> (Vec2, f32) {
        // The box filter's sample is the uniform one, inline; the others' out of line.
        match &self.axes {
            None => (u, 1.0),
            Some(axes) => self.sample_windows(axes, pixel, u),
        }
    }

    /// `sample` for a filter other than the box.
    #[inline(never)]
    fn sample_windows(
        &self,
        [x_axis, y_axis]: &[Axis; 2],
        (x, y): (u32, u32),
        u: Vec2,
    ) -> (Vec2, f32) {
        let (dx, wx) = x_axis.window(x).sample(self.filter, u.x);
        let (dy, wy) = y_axis.window(y).sample(self.filter, u.y);
        (Vec2::new(0.5 + dx, 0.5 + dy), (wx * wy) as f32)
    }
}

#[cfg(test)]
#[path = "filter_tests.rs"]
mod tests;
