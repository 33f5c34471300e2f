//! Light sampling from a shading point: solid-angle and area sampling of the same shape
//! estimate the same irradiance, solid-angle sampling with less variance close to the
//! light; the density the sampler reports is the one `pdf_from` computes for the same point.

use super::emitter::EmitterShape;
use super::shape_sample::ShapeSample;
use crate::splitmix::SplitMix64;
use glam::{Vec2, Vec3};

const SAMPLES: usize = 40_000;

/// Mean and variance of the irradiance estimator cos θ / pdf at `reference` with normal
/// `receiver`, for an emitter radiating 1 from every point facing the reference (flat
/// shapes: on both sides; a sphere's far side is hidden behind its near side).
fn irradiance(
    sample: impl Fn(Vec2) -> Option<ShapeSample>,
    reference: Vec3,
    receiver: Vec3,
    flat: bool,
    seed: u64,
) -> (f64, f64) {
    let mut rng = SplitMix64(seed);
    let (mut sum, mut sum2) = (0.0f64, 0.0f64);
    for _ in 0..SAMPLES {
        let value = sample(Vec2::new(rng.unit(), rng.unit())).map_or(0.0, |s| {
            let wi = (s.point - reference).normalize();
            let hidden = s.normal.dot(wi) > 0.0 && !flat;
            if hidden { 0.0 } else { (receiver.dot(wi).max(0.0) / s.pdf) as f64 }
        });
        sum += value;
        sum2 += value * value;
    }
    let mean = sum / SAMPLES as f64;
    (mean, sum2 / SAMPLES as f64 - mean * mean)
}

/// Every sample's density agrees with `pdf_from` at the same point.
fn assert_consistent_pdf(name: &str, shape: &EmitterShape, reference: Vec3) {
    let mut rng = SplitMix64(5);
    for _ in 0..2000 {
        let Some(s) = shape.sample_from(reference, Vec2::new(rng.unit(), rng.unit())) else {
            continue;
        };
        let pdf = shape.pdf_from(reference, s.point, s.normal);
        assert!((pdf - s.pdf).abs() <= 2e-3 * s.pdf, "{name}: sampled {} vs pdf_from {pdf}", s.pdf);
    }
}

/// Both strategies agree within 4 standard errors; returns variance(area) / variance(solid
/// angle).
fn compare_strategies(name: &str, shape: &EmitterShape, reference: Vec3, receiver: Vec3) -> f64 {
    assert_consistent_pdf(name, shape, reference);
    let flat = !matches!(shape, EmitterShape::Sphere(_));
    let sample = |u| shape.sample_from(reference, u);
    let (mean_sa, var_sa) = irradiance(sample, reference, receiver, flat, 1);
    let by_area = |u| shape.sample_by_area(reference, u);
    let (mean_area, var_area) = irradiance(by_area, reference, receiver, flat, 2);
    let standard_error = ((var_sa + var_area) / SAMPLES as f64).sqrt();
    println!(
        "{name}: solid angle {mean_sa:.5} (var {var_sa:.3e}), area {mean_area:.5} (var \
         {var_area:.3e}), variance ratio {:.1}",
        var_area / var_sa
    );
    assert!((mean_sa - mean_area).abs() < 4.0 * standard_error, "{name}: means differ");
    var_area / var_sa
}

/// Form factor from a point to a parallel rectangle of sides `a`, `b` whose corner is `h`
/// straight above it.
fn corner_form_factor(a: f64, b: f64, h: f64) -> f64 {
    let (x, y) = (a / h, b / h);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * std::f64::consts::PI)
}

#[test]
fn a_close_rectangle_is_sampled_alike_but_with_less_noise_by_solid_angle() {
    // A 2 × 2 light 0.25 above the point below its centre, facing down.
    let quad = EmitterShape::quad([
        Vec3::new(-1.0, 1.0, -1.0),
        Vec3::new(-1.0, 1.0, 1.0),
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(1.0, 1.0, -1.0),
    ])
    .expect("a square is a parallelogram");
    assert!(matches!(quad, EmitterShape::Quad { rectangle: Some(_), .. }));
    let reference = Vec3::new(0.0, 0.75, 0.0);
    let ratio = compare_strategies("square", &quad, reference, Vec3::Y);
    assert!(ratio > 3.0, "solid-angle sampling should be far less noisy here: {ratio}");
    // And the answer is the closed form: E = π F for unit radiance.
    let expected = std::f64::consts::PI * 4.0 * corner_form_factor(1.0, 1.0, 0.25);
    let (mean, var) = irradiance(|u| quad.sample_from(reference, u), reference, Vec3::Y, true, 3);
    let error = (mean - expected).abs();
    println!("square: {mean:.5} vs closed form {expected:.5}");
    assert!(error < 4.0 * (var / SAMPLES as f64).sqrt() + 1e-6, "{mean} vs {expected}");
}

