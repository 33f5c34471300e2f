//! Forcing every effect on a static scene changes no ray.

use super::*;

#[test]
/// What the forcing costs in time is measured by `embray bench effects`, not here.
fn static_scene_builds_no_motion_support_and_forcing_it_changes_no_ray() {
    let desc = cornell(32, 32);
    for backend in backends() {
        let opts = options(&desc, backend, 4);
        let scene = prepare_scene(&desc, &opts).unwrap();
        assert!(!scene.effects.motion_blur && !scene.effects.depth_of_field);
        assert!(scene.instances.iter().all(|i| !i.placement.is_moving()), "no motion BVH needed");
        let normal = render(&desc, &opts).unwrap();
        let mut forced_opts = opts.clone();
        forced_opts.effects_mode = EffectsMode::ForceAll;
        let forced = render(&desc, &forced_opts).unwrap();
        let error = image_error(&forced.film, &normal.film);
        println!(
            "{}: forced effects vs normal {error:?}\n  normal {:?}\n  forced {:?}",
            backend.name(),
            normal.stats,
            forced.stats
        );
        assert_eq!(normal.stats, forced.stats, "{}: every ray kind, every hit", backend.name());
        // Measured 2e-14: moving-instance transforms round differently from baked meshes.
        assert!(error.relative_mse < 1e-10, "{}: {error:?}", backend.name());
    }
}
