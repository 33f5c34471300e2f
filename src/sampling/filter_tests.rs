//! The filters' values, their sampling's moments and weights, and the image's edges.

use super::*;

/// The weighted positions reproduce the normalised filter: the mean weight is 1 and the
/// weighted second moment is the filter's (0.248571 for Mitsuba's Gaussian, σ = 0.5
/// truncated at 4σ and lowered by its value there, integrated numerically; r²/6 for a
/// tent).
#[test]
fn weighted_samples_have_the_filters_moments() {
    let lanczos = PixelFilter::Lanczos { lobes: 3.0 };
    // (filter, its second moment, the tolerances of a 2048² stratified grid for the
    // moment and the mean weight: wider for the negative lobes, whose signed weights the
    // grid integrates less evenly (a cell across a zero of f holds weights of both
    // signs; along one axis, 2²² points give every mean weight 1 to 1e-7 and
    // Mitchell's moment to 4e-7); the moments of
    // Mitchell's and Catmull–Rom's cubics differ by 0.04).
    for (filter, second_moment, tolerance, weight_tolerance) in [
        (PixelFilter::Gaussian { stddev: 0.5 }, 0.248571, 5e-4, 1e-4),
        (PixelFilter::Tent { radius: 1.0 }, 1.0 / 6.0, 5e-4, 1e-4),
        // ∫x² f / ∫f of the cubic and of Lanczos-3, by a fine midpoint rule here.
        (mitchell_third(), second_moment(mitchell_third()), 2.5e-3, 4e-3),
        (lanczos, second_moment(lanczos), 2e-3, 4e-3),
    ] {
        let sampler = FilterSampler::new(filter, 64, 64, FilterEdges::Renormalised);
        let side = 2048;
        let (mut weight, mut moment) = (0.0f64, 0.0f64);
        for i in 0..side * side {
            let cell = Vec2::new((i % side) as f32, (i / side) as f32);
            let (p, w) = sampler.sample((32, 32), (cell + Vec2::splat(0.5)) / side as f32);
            weight += f64::from(w);
            moment += f64::from(w) * f64::from(p.x - 0.5).powi(2);
        }
        let n = f64::from(side * side);
        let (weight, moment) = (weight / n, moment / n);
        assert!((weight - 1.0).abs() < weight_tolerance, "{filter:?}: mean weight {weight}");
        assert!(
            (moment - second_moment).abs() < tolerance,
            "{filter:?}: second moment {moment}, not {second_moment}"
        );
    }
}

/// Where the filter is positive its samples are weighed alike (to the interpolation's
/// error): a flat region is as smooth as a splatting renderer's, whose weights cancel.
/// (With a density constant over each cell, the Gaussian's weights spread by 1.3 %.)
#[test]
fn weights_are_constant_where_the_filter_is_positive() {
    for (filter, pixel, size) in [
        (PixelFilter::Gaussian { stddev: 0.5 }, 32, 64),
        (PixelFilter::Gaussian { stddev: 0.5 }, 0, 64),
        (PixelFilter::Gaussian { stddev: 2.0 }, 32, 64),
        (PixelFilter::Tent { radius: 1.0 }, 32, 64),
        (PixelFilter::Tent { radius: 1.5 }, 1, 64),
    ] {
        let sampler = FilterSampler::new(filter, size, size, FilterEdges::Renormalised);
        let n = 1 << 16;
        let (mut sum, mut sum_sq, mut worst) = (0.0f64, 0.0f64, 0.0f64);
        for i in 0..n {
            let u = (i as f32 + 0.5) / n as f32;
            let (_, w) = sampler.sample((pixel, pixel), Vec2::new(u, 0.5));
            let (_, w_centre) = sampler.sample((pixel, pixel), Vec2::new(0.5, 0.5));
            let relative = f64::from(w / w_centre);
            sum += relative;
            sum_sq += relative * relative;
            worst = worst.max((relative - 1.0).abs());
        }
        let mean = sum / n as f64;
        let spread = (sum_sq / n as f64 - mean * mean).max(0.0).sqrt();
        assert!(spread < 1e-4, "{filter:?}, pixel {pixel}: weights spread by {spread}");
        assert!(worst < 2e-3, "{filter:?}, pixel {pixel}: a weight {worst} from the rest");
    }
}

/// The ends of the unit interval, where the Gaussian's density is 0, weigh a sample as
/// the samples near them (not 0: a sample's light lost).
#[test]
fn a_sample_at_the_filters_edge_keeps_its_weight() {
    let sampler = FilterSampler::new(
        PixelFilter::Gaussian { stddev: 0.5 },
        64,
        64,
        FilterEdges::Renormalised,
    );
    let (_, centre) = sampler.sample((32, 32), Vec2::splat(0.5));
    for u in [0.0, 1.0f32.next_down()] {
        let (p, w) = sampler.sample((32, 32), Vec2::new(u, 0.5));
        assert!((p.x - 0.5).abs() > 1.99, "{p}");
        // Within the last cell's interpolation error (1.5 % at most, where f vanishes
        // linearly and bends; its samples are one in ten million).
        assert!((w / centre - 1.0).abs() < 2e-2, "u {u}: weight {w}, {centre} at the centre");
    }
}

