//! Closed-form checks of the renderer's radiance.

mod common;

use common::*;
use embray::choice::Choice;
use embray::render::prepare_scene;
use glam::Vec3;

const QUAD_UNDER_POINT_LIGHT: &str = r#"
[camera]
lookfrom = [0.0, 6.0, 6.0]
lookat = [0.0, 0.0, 0.0]
vfov = 40.0
resolution = [33, 33]

[materials.grey]
albedo = [0.5, 0.25, 0.75]

[[objects]]
type = "quad"
material = "grey"
corner = [-50.0, 0.0, -50.0]
u = [100.0, 0.0, 0.0]
v = [0.0, 0.0, 100.0]

[[lights]]
type = "point"
position = [1.0, 4.0, -0.5]
intensity = [100.0, 100.0, 100.0]
"#;

#[test]
fn diffuse_quad_lit_by_point_light_matches_closed_form_radiance() {
    let scene = scene_from_str(QUAD_UNDER_POINT_LIGHT);
    let light = Vec3::new(1.0, 4.0, -0.5);
    let albedo = Vec3::new(0.5, 0.25, 0.75);
    for backend in backends() {
        let mut opts = options(&scene, backend, 1);
        opts.jitter = false;
        opts.max_depth = 1;
        let out = render_ok(&scene, &opts);
        // Rays through pixel centres, in world space, from the renderer's own camera model.
        let mut world = opts.clone();
        world.render_space = embray::render_space::RenderSpace::World;
        let camera = prepare_scene(&scene, &world).unwrap().camera;
        let mut worst = 0.0f32;
        for y in 0..33 {
            for x in 0..33 {
                let ray =
                    camera.generate_ray(glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5), None);
                let t = -ray.origin.y / ray.dir.y;
                assert!(t > 0.0, "every pixel sees the plane");
                let p = ray.origin + ray.dir * t;
                let to_light = light - p;
                let cos = to_light.y / to_light.length();
                let expected =
                    albedo / std::f32::consts::PI * 100.0 * cos / to_light.length_squared();
                let got = out.film.pixel(x, y);
                let rel = ((got - expected).abs() / expected).max_element();
                worst = worst.max(rel);
            }
        }
        println!("{}: worst relative error {worst:.2e}", backend.name());
        assert!(worst < 0.01, "{}: radiance off by {:.3}%", backend.name(), worst * 100.0);
    }
}
