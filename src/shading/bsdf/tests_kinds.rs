//! The kinds beside the mixture — plastic (smooth and rough), rough glass, masks — checked
//! as the mixture is: sampling against the density by chi-square over the whole sphere,
//! sample weights against eval/pdf, white furnaces, and the limits each must reach.

use super::test_grid::Grid;
use super::*;
use crate::scene::Distribution;
use crate::splitmix::SplitMix64;

fn chi_square_test(name: &str, bsdf: &Bsdf, wo: Vec3, seed: u64) {
    Grid::whole_sphere(true).test(name, bsdf, wo, seed);
}

fn furnace(bsdf: &Bsdf, wo: Vec3, samples: usize) -> Vec3 {
    super::test_grid::energy(bsdf, wo, samples, 5)
}

fn plastic(base: Vec3, alpha: f32, distribution: Distribution, nonlinear: bool) -> Material {
    let desc = crate::scene::MaterialDesc {
        albedo: base,
        specular: Specular::Plastic { ior: 1.5, nonlinear },
        roughness: alpha,
        distribution,
        ..Default::default()
    };
    Material::from_desc(&desc)
}

fn rough_glass(alpha: f32, distribution: Distribution) -> Material {
    Material {
        albedo: Vec3::ZERO,
        specular: Specular::dielectric(1.5, Vec3::ZERO),
        ggx_alpha: alpha,
        ggx_alpha_v: alpha,
        distribution,
        ..Default::default()
    }
}

fn views() -> [Vec3; 3] {
    [Vec3::new(0.1, 0.0, 1.0).normalize(), Vec3::new(0.5, 0.2, 0.8).normalize(), {
        Vec3::new(-0.9, 0.3, 0.25).normalize()
    }]
}

#[test]
fn plastics_and_rough_glass_sample_their_own_density() {
    let mut cases = vec![];
    for distribution in [Distribution::Ggx, Distribution::Beckmann] {
        for alpha in [0.05, 0.2] {
            let base = Vec3::new(0.2, 0.5, 0.3);
            cases.push((
                format!("plastic {distribution:?} α {alpha}"),
                plastic(base, alpha, distribution, false),
                true,
            ));
            cases.push((
                format!("glass {distribution:?} α {alpha}"),
                rough_glass(alpha, distribution),
                true,
            ));
            cases.push((
                format!("glass from inside {distribution:?} α {alpha}"),
                rough_glass(alpha, distribution),
                false,
            ));
        }
    }
    cases.push((
        "anisotropic glass GGX α 0.3 × 0.05".into(),
        Material { ggx_alpha_v: 0.05, ..rough_glass(0.3, Distribution::Ggx) },
        true,
    ));
    cases.push((
        "smooth plastic".into(),
        plastic(Vec3::splat(0.5), 0.0, Distribution::Ggx, false),
        true,
    ));
    for (i, (name, material, front_face)) in cases.iter().enumerate() {
        let bsdf = Bsdf::new(material, material.albedo, Mat3::IDENTITY, *front_face);
        for (j, wo) in views().into_iter().enumerate() {
            chi_square_test(&format!("{name}, wo {wo}"), &bsdf, wo, (i * 7 + j) as u64);
        }
    }
}

#[test]
fn a_white_plastic_keeps_nearly_everything_and_never_more() {
    for nonlinear in [false, true] {
        for (alpha, distribution) in [(0.0, Distribution::Ggx), (0.1, Distribution::Beckmann)] {
            let material = plastic(Vec3::ONE, alpha, distribution, nonlinear);
            let bsdf = Bsdf::new(&material, material.albedo, Mat3::IDENTITY, true);
            for wo in views().into_iter().take(2) {
                let energy = furnace(&bsdf, wo, 200_000).x;
                // A white base loses nothing but what rough facets mask and the linear
                // model's approximation of the internal bounces.
                assert!(energy > 0.93 && energy < 1.01, "α {alpha} {nonlinear}: {energy}");
            }
        }
    }
    // A black base: only the coating's reflection, Fresnel's few percent at normal incidence.
    let material = plastic(Vec3::ZERO, 0.0, Distribution::Ggx, false);
    let bsdf = Bsdf::new(&material, material.albedo, Mat3::IDENTITY, true);
    let energy = furnace(&bsdf, Vec3::Z, 100_000).x;
    assert!((energy - 0.04).abs() < 2e-3, "{energy}");
}

