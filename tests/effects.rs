//! Distribution effects, materials, instancing and shading space, on every compiled backend.
//! Scenes are built in code so the checks do not depend on the file format.

mod common;

use common::build::*;
use common::*;
use embray::accel::{AccelOptions, BackendKind, build as build_accel};
use embray::choice::Choice;
use embray::compile::EffectsMode;
use embray::film::Film;
use embray::ray::Ray;
use embray::render::{RenderOptions, prepare_scene, render};
use embray::scene::{Directional, Point};
use embray::scene::{MaterialDesc, Pattern, SceneDesc, ShapeDesc, Specular, TextureDesc};
use embray::stats::TraversalCounters;
use glam::{DAffine3, DVec3, Vec3};

fn luminance_sum(film: &Film) -> f64 {
    film.color.iter().map(|c| c.element_sum() as f64).sum()
}

fn direct_only(scene: &SceneDesc, backend: BackendKind, spp: u32) -> RenderOptions {
    let mut o = options(scene, backend, spp);
    o.max_depth = 1;
    o
}

/// A tiny emissive sphere seen through a thin lens (A = 1, focused at 10).
fn dof_scene(depth: f64) -> SceneDesc {
    let mut camera = camera([0.0, 0.0, 0.0], [0.0, 0.0, -1.0], 30.0, 64, 64);
    camera.aperture = 1.0;
    camera.focus_distance = Some(10.0);
    let mut s = scene(camera);
    let light = add_material(&mut s, emissive(1.0));
    // The image centre is a pixel corner; nudge the in-focus sphere onto pixel (32, 32)'s centre.
    let pixel = 2.0 * depth * (15f64).to_radians().tan() / 64.0;
    let at = DVec3::new(0.5 * pixel, -0.5 * pixel, -depth);
    s.objects.push(object("dot", sphere(0.02), light, DAffine3::from_translation(at)));
    s
}

#[test]
fn depth_of_field_focal_plane_is_sharp_and_blur_matches_thin_lens() {
    for backend in backends() {
        let sharp_scene = dof_scene(10.0);
        let sharp = render_ok(&sharp_scene, &direct_only(&sharp_scene, backend, 64)).film;
        let total = luminance_sum(&sharp);
        let centre = sharp.pixel(32, 32).element_sum() as f64;
        println!(
            "{}: in-focus energy in one pixel: {:.1}%",
            backend.name(),
            100.0 * centre / total
        );
        assert!(centre / total > 0.95, "{}: focal plane not sharp", backend.name());

        let depth = 5.0;
        let blurred_scene = dof_scene(depth);
        let blurred = render_ok(&blurred_scene, &direct_only(&blurred_scene, backend, 256)).film;
        let (mut sum, mut mx, mut my) = (0.0, 0.0, 0.0);
        for y in 0..64 {
            for x in 0..64 {
                let e = blurred.pixel(x, y).element_sum() as f64;
                sum += e;
                mx += e * (x as f64 + 0.5);
                my += e * (y as f64 + 0.5);
            }
        }
        let (cx, cy) = (mx / sum, my / sum);
        let mut second = 0.0;
        for y in 0..64 {
            for x in 0..64 {
                let e = blurred.pixel(x, y).element_sum() as f64;
                second += e * ((x as f64 + 0.5 - cx).powi(2) + (y as f64 + 0.5 - cy).powi(2));
            }
        }
        // A uniform disk of radius r has E[ρ²] = r²/2; the pixel box adds 1/12 per axis.
        let measured = 2.0 * (2.0 * (second / sum - 1.0 / 6.0)).sqrt();
        let pixel_at_focus = 2.0 * 10.0 * (15f64).to_radians().tan() / 64.0;
        let predicted = 1.0 * (10.0 - depth) / depth / pixel_at_focus;
        println!(
            "{}: circle of confusion {measured:.2} px, thin lens predicts {predicted:.2} px",
            backend.name()
        );
        assert!((measured / predicted - 1.0).abs() < 0.10, "{}", backend.name());
    }
}

