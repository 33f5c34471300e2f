//! Environment lights (`type = "environment"`, the course's SphericalDirectionalLight):
//! a diffuse sphere under a constant sky shows exactly albedo × L (the white furnace), the
//! map is seen in the directions hw5.tex's mapping gives, and a sun-and-sky map is lit the
//! same with importance sampling as the brute-force hemisphere integral says. Every
//! backend, every render space, far from the origin.

mod common;

use common::command::TempPath;
use common::*;
use embray::film::Film;
use embray::render_space::RenderSpace;
use embray::scene::IntegratorKind;
use glam::{DVec3, Vec3};

const ALBEDO: [f32; 3] = [0.8, 0.5, 0.2];

fn furnace(sky: &str, max_depth: u32) -> String {
    format!(
        r#"
[camera]
lookfrom = [0.0, 0.0, 4.0]
lookat = [0.0, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
vfov = 40.0
resolution = [24, 24]

[render]
max_depth = {max_depth}

[materials.clay]
albedo = [{}, {}, {}]

[[objects]]
type = "sphere"
material = "clay"
center = [0.0, 0.0, 0.0]
radius = 1.0

[[lights]]
type = "environment"
{sky}
"#,
        ALBEDO[0], ALBEDO[1], ALBEDO[2]
    )
}

/// Pixels of the film whose camera ray surely hits the unit sphere (well inside its disc).
fn sphere_pixels() -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    for y in 0..24 {
        for x in 0..24 {
            let (dx, dy) = (x as f32 + 0.5 - 12.0, y as f32 + 0.5 - 12.0);
            // The sphere's disc has a radius of about 8.5 pixels here.
            if (dx * dx + dy * dy).sqrt() < 6.0 {
                out.push((x, y));
            }
        }
    }
    out
}

fn corner_pixels() -> [(u32, u32); 4] {
    [(0, 0), (23, 0), (0, 23), (23, 23)]
}

