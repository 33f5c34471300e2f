use super::super::{Emitter, EmitterShape, InstanceEmitters, LightSet};
use crate::splitmix::SplitMix64;
use glam::{Vec2, Vec3};

fn lights_of(emitters: Vec<Emitter>) -> LightSet {
    let by_instance = vec![Some((0..emitters.len() as u32).collect())];
    LightSet::new(Vec::new(), Vec::new(), InstanceEmitters { emitters, by_instance }, Vec::new())
}

/// A light set holding only `shape`.
fn lights_with(shape: EmitterShape, two_sided: bool) -> LightSet {
    lights_of(vec![Emitter::new(0, shape, Vec3::new(3.0, 2.0, 1.0), two_sided)])
}

/// Every area sample of the lone emitter against `sample_emitter`'s, bit for bit, from
/// points on both sides at assorted numbers. Points near it (sampled by solid angle) are
/// left to `sample_emitter`; behind a one-sided one it must find nothing.
fn assert_same_samples(lights: &LightSet) {
    let lone = lights.lone_emitter().expect("one flat emitter");
    let mut rng = SplitMix64(9);
    let (mut by_area, mut found, mut left, mut behind) = (0, 0, 0, 0);
    for _ in 0..20_000 {
        let reference = rng.vec3(-12.0, 12.0);
        let (u, pick) = (Vec2::new(rng.unit(), rng.unit()), Vec2::new(rng.unit(), rng.unit()));
        // The sampler's copies of the shape's tests decide as the shape does.
        let (shape, two_sided) = (&lights.emitters[0].shape, lone.sampler.two_sided);
        assert_eq!(lone.sampler.behind(reference), shape.is_behind(two_sided, reference));
        assert_eq!(lone.sampler.is_near(reference), shape.is_near(reference), "{reference}");
        if lone.sampler.behind(reference) {
            behind += 1;
            assert!(lights.sample_emitter(reference, pick, u).is_none(), "{reference} {u}");
        }
        if !lone.sampler.by_area(reference) {
            left += 1;
            continue;
        }
        by_area += 1;
        let sample = lone.sampler.sample_by_area(reference, u);
        match lights.sample_emitter(reference, pick, u) {
            Some(expected) => {
                found += 1;
                let bits = |v: Vec3| v.to_array().map(f32::to_bits);
                assert_eq!(bits(sample.point), bits(expected.point), "{reference} {u}");
                assert_eq!(bits(sample.error), bits(expected.error));
                assert_eq!(bits(sample.normal), bits(expected.normal));
                assert_eq!(sample.pdf.to_bits(), expected.pdf.to_bits());
                assert_eq!(lone.sampler.emission, expected.emission);
                let flags = (lone.sampler.visible, lone.sampler.two_sided);
                assert_eq!(flags, (expected.visible, expected.two_sided));
            }
            None => assert_eq!(sample.pdf, 0.0, "{reference} {u}"),
        }
    }
    assert!(by_area > 1000 && found > 1000 && left > 1000, "{by_area} {found} {left}");
    // Only a one-sided emitter has a back.
    if lone.sampler.two_sided {
        assert_eq!(behind, 0);
    } else {
        assert!(behind > 1000, "{behind}");
    }
}

#[test]
fn quad_area_samples_are_sample_emitter_s() {
    let quad = |v: [Vec3; 4]| EmitterShape::quad(v).expect("a parallelogram");
    let rectangle = [
        Vec3::new(-2.0, 5.0, -1.5),
        Vec3::new(2.0, 5.0, -1.5),
        Vec3::new(2.0, 5.0, 1.5),
        Vec3::new(-2.0, 5.0, 1.5),
    ];
    assert_same_samples(&lights_with(quad(rectangle), false));
    let slanted = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(3.0, 1.0, 0.5),
        Vec3::new(4.0, 3.0, 2.5),
        Vec3::new(1.0, 2.0, 2.0),
    ];
    assert_same_samples(&lights_with(quad(slanted), true));
}

#[test]
fn triangle_area_samples_are_sample_emitter_s() {
    let vertices = [Vec3::new(1.0, -2.0, 0.5), Vec3::new(4.0, 1.0, -0.5), Vec3::new(0.5, 3.0, 2.0)];
    assert_same_samples(&lights_with(EmitterShape::triangle(vertices), false));
    assert_same_samples(&lights_with(EmitterShape::triangle(vertices), true));
}

#[test]
fn only_one_flat_emitter_is_lone() {
    let triangle = || {
        let v = [Vec3::X, Vec3::Y, Vec3::Z];
        Emitter::new(0, EmitterShape::triangle(v), Vec3::ONE, false)
    };
    let two = lights_of(vec![triangle(), triangle()]);
    assert!(two.lone_emitter().is_none());
    let sphere =
        EmitterShape::Sphere(crate::light::SphereShape { center: Vec3::ZERO, radius: 1.0 });
    assert!(lights_with(sphere, false).lone_emitter().is_none());
}