/// A unit cube sliding along x over a lit floor.
fn moving_cube_scene(start: DAffine3, end: Option<DAffine3>) -> SceneDesc {
    let mut s = scene(camera([0.0, 3.0, 8.0], [0.0, 0.5, 0.0], 40.0, 32, 24));
    let grey = add_material(&mut s, diffuse(0.5));
    s.objects.push(object(
        "floor",
        quad([-10.0, 0.0, -10.0], [20.0, 0.0, 0.0], [0.0, 0.0, 20.0]),
        grey,
        DAffine3::IDENTITY,
    ));
    let mut cube = object("cube", ShapeDesc::Mesh(cube()), grey, start);
    cube.world_from_object_end = end;
    s.objects.push(cube);
    s.lights.push(embray::scene::LightDesc::Point(Point {
        position: DVec3::new(1.0, 10.0, 5.0),
        intensity: Vec3::splat(100.0),
    }));
    s
}

#[test]
fn motion_blur_equals_the_average_of_fixed_time_renders() {
    let start = DVec3::new(-2.5, 0.0, -0.5);
    let end = DVec3::new(1.5, 0.0, -0.5);
    for backend in backends() {
        let moving = moving_cube_scene(
            DAffine3::from_translation(start),
            Some(DAffine3::from_translation(end)),
        );
        let blurred = render_ok(&moving, &direct_only(&moving, backend, 256)).film;
        let steps = 16;
        let mut average = Film::new(32, 24);
        for k in 0..steps {
            let t = (k as f64 + 0.5) / steps as f64;
            let fixed = moving_cube_scene(DAffine3::from_translation(start.lerp(end, t)), None);
            let film = render_ok(&fixed, &direct_only(&fixed, backend, 16)).film;
            for (a, c) in average.color.iter_mut().zip(&film.color) {
                *a += *c / steps as f32;
            }
        }
        let error = image_error(&blurred, &average);
        let still = moving_cube_scene(DAffine3::from_translation(start), None);
        let unblurred = render_ok(&still, &direct_only(&still, backend, 16)).film;
        let control = image_error(&unblurred, &average);
        println!(
            "{}: blurred vs averaged {error:?}; unblurred vs averaged {control:?}",
            backend.name()
        );
        assert!(error.relative_mse < 2e-3, "{}: {error:?}", backend.name());
        assert!(
            control.relative_mse > 20.0 * error.relative_mse,
            "the comparison must be able to fail"
        );
    }
}

#[test]
fn moving_object_is_hit_at_both_shutter_ends() {
    let start = DAffine3::from_scale_rotation_translation(
        DVec3::splat(1.0),
        glam::DQuat::IDENTITY,
        DVec3::new(-3.0, 0.0, 0.0),
    );
    let end = DAffine3::from_scale_rotation_translation(
        DVec3::splat(2.0),
        glam::DQuat::from_rotation_y(1.5),
        DVec3::new(3.0, 1.0, 0.0),
    );
    let desc = moving_cube_scene(start, Some(end));
    for backend in backends() {
        let opts = options(&desc, backend, 1);
        let scene = prepare_scene(&desc, &opts).unwrap();
        assert!(scene.effects.motion_blur);
        let accel = build_accel(backend, &scene, &AccelOptions::default()).unwrap();
        let origin = scene.camera.position;
        let mut misses = 0;
        for step in 0..=20 {
            let time = step as f32 / 20.0;
            let placement = &scene.instances[1].placement;
            let m = placement.render_from_object(time).unwrap();
            for corner in
                [Vec3::new(0.5, 0.5, 0.5), Vec3::new(0.1, 0.9, 0.5), Vec3::new(0.9, 0.1, 0.9)]
            {
                let target = m.transform_point3(corner);
                let ray = Ray { time, ..Ray::new(origin, target - origin, f32::INFINITY) };
                match accel.intersect(&ray, &mut TraversalCounters::default()) {
                    Some(hit) if hit.geom_id == 1 => {}
                    _ => misses += 1,
                }
            }
        }
        assert_eq!(misses, 0, "{}: the moving cube was missed", backend.name());
    }
}

