//! The BSDFs checked the way the field checks them: each sampler against its own density
//! with a chi-square test over the hemisphere, white furnaces (no material reflects more
//! than it receives), and Fresnel's limits.

use super::test_grid::Grid;
use super::*;
use crate::scene::{CourseBrdf, Distribution};
use crate::shading::course_brdf::cos_weighted;
use crate::shading::fresnel::{fresnel_conductor, fresnel_dielectric};
use crate::splitmix::SplitMix64;
use std::f32::consts::PI;

/// The upper hemisphere in 12 × 24 cells, each integrated on a 24 × 24 grid: fine enough
/// for the sharpest lobe tested (GGX α 0.05, about 3° wide) to be integrated to well under
/// 1 %.
fn chi_square_test(name: &str, bsdf: &Bsdf, wo: Vec3, seed: u64) {
    let grid = Grid {
        theta_max: 0.5 * std::f64::consts::PI,
        theta_cells: 12,
        phi_cells: 24,
        sub: 24,
        delta_allowed: false,
        samples: 300_000,
    };
    grid.test(name, bsdf, wo, seed);
}

fn conductor(roughness: f32, reflectance: Vec3) -> Material {
    let (eta, k) = (Vec3::new(0.2, 0.92, 1.1), Vec3::new(3.9, 2.45, 2.14)); // copper
    Material {
        albedo: Vec3::ZERO,
        specular: Specular::Conductor { eta, k, reflectance },
        ggx_alpha: roughness,
        ggx_alpha_v: roughness,
        ..Default::default()
    }
}

fn rough_mirror(roughness: f32, albedo: Vec3) -> Material {
    Material {
        albedo,
        specular: Specular::Mirror { reflectance: Vec3::splat(0.6) },
        ggx_alpha: roughness,
        ggx_alpha_v: roughness,
        ..Default::default()
    }
}

/// `material` with α `alpha_v` along the bitangent.
fn anisotropic(material: Material, alpha_v: f32) -> Material {
    Material { ggx_alpha_v: alpha_v, ..material }
}

fn directions() -> [Vec3; 3] {
    [Vec3::Z, Vec3::new(0.4, 0.1, 0.9).normalize(), Vec3::new(-0.9, 0.3, 0.2).normalize()]
}

#[test]
fn every_smooth_lobe_samples_its_own_density() {
    let materials = [
        ("lambert", Material::diffuse(Vec3::new(0.5, 0.6, 0.7))),
        ("ggx conductor α 0.3", conductor(0.3, Vec3::ONE)),
        ("ggx conductor α 0.05", conductor(0.05, Vec3::ONE)),
        ("lambert + ggx mirror α 0.2", rough_mirror(0.2, Vec3::splat(0.8))),
        ("ggx conductor α 0.3 × 0.05", anisotropic(conductor(0.3, Vec3::ONE), 0.05)),
        ("beckmann conductor α 0.05 × 0.4", {
            let m = anisotropic(conductor(0.05, Vec3::ONE), 0.4);
            Material { distribution: Distribution::Beckmann, ..m }
        }),
    ];
    let course_models = crate::shading::course_brdf::MODELS;
    let lambert = || Material::diffuse(Vec3::splat(0.5));
    let course = course_models
        .iter()
        .map(|m| (format!("lambert + {m:?}, p 20"), course_lobe(lambert(), *m, 20.0)));
    let sharp = CourseBrdf::ModifiedPhong { normalized: true };
    let sharp = [(
        "glossy black + ModifiedPhong, p 200".to_owned(),
        course_lobe(Material::diffuse(Vec3::ZERO), sharp, 200.0),
    )];
    let materials: Vec<(String, Material)> = materials
        .into_iter()
        .map(|(name, m)| (name.to_owned(), m))
        .chain(course)
        .chain(sharp)
        .collect();
    for (m, (name, material)) in materials.iter().enumerate() {
        let bsdf = Bsdf::new(material, material.albedo, Mat3::IDENTITY, true);
        for (d, wo) in directions().into_iter().enumerate() {
            chi_square_test(&format!("{name}, wo {wo}"), &bsdf, wo, (m * 10 + d) as u64);
        }
    }
}

/// The directional albedo ∫ f cos dω of `material` for `wo`.
fn furnace(material: &Material, wo: Vec3, samples: usize) -> Vec3 {
    let bsdf = Bsdf::new(material, material.albedo, Mat3::IDENTITY, true);
    super::test_grid::energy(&bsdf, wo, samples, 99)
}

