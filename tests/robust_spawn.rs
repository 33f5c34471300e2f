//! Spawned rays never re-hit the surface they leave, even at grazing angles far away.

mod common;

use common::*;
use embray::choice::Choice;
use embray::render_space::RenderSpace;
use glam::DVec3;

/// One large plane and a point light 2 units above it, 400 units away: the light arrives at
/// about 0.3° above the surface. The plane is the only geometry, so any occluded shadow ray
/// is a self-intersection.
const GRAZING_PLANE: &str = r#"
[camera]
lookfrom = [0.0, 30.0, 120.0]
lookat = [0.0, 0.0, 0.0]
vfov = 50.0
resolution = [48, 32]

[materials.white]
albedo = [0.8, 0.8, 0.8]

[[objects]]
type = "quad"
material = "white"
corner = [-1000.0, 0.0, -1000.0]
u = [2000.0, 0.0, 0.0]
v = [0.0, 0.0, 2000.0]

[[lights]]
type = "point"
position = [0.0, 2.0, -400.0]
intensity = [1e6, 1e6, 1e6]
"#;

#[test]
fn grazing_light_at_offset_1e6_causes_no_self_shadowing() {
    let scene = scene_from_str(GRAZING_PLANE);
    for backend in backends() {
        for space in [RenderSpace::Cameraworld, RenderSpace::World] {
            let mut o = options(&scene, backend, 4);
            o.offset = DVec3::new(1e6, 1e6, -1e6);
            o.render_space = space;
            o.max_depth = 2;
            let out = render_ok(&scene, &o);
            println!("{} {}: {:?}", backend.name(), space.name(), out.stats.shadow);
            assert!(out.stats.shadow.rays > 1000, "the test must trace shadow rays");
            assert_eq!(
                out.stats.shadow.hits,
                0,
                "{} {}: self-shadowed rays",
                backend.name(),
                space.name()
            );
            let lit = out.film.color.iter().filter(|c| c.x > 0.0).count();
            assert!(lit > out.film.color.len() / 2, "the plane must be lit");
        }
    }
}