fn mitchell_third() -> PixelFilter {
    PixelFilter::Mitchell { b: 1.0 / 3.0, c: 1.0 / 3.0 }
}

fn second_moment(filter: PixelFilter) -> f64 {
    let (n, r) = (200_000, f64::from(filter.radius()));
    let (mut f, mut x2f) = (0.0, 0.0);
    for i in 0..n {
        let x = -r + 2.0 * r * (i as f64 + 0.5) / n as f64;
        let v = f64::from(filter.eval(x as f32));
        f += v;
        x2f += x * x * v;
    }
    x2f / f
}

#[test]
fn the_cubics_take_their_known_values() {
    // Mitchell–Netravali with B = C = ⅓: 16/18 at 0, 1/18 at ±1, 0 at ±2; Catmull–Rom
    // interpolates (1 at 0, 0 at ±1) and dips below zero in between 1 and 2.
    let m = mitchell_third();
    assert!((m.eval(0.0) - 16.0 / 18.0).abs() < 1e-6 && (m.eval(1.0) - 1.0 / 18.0).abs() < 1e-6);
    assert!(m.eval(1.999).abs() < 1e-3 && m.eval(2.0) == 0.0);
    let cr = PixelFilter::Mitchell { b: 0.0, c: 0.5 };
    assert!((cr.eval(0.0) - 1.0).abs() < 1e-6 && cr.eval(1.0).abs() < 1e-6);
    assert!(cr.eval(1.5) < 0.0);
    let l = PixelFilter::Lanczos { lobes: 3.0 };
    assert!((l.eval(0.0) - 1.0).abs() < 1e-6 && l.eval(1.0).abs() < 1e-6 && l.eval(1.5) < 0.0);
}

#[test]
fn the_box_keeps_the_position_and_weight_one() {
    let sampler = FilterSampler::new(PixelFilter::Box, 8, 8, FilterEdges::Renormalised);
    assert_eq!(sampler.sample((0, 7), Vec2::new(0.25, 0.75)), (Vec2::new(0.25, 0.75), 1.0));
}

/// Near the image's edges the filter is cut where the image ends: no sample leaves it,
/// and the weights still average 1 over the part that is left (renormalised), or the
/// fraction of the filter that part is (cut, as a light tracer's splats).
#[test]
fn pixels_at_the_edges_sample_only_the_image() {
    let filter = PixelFilter::Gaussian { stddev: 0.5 };
    // The share of Mitsuba's Gaussian over [-0.5, 2] of its [-2, 2] (one axis), and over
    // [-1.5, 2]: by a fine midpoint rule.
    let share = |lo: f64| {
        let n = 100_000;
        let part = |a: f64, b: f64| -> f64 {
            let at = |i: usize| a + (b - a) * (i as f64 + 0.5) / n as f64;
            (0..n).map(|i| f64::from(filter.eval(at(i) as f32))).sum::<f64>() * (b - a)
        };
        part(lo, 2.0) / part(-2.0, 2.0)
    };
    let cases = [
        (48, 0, 1.0, 1.0),
        (48, 1, 1.0, 1.0),
        (48, 46, 1.0, 1.0),
        (48, 47, 1.0, 1.0),
        (3, 1, 1.0, 1.0),
        (1, 0, 1.0, 1.0),
        (48, 0, share(-0.5), share(-0.5)),
        (48, 1, share(-1.5), share(-1.5)),
        (48, 2, 1.0, 1.0),
    ];
    for (k, (size, pixel, x_share, y_share)) in cases.into_iter().enumerate() {
        let edges = if k < 6 { FilterEdges::Renormalised } else { FilterEdges::Cut };
        let sampler = FilterSampler::new(filter, size, size, edges);
        let side = 1024;
        let mut weight = 0.0f64;
        for i in 0..side * side {
            let cell = Vec2::new((i % side) as f32, (i / side) as f32);
            let (p, w) = sampler.sample((pixel, pixel), (cell + Vec2::splat(0.5)) / side as f32);
            let q = pixel as f32 + p;
            assert!(q.cmpge(Vec2::ZERO).all() && q.cmple(Vec2::splat(size as f32)).all());
            weight += f64::from(w);
        }
        let weight = weight / f64::from(side * side);
        let expected = x_share * y_share;
        assert!(
            (weight - expected).abs() < 1e-3,
            "{edges:?}, size {size}, pixel {pixel}: mean weight {weight}, not {expected}"
        );
    }
}