#[test]
fn a_close_triangle_is_sampled_alike_but_with_less_noise_by_solid_angle() {
    let tri = EmitterShape::triangle([
        Vec3::new(-1.0, 1.0, -1.0),
        Vec3::new(1.5, 1.0, -0.5),
        Vec3::new(0.0, 1.0, 1.5),
    ]);
    let ratio = compare_strategies("triangle", &tri, Vec3::new(0.1, 0.8, 0.0), Vec3::Y);
    assert!(ratio > 3.0, "{ratio}");
    // Seen from the side, tilted receiver.
    let receiver = Vec3::new(0.3, 1.0, 0.2).normalize();
    compare_strategies("triangle, oblique", &tri, Vec3::new(2.0, 0.6, 0.3), receiver);
}

#[test]
fn a_close_sphere_is_sampled_alike_but_with_less_noise_by_its_cone() {
    let sphere = EmitterShape::Sphere(super::sphere_shape::SphereShape {
        center: Vec3::new(0.0, 1.5, 0.0),
        radius: 0.5,
    });
    let ratio = compare_strategies("sphere", &sphere, Vec3::new(0.2, 0.9, 0.0), Vec3::Y);
    assert!(ratio > 3.0, "{ratio}");
    // A sphere straight above the horizon: E = π sin²θ_max.
    let reference = Vec3::new(0.0, 0.0, 0.0);
    let (mean, _) = irradiance(|u| sphere.sample_from(reference, u), reference, Vec3::Y, false, 4);
    let expected = std::f64::consts::PI * (0.5f64 / 1.5).powi(2);
    assert!((mean / expected - 1.0).abs() < 1e-3, "{mean} vs {expected}");
    // From inside, by area.
    assert_consistent_pdf("sphere from inside", &sphere, Vec3::new(0.1, 1.4, 0.0));
}

#[test]
fn far_and_edge_on_lights_fall_back_to_area_sampling() {
    let tri = EmitterShape::triangle([Vec3::ZERO, Vec3::X, Vec3::Z]);
    // Solid angle about 1e-6 sr: sampled by area, densities still consistent.
    assert_consistent_pdf("far triangle", &tri, Vec3::new(0.3, 500.0, 0.2));
    let far = tri.sample_from(Vec3::new(0.3, 500.0, 0.2), Vec2::splat(0.5)).unwrap();
    let by_area = tri.sample_by_area(Vec3::new(0.3, 500.0, 0.2), Vec2::splat(0.5)).unwrap();
    assert_eq!(far.point, by_area.point);
    // In the light's own plane nothing is sampled.
    assert!(tri.sample_from(Vec3::new(3.0, 0.0, 3.0), Vec2::splat(0.5)).is_none());
}

#[test]
fn only_parallelograms_become_quads() {
    let square = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 0.0, 1.0), Vec3::Z];
    assert!(EmitterShape::quad(square).is_some());
    let mut kite = square;
    kite[2] = Vec3::new(1.2, 0.0, 1.2);
    assert!(EmitterShape::quad(kite).is_none());
    let mut sheared = square;
    sheared[2].x += 0.5;
    sheared[3].x += 0.5;
    assert!(matches!(
        EmitterShape::quad(sheared),
        Some(EmitterShape::Quad { rectangle: None, .. })
    ));
}

