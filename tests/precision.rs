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

/// Offsets of 1e9–1e11 units, where an f32 ulp is 64 to 8192 units, larger than the whole
/// 555-unit box. `cameraworld` and `camera` subtract the camera position in f64 (ulp 1.5e-5
/// at 1e11) before anything becomes f32, so the image stays the origin's; `world` would
/// collapse the box to a few f32 values and is refused with the reason and the way out.
#[test]
fn offsets_1e9_to_1e11_cameraworld_matches_origin_and_world_is_refused() {
    let scene = cornell(24, 24);
    for backend in backends() {
        let base = options(&scene, backend, 2);
        let reference = render_ok(&scene, &base).film;
        for offset in [1e9, 1e10, 1e11] {
            let far = |space| {
                let mut o = base.clone();
                o.offset = DVec3::new(offset, -0.5 * offset, 0.25 * offset);
                o.render_space = space;
                o
            };
            for space in [RenderSpace::Cameraworld, RenderSpace::Camera] {
                let reference = match space {
                    RenderSpace::Camera => {
                        let mut o = base.clone();
                        o.render_space = space;
                        render_ok(&scene, &o).film
                    }
                    _ => reference.clone(),
                };
                let error = image_error(&render_ok(&scene, &far(space)).film, &reference);
                println!("{} {} @ {offset:e}: {error:?}", backend.name(), space.name());
                // Scene coordinates are f32 values; plus 1e11 in f64 they round to 1.5e-5
                // units, far below a pixel's footprint, so the tolerance is tight.
                assert!(
                    error.relative_mse <= 1e-8 && error.non_finite == 0,
                    "{} {} @ {offset:e}: {error:?}",
                    backend.name(),
                    space.name()
                );
            }
            let refused = embray::render::render(&scene, &far(RenderSpace::World)).unwrap_err();
            let message = refused.to_string();
            assert!(
                message.contains("camera.lookfrom")
                    && message.contains("±1e8 (world render space")
                    && message.contains("render in cameraworld"),
                "{message}"
            );
        }
    }
}