#[test]
fn quad_light_irradiance_matches_the_analytic_form_factor() {
    let (a, b, h) = (2.0, 1.0, 1.0);
    let mut s = scene(camera([0.0, 0.5, 4.0], [0.0, 0.0, 0.0], 20.0, 5, 5));
    let white = add_material(&mut s, diffuse(1.0));
    let light = add_material(&mut s, emissive(1.0));
    s.objects.push(object(
        "floor",
        quad([-10.0, 0.0, -10.0], [20.0, 0.0, 0.0], [0.0, 0.0, 20.0]),
        white,
        DAffine3::IDENTITY,
    ));
    s.objects.push(object(
        "light",
        quad([-a / 2.0, h, -b / 2.0], [a, 0.0, 0.0], [0.0, 0.0, b]),
        light,
        DAffine3::IDENTITY,
    ));
    let expected = 4.0 * corner_form_factor(a / 2.0, b / 2.0, h); // albedo·L·F
    for backend in backends() {
        let mut o = direct_only(&s, backend, 1);
        o.jitter = false;
        o.light_samples = 20_000;
        let got = render_ok(&s, &o).film.pixel(2, 2);
        println!("{}: radiance {got:?}, analytic {expected:.5}", backend.name());
        assert!((got.x as f64 / expected - 1.0).abs() < 0.01, "{}", backend.name());
    }
}

fn furnace(material: MaterialDesc) -> SceneDesc {
    let mut s = scene(camera([0.0, 0.0, 3.0], [0.0, 0.0, 0.0], 45.0, 16, 16));
    s.settings.background = Vec3::ONE;
    s.settings.max_depth = 64;
    let m = add_material(&mut s, material);
    s.objects.push(object("ball", sphere(1.0), m, DAffine3::IDENTITY));
    s
}

#[test]
fn white_mirror_and_glass_conserve_energy_in_a_furnace() {
    let mirror = MaterialDesc {
        albedo: Vec3::ZERO,
        specular: Specular::Mirror { reflectance: Vec3::ONE },
        ..Default::default()
    };
    let glass = MaterialDesc {
        albedo: Vec3::ZERO,
        specular: Specular::Dielectric { ior: 1.5, absorption: Vec3::ZERO },
        ..Default::default()
    };
    for backend in backends() {
        for (name, material) in [("mirror", mirror.clone()), ("glass", glass.clone())] {
            let s = furnace(material);
            let film = render_ok(&s, &options(&s, backend, 64)).film;
            let mean = luminance_sum(&film) / (3.0 * film.color.len() as f64);
            let worst = film.color.iter().map(|c| (c.x - 1.0).abs()).fold(0.0f32, f32::max);
            println!("{} {name}: mean {mean:.4}, worst pixel off by {worst:.3}", backend.name());
            assert!(film.color.iter().all(|c| c.is_finite()), "{name}: NaN");
            assert!((mean - 1.0).abs() < 0.01, "{} {name}: mean {mean}", backend.name());
            assert!(worst < 0.3, "{} {name}", backend.name());
        }
    }
}