#[test]
fn white_furnace_no_material_reflects_more_than_it_receives() {
    let white = Vec3::ONE;
    let smooth_glass = Material {
        albedo: white,
        specular: Specular::dielectric(1.5, Vec3::ZERO),
        ..Default::default()
    };
    let mirror_over_lambert = Material {
        albedo: white,
        specular: Specular::Mirror { reflectance: Vec3::splat(0.5) },
        ..Default::default()
    };
    let white_mirror =
        Material { specular: Specular::Mirror { reflectance: white }, ..Default::default() };
    let cases: [(&str, Material, f32, f32); 7] = [
        // (name, material, least and most energy reflected)
        ("white lambert", Material::diffuse(white), 0.995, 1.005),
        ("white mirror", white_mirror, 0.9999, 1.0001),
        ("half mirror over white lambert", mirror_over_lambert, 0.995, 1.005),
        ("white rough mirror α 0.3 over white lambert", rough_mirror(0.3, white), 0.6, 1.005),
        ("rough conductor α 0.5, reflectance 1", conductor(0.5, white), 0.3, 1.005),
        (
            "lambert albedo 1.5 (the course allows it)",
            Material::diffuse(Vec3::splat(1.5)),
            0.995,
            1.005,
        ),
        ("glass", smooth_glass, 0.9999, 1.0001),
    ];
    // The course's lobe on top of materials that reflect or transmit everything by
    // themselves (hw6's glass sphere: ModifiedPhong normalized, p 200, ks 0.3); every model.
    let glass =
        || Material { specular: Specular::dielectric(1.5, Vec3::ZERO), ..Default::default() };
    let mirror =
        || Material { specular: Specular::Mirror { reflectance: Vec3::ONE }, ..Default::default() };
    let course_cases = crate::shading::course_brdf::MODELS.iter().flat_map(|brdf| {
        [1.0, 20.0, 200.0].into_iter().flat_map(move |p| {
            [
                (format!("glass + {brdf:?}, p {p}"), course_lobe(glass(), *brdf, p)),
                (
                    format!("white lambert + {brdf:?}, p {p}"),
                    course_lobe(Material::diffuse(Vec3::ONE), *brdf, p),
                ),
                (format!("white mirror + {brdf:?}, p {p}"), course_lobe(mirror(), *brdf, p)),
            ]
        })
    });
    let cases = cases
        .into_iter()
        .map(|(name, m, least, most)| (name.to_owned(), m, least, most))
        .chain(course_cases.map(|(name, m)| (name, m, 0.0, 1.005)));
    for (name, material, least, most) in cases {
        for wo in directions() {
            let energy = furnace(&material, wo, 100_000);
            println!("{name}, wo {wo}: {energy}");
            for c in energy.to_array() {
                assert!(c >= least && c <= most, "{name}, wo {wo}: reflects {energy}");
            }
        }
    }
}

#[test]
fn glass_reflects_the_fresnel_fraction() {
    let glass = Material { specular: Specular::dielectric(1.5, Vec3::ZERO), ..Default::default() };
    let bsdf = Bsdf::new(&glass, Vec3::ZERO, Mat3::IDENTITY, true);
    let wo = Vec3::new(0.6, 0.0, 0.8);
    let mut rng = SplitMix64(5);
    let n = 200_000;
    let reflected = (0..n)
        .filter(|_| {
            let s = bsdf.sample(wo, rng.unit(), Vec2::new(rng.unit(), rng.unit())).unwrap();
            !s.transmitted
        })
        .count() as f64;
    let expected = fresnel_dielectric(0.8, 1.5) as f64;
    let sigma = (expected * (1.0 - expected) / n as f64).sqrt();
    println!("reflected {:.5}, Fresnel {expected:.5}", reflected / n as f64);
    assert!((reflected / n as f64 - expected).abs() < 4.0 * sigma);
}

#[test]
fn fresnel_limits() {
    assert!((fresnel_dielectric(1.0, 1.5) - 0.04).abs() < 1e-3);
    assert_eq!(fresnel_dielectric(0.1, 1.0 / 1.5), 1.0);
    let gold = fresnel_conductor(1.0, Vec3::new(0.143, 0.374, 1.442), Vec3::new(3.98, 2.38, 1.60));
    assert!(gold.x > gold.z && gold.x > 0.9);
}

/// `material` plus the course's specular term of `brdf`: ks 0.3, exponent `exponent`.
fn course_lobe(material: Material, brdf: CourseBrdf, exponent: f32) -> Material {
    let phong =
        crate::scene::PhongDesc { ambient: Vec3::ZERO, specular: Vec3::splat(0.3), exponent, brdf };
    material.with_phong(Some(phong))
}

