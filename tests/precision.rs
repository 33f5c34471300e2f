//! Far from the origin: `cameraworld` keeps full precision, `world` does not.

mod common;

use common::*;
use embray::choice::Choice;
use embray::render_space::RenderSpace;
use glam::DVec3;

#[test]
fn offset_1e7_cameraworld_matches_origin_and_world_does_not() {
    let scene = cornell(48, 48);
    for backend in backends() {
        let base = options(&scene, backend, 4);
        let reference = render_ok(&scene, &base).film;
        let far = |space| {
            let mut o = base.clone();
            o.offset = DVec3::splat(1e7);
            o.render_space = space;
            image_error(&render_ok(&scene, &o).film, &reference)
        };
        let cameraworld = far(RenderSpace::Cameraworld);
        let world = far(RenderSpace::World);
        println!("{}: offset 1e7 cameraworld {cameraworld:?}", backend.name());
        println!("{}: offset 1e7 world       {world:?}", backend.name());
        // Tolerance: relative MSE ≤ 1e-10 (in practice the images are bit-identical, since
        // the offset cancels exactly in f64 before anything is rounded to f32).
        assert!(cameraworld.relative_mse <= 1e-10, "{}: {cameraworld:?}", backend.name());
        assert_eq!(cameraworld.non_finite, 0);
        // At 1e7 an f32 ulp is 1 unit: edges and shadow boundaries of the 555-unit box move.
        assert!(
            world.relative_mse > 1e-5 && world.fraction_off > 0.1,
            "{}: world space should break down: {world:?}",
            backend.name()
        );
    }
}
