//! Spherical triangles and rectangles: the sampled points follow the density "uniform in
//! solid angle" (a chi-square test over the shape's own parameters, with the expected
//! fractions integrated from cos θ / d²), and the solid angles are right (the expected
//! fractions sum to one).

use super::chi_square::assert_fits;
use super::spherical_rectangle::SphericalRectangle;
use super::spherical_triangle;
use crate::splitmix::SplitMix64;
use glam::{DVec3, Vec2, Vec3};

/// Cells per side of the parameter grid, and sub-cells per cell side for the integration.
const CELLS: usize = 12;
const SUB: usize = 24;
const SAMPLES: u64 = 200_000;

/// ∫ density over each cell of the unit square (midpoint rule).
fn expected_fractions(density: impl Fn(f64, f64) -> f64) -> Vec<f64> {
    let h = 1.0 / (CELLS * SUB) as f64;
    (0..CELLS * CELLS)
        .map(|cell| {
            let (cx, cy) = (cell % CELLS, cell / CELLS);
            let mut sum = 0.0;
            for i in 0..SUB {
                for j in 0..SUB {
                    let x = ((cx * SUB + i) as f64 + 0.5) * h;
                    let y = ((cy * SUB + j) as f64 + 0.5) * h;
                    sum += density(x, y) * h * h;
                }
            }
            sum
        })
        .collect()
}

fn cell_of(p: Vec2) -> usize {
    let index = |v: f32| ((v * CELLS as f32) as usize).min(CELLS - 1);
    index(p.y) * CELLS + index(p.x)
}

/// Solid angle per unit area at `point` (unit normal `normal`) seen from `reference`.
fn solid_angle_per_area(reference: DVec3, point: DVec3, normal: DVec3) -> f64 {
    let d = point - reference;
    normal.dot(d).abs() / d.length_squared().powf(1.5)
}

fn check_rectangle(name: &str, reference: Vec3, corner: Vec3, edge_u: Vec3, edge_v: Vec3) {
    let rect = SphericalRectangle::new(reference, corner, edge_u, edge_v).unwrap();
    let (c, u, v) = (corner.as_dvec3(), edge_u.as_dvec3(), edge_v.as_dvec3());
    let normal = u.cross(v).normalize();
    let jacobian = u.cross(v).length();
    let omega = rect.solid_angle();
    let expected = expected_fractions(|s, t| {
        solid_angle_per_area(reference.as_dvec3(), c + s * u + t * v, normal) * jacobian / omega
    });
    let total: f64 = expected.iter().sum();
    assert!((total - 1.0).abs() < 1e-3, "{name}: Ω is off, ∫ = {total}");
    let mut rng = SplitMix64(7);
    let mut counts = vec![0u64; CELLS * CELLS];
    for _ in 0..SAMPLES {
        counts[cell_of(rect.sample(Vec2::new(rng.unit(), rng.unit())))] += 1;
    }
    assert_fits(name, &counts, &expected, SAMPLES);
}

fn check_triangle(name: &str, reference: Vec3, tri: [Vec3; 3]) {
    let [v0, v1, v2] = tri.map(|v| v.as_dvec3());
    let (e1, e2) = (v1 - v0, v2 - v0);
    let normal = e1.cross(e2).normalize();
    let omega = spherical_triangle::solid_angle(&tri, reference);
    // The unit square onto the triangle: b1 = x, b2 = y (1 − x), so dA = |e1 × e2| (1 − x).
    let expected = expected_fractions(|x, y| {
        let point = v0 + x * e1 + y * (1.0 - x) * e2;
        let jacobian = e1.cross(e2).length() * (1.0 - x);
        solid_angle_per_area(reference.as_dvec3(), point, normal) * jacobian / omega
    });
    let total: f64 = expected.iter().sum();
    assert!((total - 1.0).abs() < 1e-3, "{name}: Ω is off, ∫ = {total}");
    let mut rng = SplitMix64(9);
    let mut counts = vec![0u64; CELLS * CELLS];
    for _ in 0..SAMPLES {
        let b = spherical_triangle::sample(&tri, reference, Vec2::new(rng.unit(), rng.unit()));
        let b = b.expect("a regular triangle is always sampled");
        let y = if b.x < 1.0 { b.y / (1.0 - b.x) } else { 0.0 };
        counts[cell_of(Vec2::new(b.x, y))] += 1;
    }
    assert_fits(name, &counts, &expected, SAMPLES);
}

#[test]
fn spherical_rectangles_sample_uniformly_by_solid_angle() {
    let (corner, u, v) = (Vec3::new(-1.0, -1.0, 1.0), Vec3::new(3.0, 0.0, 0.0), Vec3::Y * 2.0);
    check_rectangle("rectangle, close and off-centre", Vec3::new(0.3, -0.2, 0.7), corner, u, v);
    check_rectangle("rectangle, seen obliquely", Vec3::new(4.0, 3.0, 0.2), corner, u, v);
    let tilted_u = Vec3::new(1.0, 1.0, 0.5);
    let tilted_v = tilted_u.cross(Vec3::Z).normalize() * 0.5;
    check_rectangle(
        "rectangle, tilted, from behind",
        Vec3::new(0.2, 0.1, 2.5),
        corner,
        tilted_u,
        tilted_v,
    );
}

#[test]
fn spherical_triangles_sample_uniformly_by_solid_angle() {
    let tri = [Vec3::new(-1.0, -0.5, 1.0), Vec3::new(1.5, -0.5, 1.0), Vec3::new(0.0, 1.5, 1.2)];
    check_triangle("triangle, close", Vec3::new(0.1, 0.0, 0.6), tri);
    check_triangle("triangle, oblique", Vec3::new(3.0, -2.0, 0.5), tri);
    check_triangle("triangle, from behind", Vec3::new(0.0, 0.0, 2.0), tri);
}