/// The course's glass: Fresnel reflection and refraction plus its specular term, the two
/// delta lobes giving up what the lobe reflects for that view so that the sum is exactly
/// what arrives. The sampled estimator must give each part its own integral: the smooth
/// samples the course lobe's directional albedo a (by quadrature), reflection (1 − a) times
/// Fresnel's share, refraction (1 − a) times the rest.
#[test]
fn course_glass_adds_its_specular_term_to_fresnel() {
    let glass = Material { specular: Specular::dielectric(1.5, Vec3::ZERO), ..Default::default() };
    let glass = course_lobe(glass, CourseBrdf::ModifiedPhong { normalized: true }, 20.0);
    let bsdf = Bsdf::new(&glass, Vec3::ZERO, Mat3::IDENTITY, true);
    assert!(bsdf.has_smooth_lobe(), "next-event estimation sees the course lobe");
    let Scatter::Mixture(mixture) = bsdf.scatter else { panic!("glass is a mixture") };
    let (brdf, terms) = mixture.course.unwrap();
    for wo in directions() {
        let (rings, sectors) = (1000, 180);
        let mut lobe = 0.0f64;
        for i in 0..rings {
            let cos_theta = (i as f32 + 0.5) / rings as f32;
            for j in 0..sectors {
                let phi = 2.0 * PI * (j as f32 + 0.5) / sectors as f32;
                let sin_theta = (1.0 - cos_theta * cos_theta).sqrt();
                let wi = Vec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), cos_theta);
                lobe += f64::from(cos_weighted(&brdf, &terms, Vec3::Z, wi, wo).x);
            }
        }
        lobe *= 2.0 * std::f64::consts::PI / (rings * sectors) as f64;
        let mut rng = SplitMix64(17);
        let n = 400_000;
        let (mut smooth, mut smooth2, mut reflected, mut transmitted) = (0.0, 0.0, 0.0, 0.0);
        for _ in 0..n {
            let Some(s) = bsdf.sample(wo, rng.unit(), Vec2::new(rng.unit(), rng.unit())) else {
                continue;
            };
            let w = f64::from(s.weight.x);
            match (s.delta, s.transmitted) {
                (false, _) => {
                    smooth += w;
                    smooth2 += w * w;
                }
                (true, false) => reflected += w,
                (true, true) => transmitted += w * 2.25, // radiance compression (η²) undone
            }
        }
        let n = n as f64;
        let (smooth, reflected, transmitted) = (smooth / n, reflected / n, transmitted / n);
        let sigma = ((smooth2 / n - smooth * smooth) / n).sqrt();
        let fresnel = f64::from(fresnel_dielectric(wo.z, 1.5));
        println!(
            "wo {wo}: course lobe {smooth:.4} vs {lobe:.4} (σ {sigma:.4}), reflected \
             {reflected:.4} vs {fresnel:.4}, transmitted {transmitted:.4}"
        );
        assert!((smooth - lobe).abs() < 4.0 * sigma + 1e-3, "{smooth} vs {lobe}");
        let kept = 1.0 - lobe;
        assert!((reflected - kept * fresnel).abs() < 0.01, "{reflected} vs {fresnel}");
        assert!((transmitted - kept * (1.0 - fresnel)).abs() < 0.01, "{transmitted}");
        assert!((smooth + reflected + transmitted - 1.0).abs() < 4.0 * sigma + 0.01, "energy");
    }
}

#[test]
fn a_lone_lambertian_lobe_samples_what_eval_gives() {
    // Its sample takes the weight ρ and the density cos/π in closed form: they must be
    // what `eval` gives for the sampled direction (MIS pairs the two), up to rounding.
    let albedo = Vec3::new(0.2, 0.5, 0.9);
    let frame = Mat3::from_quat(glam::Quat::from_rotation_arc(
        Vec3::Z,
        Vec3::new(0.3, -0.5, 0.8).normalize(),
    ));
    let bsdf = Bsdf::new(&Material::diffuse(albedo), albedo, frame, true);
    let mut rng = SplitMix64(11);
    let mut samples = 0;
    for wo in directions().map(|w| frame * w) {
        for _ in 0..2000 {
            let u = Vec2::new(rng.unit(), rng.unit());
            let Some(sample) = bsdf.sample(wo, rng.unit(), u) else { continue };
            let (value, pdf) = bsdf.eval(wo, sample.wi);
            assert!((sample.pdf - pdf).abs() <= 1e-5 * pdf, "pdf {} vs {pdf}", sample.pdf);
            let weight = value / pdf;
            assert!((sample.weight - weight).abs().max_element() <= 1e-5, "{weight}");
            assert_eq!(sample.weight, albedo);
            samples += 1;
        }
    }
    assert!(samples > 5900, "only {samples} of 6000 draws gave a sample");
}
