//! A quad light against its analytic form factor; mirrors and glass in a furnace.

use super::*;

/// A floor under an `a` × `b` quad light at height `h`; `facing_down` picks the order of its
/// edges (a quad emits along u × v), `two_sided` its emission's sides.
fn floor_under_quad_light(facing_down: bool, two_sided: bool) -> SceneDesc {
    let (a, b, h) = LIGHT;
    let mut s = scene(camera([0.0, 0.5, 4.0], [0.0, 0.0, 0.0], 20.0, 5, 5));
    let white = add_material(&mut s, diffuse(1.0));
    let light =
        add_material(&mut s, MaterialDesc { two_sided_emission: two_sided, ..emissive(1.0) });
    s.objects.push(object(
        "floor",
        quad([-10.0, 0.0, -10.0], [20.0, 0.0, 0.0], [0.0, 0.0, 20.0]),
        white,
        DAffine3::IDENTITY,
    ));
    let (u, v) = ([a, 0.0, 0.0], [0.0, 0.0, b]);
    let (u, v) = if facing_down { (u, v) } else { (v, u) };
    s.objects.push(object("light", quad([-a / 2.0, h, -b / 2.0], u, v), light, DAffine3::IDENTITY));
    s
}

const LIGHT: (f64, f64, f64) = (2.0, 1.0, 1.0);

/// The floor's radiance under the light, per backend (direct light only, many samples).
fn floor_radiance(s: &SceneDesc) -> Vec<(&'static str, f64)> {
    backends()
        .into_iter()
        .map(|backend| {
            let mut o = direct_only(s, backend, 1);
            o.jitter = false;
            o.light_samples = 20_000;
            (backend.name(), render_ok(s, &o).film.pixel(2, 2).x as f64)
        })
        .collect()
}

#[test]
fn quad_light_irradiance_matches_the_analytic_form_factor() {
    let (a, b, h) = LIGHT;
    let expected = 4.0 * corner_form_factor(a / 2.0, b / 2.0, h); // albedo·L·F
    // Facing the floor, one-sided or two; facing away, two-sided only.
    for (facing_down, two_sided) in [(true, false), (true, true), (false, true)] {
        let s = floor_under_quad_light(facing_down, two_sided);
        for (backend, got) in floor_radiance(&s) {
            println!(
                "{backend} (down {facing_down}, two-sided {two_sided}): {got:.5}, analytic {expected:.5}"
            );
            assert!((got / expected - 1.0).abs() < 0.01, "{backend} {facing_down} {two_sided}");
        }
    }
}

#[test]
fn a_one_sided_light_facing_away_lights_nothing_and_is_reported() {
    let away = floor_under_quad_light(false, false);
    for (backend, got) in floor_radiance(&away) {
        assert_eq!(got, 0.0, "{backend}");
    }
    let warnings = |s: &SceneDesc| render_ok(s, &options(s, backends()[0], 1)).warnings;
    let said = warnings(&away);
    assert_eq!(said.len(), 1, "{said:?}");
    assert!(said[0].contains("light") && said[0].contains("lights nothing"), "{said:?}");
    assert_eq!(warnings(&floor_under_quad_light(true, false)), Vec::<String>::new());
    assert_eq!(warnings(&floor_under_quad_light(false, true)), Vec::<String>::new());
}

#[test]
fn a_two_sided_light_is_seen_from_behind() {
    // The light faces the floor; the camera above sees its back: black one-sided, L two-sided.
    for two_sided in [false, true] {
        let mut s = floor_under_quad_light(true, two_sided);
        s.camera = camera([0.0, 3.0, 0.5], [0.0, 0.0, 0.0], 10.0, 3, 3);
        for backend in backends() {
            let seen = render_ok(&s, &options(&s, backend, 4)).film.pixel(1, 1).x;
            let expected = if two_sided { 1.0 } else { 0.0 };
            assert!(
                (seen - expected).abs() < 1e-4,
                "{} two-sided {two_sided}: {seen}",
                backend.name()
            );
        }
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
        specular: Specular::dielectric(1.5, Vec3::ZERO),
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