/// A 100 × 50 × 2 = 10,000-triangle grid.
fn grid_mesh() -> std::sync::Arc<embray::scene::MeshData> {
    let (nx, nz) = (100u32, 50u32);
    let mut positions = Vec::new();
    for j in 0..=nz {
        for i in 0..=nx {
            positions.push(DVec3::new(
                i as f64 * 0.01,
                ((i * 7 + j * 3) % 5) as f64 * 0.002,
                j as f64 * 0.01,
            ));
        }
    }
    let mut indices = Vec::new();
    for j in 0..nz {
        for i in 0..nx {
            let a = j * (nx + 1) + i;
            let (b, c, d) = (a + 1, a + nx + 1, a + nx + 2);
            indices.push([a, c, b]);
            indices.push([b, c, d]);
        }
    }
    std::sync::Arc::new(embray::scene::MeshData { positions, indices, normals: None, uvs: None })
}

fn instanced_scene(copies: usize) -> SceneDesc {
    let mut s = scene(camera([0.0, 5.0, 10.0], [0.0, 0.0, 0.0], 40.0, 8, 8));
    let m = add_material(&mut s, diffuse(0.5));
    let mesh = grid_mesh();
    for i in 0..copies {
        let at = DVec3::new((i % 100) as f64 * 1.1, 0.0, (i / 100) as f64 * 1.1);
        s.objects.push(object(
            "grid",
            ShapeDesc::Mesh(mesh.clone()),
            m,
            DAffine3::from_translation(at),
        ));
    }
    s
}

#[test]
fn ten_thousand_instances_cost_far_less_than_copies() {
    for backend in backends() {
        // The structure's own byte count (obvhs counts its arrays, Embree's memory monitor
        // its device): exact, and untouched by tests running alongside.
        let measure = |desc: SceneDesc| {
            let scene = prepare_scene(&desc, &options(&desc, backend, 1)).unwrap();
            let accel = build_accel(backend, &scene, &AccelOptions::default()).unwrap();
            accel.memory_bytes().expect("both backends count their bytes")
        };
        // Real copies for comparison: 200 placements of 200 distinct (equal) meshes.
        let copies_scene = |n: usize| {
            let mut desc = instanced_scene(n);
            for object in &mut desc.objects {
                if let ShapeDesc::Mesh(mesh) = &object.shape {
                    object.shape = ShapeDesc::Mesh(std::sync::Arc::new((**mesh).clone()));
                }
            }
            desc
        };
        let one = measure(copies_scene(200)) / 200;
        let many = measure(instanced_scene(10_000));
        println!(
            "{}: {one} bytes for one placed copy; 10,000 instances take {many} bytes \
             (copies would need ~{} bytes, {:.3} %)",
            backend.name(),
            one * 10_000,
            100.0 * many as f64 / (one * 10_000) as f64
        );
        // Measured 0.024 % (Embree) and 0.026 % (obvhs).
        assert!(
            many < one * 10_000 / 1000,
            "{}: instancing is not O(1) per instance",
            backend.name()
        );
    }
}

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

#[test]
/// What the forcing costs in time is measured by `embray bench effects`, not here.
fn static_scene_builds_no_motion_support_and_forcing_it_changes_no_ray() {
    let desc = cornell(32, 32);
    for backend in backends() {
        let opts = options(&desc, backend, 4);
        let scene = prepare_scene(&desc, &opts).unwrap();
        assert!(!scene.effects.motion_blur && !scene.effects.depth_of_field);
        assert!(scene.instances.iter().all(|i| !i.placement.is_moving()), "no motion BVH needed");
        let normal = render(&desc, &opts).unwrap();
        let mut forced_opts = opts.clone();
        forced_opts.effects_mode = EffectsMode::ForceAll;
        let forced = render(&desc, &forced_opts).unwrap();
        let error = image_error(&forced.film, &normal.film);
        println!(
            "{}: forced effects vs normal {error:?}\n  normal {:?}\n  forced {:?}",
            backend.name(),
            normal.stats,
            forced.stats
        );
        assert_eq!(normal.stats, forced.stats, "{}: every ray kind, every hit", backend.name());
        // Measured 2e-14: moving-instance transforms round differently from baked meshes.
        assert!(error.relative_mse < 1e-10, "{}: {error:?}", backend.name());
    }
}
