//! Solid textures stay fixed to their object whatever the placement or instancing.

use super::*;

fn checker_material() -> MaterialDesc {
    MaterialDesc {
        texture: Some(TextureDesc {
            pattern: Pattern::Checker3d {
                scale: 4.0,
                even: Vec3::splat(0.9),
                odd: Vec3::new(0.8, 0.1, 0.1),
            },
            mode: Default::default(),
            texture_from_object: DAffine3::IDENTITY,
        }),
        ..Default::default()
    }
}

/// Perlin noise (|noise|: dark veins) as the albedo.
fn perlin_material() -> MaterialDesc {
    MaterialDesc {
        texture: Some(TextureDesc {
            pattern: Pattern::Perlin {
                scale: 7.0,
                conversion: embray::scene::NoiseConversion::Absolute,
            },
            mode: embray::scene::TextureMode::Replace,
            texture_from_object: DAffine3::IDENTITY,
        }),
        ..Default::default()
    }
}

/// An 8 × 4 image of red and grey stripes, bilinear, in 0–255 units.
fn image_material() -> MaterialDesc {
    let texels =
        (0..32)
            .map(|i| {
                if (i % 8) / 2 % 2 == 0 { Vec3::new(230.0, 20.0, 20.0) } else { Vec3::splat(200.0) }
            })
            .collect();
    let image = embray::scene::TextureImage {
        file: "stripes".into(),
        width: 8,
        height: 4,
        texels,
        srgb_decoded: false,
        hdr: false,
        rows_flipped: false,
    };
    MaterialDesc {
        texture: Some(TextureDesc {
            pattern: Pattern::Image {
                image: std::sync::Arc::new(image),
                interpolation: embray::scene::Interpolation::Bilinear,
                normalizer: 255.0,
            },
            mode: Default::default(),
            texture_from_object: DAffine3::IDENTITY,
        }),
        ..Default::default()
    }
}

/// A checker-textured sphere placed by `placement`, seen from a camera placed the same way.
fn textured_sphere(placement: DAffine3, instanced: bool, material: MaterialDesc) -> SceneDesc {
    let eye = placement.transform_point3(DVec3::new(0.0, 1.0, 4.0));
    let target = placement.transform_point3(DVec3::ZERO);
    let mut s = scene(camera(eye.to_array(), target.to_array(), 40.0, 32, 32));
    let m = add_material(&mut s, material);
    let mut shape = sphere(1.0);
    if instanced {
        // The same mesh twice makes it a shared prototype placed by a transform.
        let mesh = cube();
        shape = ShapeDesc::Mesh(mesh.clone());
        let far = placement * DAffine3::from_translation(DVec3::new(0.0, -100.0, 0.0));
        s.objects.push(object("far copy", ShapeDesc::Mesh(mesh), m, far));
    }
    let centred =
        if instanced { DAffine3::from_translation(DVec3::splat(-0.5)) } else { DAffine3::IDENTITY };
    s.objects.push(object("textured", shape, m, placement * centred));
    s.lights.push(embray::scene::LightDesc::Directional(Directional {
        direction: placement.transform_vector3(DVec3::new(-1.0, -2.0, -1.5)),
        irradiance: Vec3::splat(3.0),
    }));
    s
}

#[test]
fn solid_texture_stays_fixed_to_its_object() {
    let moved = DAffine3::from_scale_rotation_translation(
        DVec3::splat(2.5),
        glam::DQuat::from_rotation_y(0.8),
        DVec3::new(30.0, -4.0, 12.0),
    );
    // The solid checker and Perlin noise (object-space points) and an image (texture
    // coordinates), each of which colours red and grey regions.
    let materials = [
        ("checker", checker_material()),
        ("perlin", perlin_material()),
        ("image", image_material()),
    ];
    // Far from the origin too: the default camera-relative render space keeps the
    // object-space points precise there.
    let far = DAffine3::from_translation(DVec3::new(3e6, -2e6, 5e6)) * moved;
    for backend in backends() {
        for ((kind, material), placement) in materials.iter().flat_map(|m| [(m, moved), (m, far)]) {
            for instanced in [false, true] {
                let reference = textured_sphere(DAffine3::IDENTITY, instanced, material.clone());
                let transformed = textured_sphere(placement, instanced, material.clone());
                let a = render_ok(&reference, &direct_only(&reference, backend, 4)).film;
                let b = render_ok(&transformed, &direct_only(&transformed, backend, 4)).film;
                let error = image_error(&b, &a);
                // The pattern shows as green (absent from the red parts and from the
                // noise's dark veins) varying across the lit pixels.
                let lit: Vec<f32> = a.color.iter().filter(|c| c.x > 0.05).map(|c| c.y).collect();
                let top = lit.iter().copied().fold(0.0, f32::max);
                let dark = lit.iter().filter(|&&g| g < 0.25 * top).count();
                let bright = lit.iter().filter(|&&g| g > 0.6 * top).count();
                println!(
                    "{} {kind} instanced={instanced}: {error:?}, {dark} dark, {bright} bright",
                    backend.name()
                );
                assert!(dark > 20 && bright > 20, "{kind}: the pattern must be visible");
                assert!(
                    error.fraction_off < 0.02,
                    "{} {kind} instanced={instanced} at {}: {error:?}",
                    backend.name(),
                    placement.translation
                );
            }
        }
    }
}
