//! Blends of two BSDFs checked as every kind is: sampling against the mixture's density by
//! chi-square, the mixture's value and density as the parts' weighted sum, and its energy.

use super::test_grid::{Grid, energy};
use super::*;

fn rough_copper(alpha: f32) -> Material {
    let (eta, k) = (Vec3::new(0.2, 0.92, 1.1), Vec3::new(3.9, 2.45, 2.14));
    Material {
        albedo: Vec3::ZERO,
        specular: Specular::Conductor { eta, k, reflectance: Vec3::ONE },
        ggx_alpha: alpha,
        ggx_alpha_v: alpha,
        ..Default::default()
    }
}

fn bsdf(material: &Material) -> Bsdf {
    Bsdf::new(material, material.albedo, Mat3::IDENTITY, true)
}

fn blend(first: &Material, second: &Material, weight: f32) -> Bsdf {
    Bsdf::blend(bsdf(first), bsdf(second), weight, Mat3::IDENTITY)
}

#[test]
fn a_blend_samples_its_own_density() {
    let diffuse = Material::diffuse(Vec3::new(0.7, 0.4, 0.2));
    let mirror = Material {
        specular: Specular::Mirror { reflectance: Vec3::splat(0.9) },
        ..Material::diffuse(Vec3::ZERO)
    };
    let cases = [
        ("diffuse | rough copper α 0.2, 0.3", blend(&diffuse, &rough_copper(0.2), 0.3)),
        ("rough copper α 0.05 | diffuse, 0.8", blend(&rough_copper(0.05), &diffuse, 0.8)),
        ("mirror | diffuse, 0.5", blend(&mirror, &diffuse, 0.5)),
    ];
    let grid = Grid::whole_sphere(true);
    for (i, (name, bsdf)) in cases.iter().enumerate() {
        for (j, wo) in [Vec3::new(0.1, 0.0, 1.0), Vec3::new(0.6, -0.3, 0.5)].iter().enumerate() {
            grid.test(&format!("{name}, wo {wo}"), bsdf, wo.normalize(), (i * 3 + j) as u64);
        }
    }
}

#[test]
fn a_blend_is_the_weighted_sum_of_its_parts() {
    let (first, second) = (Material::diffuse(Vec3::splat(0.8)), rough_copper(0.3));
    let wo = Vec3::new(0.3, 0.2, 0.9).normalize();
    for weight in [0.0, 0.25, 1.0] {
        let mixed = blend(&first, &second, weight);
        for wi in [Vec3::new(-0.3, 0.1, 0.95).normalize(), Vec3::new(0.7, -0.7, 0.1).normalize()] {
            let ((f0, p0), (f1, p1)) = (bsdf(&first).eval(wo, wi), bsdf(&second).eval(wo, wi));
            let (f, p) = mixed.eval(wo, wi);
            assert!((f - ((1.0 - weight) * f0 + weight * f1)).abs().max_element() < 1e-6);
            assert!((p - ((1.0 - weight) * p0 + weight * p1)).abs() < 1e-6);
        }
        // Its albedo is the parts' weighted sum too (a white diffuse keeps 0.8 of the light).
        let expected = (1.0 - weight) * energy(&bsdf(&first), wo, 100_000, 1)
            + weight * energy(&bsdf(&second), wo, 100_000, 2);
        let measured = energy(&mixed, wo, 100_000, 3);
        assert!(
            (measured - expected).abs().max_element() < 0.01,
            "{weight}: {measured} vs {expected}"
        );
    }
}

#[test]
fn a_blend_of_blends_is_flattened_with_its_shares_and_masks() {
    let (a, b, c) = (Material::diffuse(Vec3::splat(0.8)), rough_copper(0.3), rough_copper(0.05));
    let inner = blend(&a, &b, 0.5).with_opacity(0.6);
    let outer = Bsdf::blend(inner, bsdf(&c), 0.25, Mat3::IDENTITY);
    let (wo, wi) = (Vec3::new(0.3, 0.2, 0.9).normalize(), Vec3::new(-0.3, 0.1, 0.95).normalize());
    let (fa, pa) = bsdf(&a).eval(wo, wi);
    let (fb, pb) = bsdf(&b).eval(wo, wi);
    let (fc, pc) = bsdf(&c).eval(wo, wi);
    let (f, p) = outer.eval(wo, wi);
    // The inner blend's share 0.75, masked to 0.6 of the light: 0.225 each of a and b.
    assert!((f - (0.225 * fa + 0.225 * fb + 0.25 * fc)).abs().max_element() < 1e-6);
    assert!((p - (0.225 * pa + 0.225 * pb + 0.25 * pc)).abs() < 1e-6);
    // The rest of the inner share passes straight on: 0.75 · 0.4 of the samples.
    let mut rng = crate::splitmix::SplitMix64(5);
    let n = 100_000;
    let passed = (0..n)
        .filter(|_| {
            let s = outer.sample(wo, rng.unit(), Vec2::new(rng.unit(), rng.unit()));
            s.is_some_and(|s| s.passes)
        })
        .count();
    assert!((passed as f64 / n as f64 - 0.3).abs() < 0.01, "{passed}");
}