#[test]
fn a_diffuse_sphere_under_a_constant_sky_shows_albedo_times_radiance() {
    let radiance = Vec3::new(2.0, 1.5, 3.0);
    let expected = Vec3::from_array(ALBEDO) * radiance;
    for max_depth in [1, 6] {
        let sky = format!("radiance = [{}, {}, {}]", radiance.x, radiance.y, radiance.z);
        let scene = scene_from_str(&furnace(&sky, max_depth));
        for backend in backends() {
            for space in [RenderSpace::Cameraworld, RenderSpace::Camera, RenderSpace::World] {
                for offset in [DVec3::ZERO, DVec3::new(3e5, -2e5, 1e5)] {
                    let mut options = options(&scene, backend, 64);
                    options.render_space = space;
                    options.offset = offset;
                    let film = render_ok(&scene, &options).film;
                    let what = format!("depth {max_depth}, {backend:?}, {space:?}, {offset}");
                    // The sky itself, in the corners, is exactly L.
                    for (x, y) in corner_pixels() {
                        assert_eq!(film.pixel(x, y), radiance, "{what}: sky at ({x}, {y})");
                    }
                    let pixels = sphere_pixels();
                    let n = pixels.len() as f64;
                    let mean =
                        pixels.iter().map(|&(x, y)| film.pixel(x, y).as_dvec3()).sum::<DVec3>() / n;
                    let var = pixels
                        .iter()
                        .map(|&(x, y)| (film.pixel(x, y).as_dvec3() - mean).powf(2.0))
                        .sum::<DVec3>()
                        / (n - 1.0);
                    let stderr = (var / n).powf(0.5);
                    let error = (mean - expected.as_dvec3()).abs();
                    println!("{what}: mean {mean:.4} (expected {expected:.4}, ±{stderr:.4})");
                    for c in 0..3 {
                        // Within 4 standard errors and 1.5 %: the furnace is exact in
                        // expectation, so only noise may remain.
                        assert!(
                            error[c] < 4.0 * stderr[c] + 1e-6
                                && error[c] < 0.015 * expected[c] as f64,
                            "{what}: channel {c} is {} against {}",
                            mean[c],
                            expected[c]
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn whitted_lights_a_diffuse_surface_with_the_sky_as_the_course_does() {
    // The course's diffuse term is kd · cos θ · L̂ with no 1/π: under a constant sky of
    // radiance L a surface shows kd · π · L.
    let radiance = Vec3::splat(1.0);
    let scene = scene_from_str(&furnace("radiance = [1.0, 1.0, 1.0]", 1));
    for backend in backends() {
        let mut options = options(&scene, backend, 256);
        options.integrator = IntegratorKind::Whitted;
        let film = render_ok(&scene, &options).film;
        assert_eq!(film.pixel(0, 0), radiance, "the sky is seen where rays leave");
        let pixels = sphere_pixels();
        let mean = pixels.iter().map(|&(x, y)| film.pixel(x, y).as_dvec3()).sum::<DVec3>()
            / pixels.len() as f64;
        let expected = Vec3::from_array(ALBEDO).as_dvec3() * std::f64::consts::PI;
        println!("{backend:?}: {mean:.4} (expected {expected:.4})");
        assert!((mean - expected).abs().max_element() < 0.02 * expected.max_element());
    }
}

/// A `width` × `height` EXR map whose texel (col, row) is `texel(col, row)`.
fn write_map(name: &str, width: u32, height: u32, texel: impl Fn(u32, u32) -> Vec3) -> TempPath {
    let dir = common::command::temp_dir(name);
    let mut film = Film::new(width, height);
    for row in 0..height {
        for col in 0..width {
            film.color[(row * width + col) as usize] = texel(col, row);
        }
    }
    let path = dir.file("sky.exr");
    embray::output::write_exr(&film, &path).unwrap();
    path
}

/// A scene seen by a 1-pixel camera at `from` looking along `dir`, under the map `file`.
fn looking(dir: DVec3, file: &std::path::Path) -> String {
    let up = if dir.y.abs() > 0.9 { "[1.0, 0.0, 0.0]" } else { "[0.0, 1.0, 0.0]" };
    format!(
        r#"
[camera]
lookfrom = [0.0, 0.0, 0.0]
lookat = [{}, {}, {}]
up = {up}
vfov = 1.0
resolution = [1, 1]

[render]
max_depth = 1

[[lights]]
type = "environment"
file = "{}"
"#,
        dir.x,
        dir.y,
        dir.z,
        file.display()
    )
}

#[test]
fn the_map_is_seen_where_the_course_mapping_puts_it() {
    let (w, h) = (16u32, 8u32);
    let code = |col: u32, row: u32| Vec3::new(col as f32, row as f32, 1.0 + (col * h + row) as f32);
    let map = write_map("environment-mapping", w, h, code);
    // Each direction sees the texel of hw5.tex's u = (1 + atan2(x, −z)/π)/2, v = acos(y)/π
    // (computed here in f64): ahead (−z) is the image centre, +x a quarter turn right.
    let cases = [
        DVec3::new(0.01, -0.01, -1.0),
        DVec3::new(1.0, 0.1, -0.3),
        DVec3::new(-1.0, 0.2, 0.1),
        DVec3::new(0.3, 0.95, 0.1),
        DVec3::new(0.2, -0.9, 0.3),
        DVec3::new(-0.1, 0.3, 1.0),
    ];
    for backend in backends() {
        for space in [RenderSpace::Cameraworld, RenderSpace::Camera, RenderSpace::World] {
            for offset in [DVec3::ZERO, DVec3::new(-4e5, 1e5, 7e5)] {
                for dir in cases {
                    let d = dir.normalize();
                    let u = 0.5 * (1.0 + d.x.atan2(-d.z) / std::f64::consts::PI);
                    let v = d.y.acos() / std::f64::consts::PI;
                    let (col, row) =
                        ((u * w as f64) as u32 % w, ((v * h as f64) as u32).min(h - 1));
                    let scene = scene_from_str(&looking(dir, &map));
                    let mut options = options(&scene, backend, 1);
                    options.jitter = false;
                    options.render_space = space;
                    options.offset = offset;
                    let seen = render_ok(&scene, &options).film.pixel(0, 0);
                    assert_eq!(
                        seen,
                        code(col, row),
                        "{backend:?} {space:?} {offset}: looking along {dir} sees texel \
                         ({}, {}), expected ({col}, {row})",
                        seen.x,
                        seen.y
                    );
                }
            }
        }
    }
}

#[test]
fn a_constant_light_probe_is_a_white_furnace_too() {
    // The angular map's solid angle per texel varies across the disc: only the right
    // Jacobian in the sampling density keeps the furnace exact.
    let radiance = Vec3::splat(1.5);
    let map = write_map("environment-probe-furnace", 16, 16, |_, _| radiance);
    let sky = format!("file = \"{}\"\nmapping = \"probe\"", map.display());
    for max_depth in [1, 6] {
        let scene = scene_from_str(&furnace(&sky, max_depth));
        for backend in backends() {
            let film = render_ok(&scene, &options(&scene, backend, 64)).film;
            let pixels = sphere_pixels();
            let mean = pixels.iter().map(|&(x, y)| film.pixel(x, y).as_dvec3()).sum::<DVec3>()
                / pixels.len() as f64;
            let expected = (Vec3::from_array(ALBEDO) * radiance).as_dvec3();
            println!("probe, depth {max_depth}, {backend:?}: {mean:.4} (expected {expected:.4})");
            assert!(
                ((mean - expected) / expected).abs().max_element() < 0.015,
                "{backend:?}: {mean} vs {expected}"
            );
        }
    }
}
