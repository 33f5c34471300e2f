//! Spot lights (`type = "spot"`, the course's SpotLight): seen from the light itself, every
//! pixel of a lit floor is the point light's value times the cone's factor at that pixel's
//! angle from the axis: full within half the falloff angle, nothing beyond half the coverage
//! angle, the fourth-power blend between. Both integrators, both backends.

mod common;

use common::*;
use embray::choice::Choice;
use embray::scene::{IntegratorKind, LightDesc};

fn floor_under(light: &str) -> String {
    format!(
        r#"
[camera]
lookfrom = [0.0, 6.0, 0.0]
lookat = [0.0, 0.0, 0.0]
up = [0.0, 0.0, -1.0]
vfov = 90.0
resolution = [32, 32]

[render]
max_depth = 1
background = [0.0, 0.0, 0.0]

[materials.grey]
albedo = [0.5, 0.5, 0.5]

[[objects]]
type = "quad"
material = "grey"
corner = [-20.0, 0.0, -20.0]
u = [0.0, 0.0, 40.0]
v = [40.0, 0.0, 0.0]

[[lights]]
{light}
"#
    )
}

const POINT: &str = "type = \"point\"\nposition = [0.0, 6.0, 0.0]\nintensity = [50.0, 50.0, 50.0]";
const SPOT: &str = "type = \"spot\"\nposition = [0.0, 6.0, 0.0]\ndirection = [0.0, -1.0, 0.0]\n\
    intensity = [50.0, 50.0, 50.0]\ncoverage_angle = 60.0\nfalloff_angle = 20.0";

/// The cone factor the scene's spot gives at angle `alpha` (radians) from its axis.
fn factor(alpha: f64) -> f64 {
    let (falloff, coverage) = (10f64.to_radians().cos(), 30f64.to_radians().cos());
    let c = alpha.cos();
    if c >= falloff {
        1.0
    } else if c > coverage {
        ((c - coverage) / (falloff - coverage)).powi(4)
    } else {
        0.0
    }
}

#[test]
fn a_spot_light_is_a_point_light_times_its_cone() {
    let point = scene_from_str(&floor_under(POINT));
    let spot = scene_from_str(&floor_under(SPOT));
    assert!(matches!(spot.lights[0], LightDesc::Spot(_)));
    for integrator in [IntegratorKind::Path, IntegratorKind::Whitted] {
        for backend in backends() {
            let mut options = options(&point, backend, 1);
            options.jitter = false;
            options.integrator = integrator;
            let p = render_ok(&point, &options).film;
            let s = render_ok(&spot, &options).film;
            let (mut full, mut blended, mut dark) = (0, 0, 0);
            for y in 0..32 {
                for x in 0..32 {
                    // The camera sits at the light: a pixel's ray is the light's direction.
                    let u = (x as f64 + 0.5) / 16.0 - 1.0;
                    let v = (y as f64 + 0.5) / 16.0 - 1.0;
                    let alpha = (u * u + v * v).sqrt().atan();
                    let expected = p.pixel(x, y).x as f64 * factor(alpha);
                    let got = s.pixel(x, y).x as f64;
                    let what = format!(
                        "{integrator:?} {} ({x}, {y}) at {:.2}°",
                        backend.name(),
                        alpha.to_degrees()
                    );
                    assert!(
                        (got - expected).abs() <= 1e-4 + 1e-3 * expected,
                        "{what}: {got} vs {expected}"
                    );
                    let f = factor(alpha);
                    if f == 1.0 {
                        full += 1;
                    } else if f == 0.0 {
                        dark += 1;
                    } else {
                        blended += 1;
                    }
                }
            }
            assert!(full > 0 && blended > 20 && dark > 100, "{full} {blended} {dark}");
        }
    }
}

#[test]
fn spot_angles_out_of_range_are_refused_with_their_line() {
    let bad = SPOT.replace("falloff_angle = 20.0", "falloff_angle = 70.0");
    let path = repo_path("tests/inline.toml");
    let text = floor_under(&bad);
    let line = 1 + text.lines().position(|l| l.starts_with("falloff_angle")).unwrap();
    let message = embray::scene::load_str(&text, &path).unwrap_err().to_string();
    assert!(message.contains("lights[0].falloff_angle is 70"), "{message}");
    assert!(message.contains(&format!("(line {line})")), "{message}");
    let missing = SPOT.replace("coverage_angle = 60.0\n", "");
    let message = embray::scene::load_str(&floor_under(&missing), &path).unwrap_err().to_string();
    assert!(message.contains("coverage_angle"), "{message}");
}
