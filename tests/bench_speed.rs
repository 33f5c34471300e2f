//! `embray bench speed` on a tiny configuration: every number of a row is sane.

use embray::accel::BackendKind;
use embray::bench::{procedural, speed};

#[test]
fn speed_rows_of_a_tiny_scene_are_finite_and_positive() {
    let scene = procedural::displaced_sphere_scene(2000, 16, 16);
    for backend in BackendKind::compiled() {
        let row = speed::measure("tiny", &scene, backend, 1, 1).expect("measures");
        println!("{row:?}");
        assert_eq!(row.backend, backend.name());
        assert!(row.triangles > 1000, "{row:?}");
        for (what, value) in [
            ("build_ms", row.build_ms),
            ("primary_mrays", row.primary_mrays),
            ("diffuse_mrays", row.diffuse_mrays),
            ("samples_per_s_1t", row.samples_per_s_1t),
            ("samples_per_s_2t", row.samples_per_s_2t),
        ] {
            assert!(value.is_finite() && value > 0.0, "{}: {what} = {value}", backend.name());
        }
        // Resident memory can stay flat for a scene this small.
        assert!(row.accel_mib.is_finite() && row.accel_mib >= 0.0, "{row:?}");
    }
}