#[test]
fn spot_cone_falls_off_from_full_to_nothing_between_its_angles() {
    use super::{PointLight, SpotCone};
    let half_cos = |degrees: f32| (0.5 * degrees).to_radians().cos();
    // Coverage 60°, falloff 20°: full within 10° of the axis, none beyond 30°.
    let cone = SpotCone::course(Vec3::NEG_Y, half_cos(20.0), half_cos(60.0));
    let light = PointLight {
        position: Vec3::ZERO,
        intensity: Vec3::splat(100.0),
        spot: Some(cone),
        projection: None,
    };
    let at = |degrees: f32| {
        let a = degrees.to_radians();
        light.intensity_towards(Vec3::new(a.sin(), -a.cos(), 0.0)).x
    };
    assert_eq!(at(0.0), 100.0);
    assert_eq!(at(9.9), 100.0);
    assert_eq!(at(30.1), 0.0);
    assert_eq!(at(120.0), 0.0);
    for degrees in [12.0f32, 20.0, 28.0] {
        let cos = degrees.to_radians().cos();
        let s = ((cos - half_cos(60.0)) / (half_cos(20.0) - half_cos(60.0))).powi(4);
        assert!(
            (at(degrees) - 100.0 * s).abs() < 1e-3,
            "{degrees}°: {} vs {}",
            at(degrees),
            100.0 * s
        );
    }
    // Continuous at the falloff edge, monotone down to zero at the coverage edge.
    assert!(at(10.01) > 99.0 && at(29.9) < 1e-3);
    let point = PointLight { spot: None, ..light.clone() };
    assert_eq!(point.intensity_towards(Vec3::X), Vec3::splat(100.0));
}

#[test]
fn mitsubas_spot_falls_off_linearly_in_angle_and_projects_its_image() {
    use super::SpotCone;
    use super::kinds::{Spot, SpotProfile};
    use crate::light::LightKind;
    use crate::texels::TextureImage;
    // Mitsuba's cutoff 30°, beam width 10°: full within 10°, half at 20°, none past 30°.
    let image = TextureImage {
        file: "two.png".into(),
        width: 2,
        height: 1,
        texels: vec![Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0)],
        srgb_decoded: true,
        hdr: false,
        rows_flipped: false,
    };
    let spot = Spot {
        position: glam::DVec3::ZERO,
        direction: glam::DVec3::NEG_Y,
        intensity: Vec3::splat(10.0),
        coverage_degrees: 60.0,
        falloff_degrees: 20.0,
        profile: SpotProfile::Linear,
        texture: Some((std::sync::Arc::new(image), glam::DVec3::Z)),
    };
    let mut parts = super::kinds::LightParts::default();
    spot.compile(&glam::DAffine3::IDENTITY, &mut parts);
    let light = &parts.points[0];
    let cone: &SpotCone = light.spot.as_ref().unwrap();
    let towards = |degrees: f32, about_z: bool| {
        let a = degrees.to_radians();
        if about_z { Vec3::new(a.sin(), -a.cos(), 0.0) } else { Vec3::new(0.0, -a.cos(), a.sin()) }
    };
    assert_eq!(cone.factor(towards(5.0, true)), 1.0);
    assert!((cone.factor(towards(20.0, true)) - 0.5).abs() < 1e-5);
    assert_eq!(cone.factor(towards(30.5, true)), 0.0);
    // x = up × direction = Z × −Y = +X: u grows towards +x, the image's right (blue) half;
    // along the axis the two texels blend half and half.
    let right = cone.tint(towards(25.0, true));
    let left = cone.tint(towards(-25.0, true));
    assert!(right.z > right.x && left.x > left.z, "{right} {left}");
    let centre = cone.tint(Vec3::NEG_Y);
    assert!((centre - Vec3::new(0.5, 0.0, 0.5)).abs().max_element() < 1e-5, "{centre}");
    assert_eq!(light.intensity_towards(towards(31.0, false)), Vec3::ZERO);
}

#[test]
fn an_emitter_stays_small() {
    // Every triangle of an emissive mesh is one; a rectangle's frame is boxed.
    let size = std::mem::size_of::<EmitterShape>();
    println!("EmitterShape: {size} bytes");
    assert!(size <= 176, "EmitterShape is {size} bytes");
}

/// The memory estimate's cost of an emitter (`limits::BYTES_PER_EMITTER`) covers one: the
/// emitter, its index among a primitive's, its row of the alias table that picks it (two
/// f64 and a u32) and a textured one's boxed map (with the allocator's header).
#[test]
fn an_emitter_fits_its_share_of_the_memory_estimate() {
    let alias_row = 2 * size_of::<f64>() + size_of::<u32>();
    let map = size_of::<super::EmissionMap>() + 16;
    let one = size_of::<super::Emitter>() + size_of::<u32>() + alias_row + map;
    assert!(one as u64 <= crate::limits::BYTES_PER_EMITTER, "{one} bytes");
}
