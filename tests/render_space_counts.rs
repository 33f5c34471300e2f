//! BVH quality by render space on the axis-aligned city block: translation-only camera space
//! costs the same primitive tests as world space; rotated camera space costs more.

mod common;

use common::*;
use embray::choice::Choice;
use embray::render::render;
use embray::render_space::RenderSpace;
use embray::scene::load;

#[test]
fn rotated_camera_space_costs_more_primitive_tests_than_cameraworld() {
    let mut scene = load(&repo_path("scenes/city_block.toml")).unwrap();
    scene.camera.width = 96;
    scene.camera.height = 60;
    for backend in backends() {
        let mut tests = Vec::new();
        for space in [RenderSpace::World, RenderSpace::Camera, RenderSpace::Cameraworld] {
            let mut o = options(&scene, backend, 2);
            o.render_space = space;
            o.count_traversal = true;
            let out = render(&scene, &o).unwrap();
            tests.push((space, out.stats.traversal, out.observes));
        }
        // Both backends count primitive tests when asked (Embree through user geometry).
        assert!(tests[0].2.prim_tests, "{}: primitive tests not observed", backend.name());
        let prims = |i: usize| tests[i].1.prim_tests as f64;
        let (world, camera, cameraworld) = (prims(0), prims(1), prims(2));
        println!(
            "{}: primitive tests world {world}, camera {camera}, cameraworld {cameraworld}; \
             camera/cameraworld = {:.2}, cameraworld/world = {:.4}",
            backend.name(),
            camera / cameraworld,
            cameraworld / world
        );
        assert!((cameraworld / world - 1.0).abs() < 0.02, "{}", backend.name());
        assert!(camera > 1.2 * cameraworld, "{}: rotated space should cost more", backend.name());
    }
}
