//! Depth of field and motion blur against their definitions.

use super::*;

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