#[test]
fn rough_glass_passes_on_what_it_does_not_mask_from_either_side() {
    for distribution in [Distribution::Ggx, Distribution::Beckmann] {
        for front_face in [true, false] {
            let material = rough_glass(0.05, distribution);
            let bsdf = Bsdf::new(&material, material.albedo, Mat3::IDENTITY, front_face);
            let energy = furnace(&bsdf, Vec3::new(0.3, 0.0, 0.95).normalize(), 200_000).x;
            assert!(energy > 0.97 && energy < 1.005, "{distribution:?} {front_face}: {energy}");
        }
    }
}

#[test]
fn a_mask_passes_the_rest_of_the_light_straight_on() {
    let material = Material::diffuse(Vec3::splat(0.5));
    let bsdf = Bsdf::new(&material, material.albedo, Mat3::IDENTITY, true).with_opacity(0.25);
    let wo = Vec3::new(0.3, 0.1, 0.9).normalize();
    let (mut passed, mut rng, n) = (0, SplitMix64(3), 100_000);
    for _ in 0..n {
        let s = bsdf.sample(wo, rng.unit(), Vec2::new(rng.unit(), rng.unit())).unwrap();
        if s.passes {
            assert!(s.delta && s.transmitted && s.wi == -wo && s.weight == Vec3::ONE);
            passed += 1;
        }
    }
    assert!((passed as f64 / n as f64 - 0.75).abs() < 0.01, "{passed}");
    let plain = Bsdf::new(&material, material.albedo, Mat3::IDENTITY, true);
    let wi = Vec3::new(-0.2, 0.4, 0.8).normalize();
    let ((masked, masked_pdf), (full, full_pdf)) = (bsdf.eval(wo, wi), plain.eval(wo, wi));
    assert!((masked - full * 0.25).abs().max_element() < 1e-7);
    assert!((masked_pdf - full_pdf * 0.25).abs() < 1e-7);
    chi_square_test("lambert, opacity 0.25", &bsdf, wo, 11);
}

#[test]
fn a_one_sided_material_is_black_from_behind_but_glass_is_not() {
    let one_sided = Material { one_sided: true, ..Material::diffuse(Vec3::splat(0.5)) };
    let wo = Vec3::new(0.3, 0.1, 0.9).normalize();
    let behind = Bsdf::new(&one_sided, one_sided.albedo, Mat3::IDENTITY, false);
    assert_eq!(behind.eval(wo, Vec3::Z), (Vec3::ZERO, 0.0));
    assert!(behind.sample(wo, 0.5, Vec2::splat(0.5)).is_none());
    let front = Bsdf::new(&one_sided, one_sided.albedo, Mat3::IDENTITY, true);
    assert!(front.eval(wo, Vec3::Z).0.x > 0.0);
    let glass = Material { one_sided: true, ..rough_glass(0.2, Distribution::Ggx) };
    let inside = Bsdf::new(&glass, glass.albedo, Mat3::IDENTITY, false);
    assert!(furnace(&inside, wo, 10_000).x > 0.9);
}

#[test]
fn bump_shadowing_darkens_the_terminator_and_refuses_light_from_the_other_side() {
    let material = Material::diffuse(Vec3::splat(0.5));
    let tilted = Vec3::new(0.5, 0.0, 1.0).normalize();
    let frame = crate::sampling::frame_from_normal(tilted);
    let plain = Bsdf::new(&material, material.albedo, frame, true);
    let shadowed = plain.clone().with_bump_shadowing(Vec3::Z);
    let wo = Vec3::new(0.1, 0.2, 0.9).normalize();
    // Light above both normals: dimmed by at most the term's floor, more at grazing angles.
    let high = Vec3::new(0.2, 0.0, 0.95).normalize();
    let low = Vec3::new(0.95, 0.0, 0.1).normalize();
    let ratio = |wi: Vec3| shadowed.eval(wo, wi).0.x / plain.eval(wo, wi).0.x;
    let (high_ratio, low_ratio) = (ratio(high), ratio(low));
    assert!(high_ratio < 1.0 && high_ratio > 0.97, "{high_ratio}");
    assert!(low_ratio < high_ratio && low_ratio > 0.0, "{low_ratio}");
    // Above the mapped normal but below the unmapped one: no light.
    let below = Vec3::new(0.99, 0.0, -0.05).normalize();
    assert!(plain.eval(wo, below).0.x > 0.0);
    assert_eq!(shadowed.eval(wo, below), (Vec3::ZERO, 0.0));
    // An unmapped normal equal to the mapped one changes nothing.
    let same = plain.clone().with_bump_shadowing(tilted);
    assert!((same.eval(wo, high).0 - plain.eval(wo, high).0).abs().max_element() < 1e-6);
}
