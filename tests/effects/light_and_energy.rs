//! A quad light against its analytic form factor; mirrors and glass in a furnace.

use super::*;

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
