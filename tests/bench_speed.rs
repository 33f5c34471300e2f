//! `embray bench speed` on a tiny configuration: every number of a row is sane.

use embray::accel::{BackendKind, BuildQuality};
use embray::bench::{procedural, speed};
use embray::choice::Choice;

#[test]
fn speed_rows_of_a_tiny_scene_are_finite_and_positive() {
    let scene = procedural::displaced_sphere_scene(2000, 16, 16);
    for backend in BackendKind::compiled() {
        let row =
            speed::measure("tiny", &scene, backend, 1, 1, BuildQuality::Medium).expect("measures");
        println!("{row:?}");
        assert_eq!(row.backend, backend.name());
        assert!(row.triangles > 1000, "{row:?}");
        for (what, value) in [
            ("build_ms low", row.build_ms[0]),
            ("build_ms medium", row.build_ms[1]),
            ("build_ms high", row.build_ms[2]),
            ("primary_mrays", row.primary_mrays),
            ("primary_batch_mrays", row.primary_batch_mrays),
            ("diffuse_mrays", row.diffuse_mrays),
            ("samples_per_s_1t", row.samples_per_s_1t),
            ("samples_per_s_2t", row.samples_per_s_2t),
        ] {
            assert!(value.is_finite() && value > 0.0, "{}: {what} = {value}", backend.name());
        }
        // The raw loop exists for Embree only.
        let raw = row.raw_embree_mrays;
        assert_eq!(raw.is_some(), backend == BackendKind::Embree, "{row:?}");
        assert!(raw.is_none_or(|r| r.is_finite() && r > 0.0), "{row:?}");
        // Both backends count their structure's bytes; any BVH takes some.
        assert!(row.accel_mib.is_finite() && row.accel_mib > 0.0, "{row:?}");
    }
}

#[test]
fn query_rows_cover_every_backend_batch_mode_and_triangle_test_with_sane_costs() {
    use embray::bench::queries;
    let scene = procedural::displaced_sphere_scene(2000, 16, 16);
    let rows = queries::measure(&scene, &BackendKind::compiled(), 1).expect("measures");
    let expected: Vec<(&str, &str)> = BackendKind::compiled()
        .into_iter()
        .flat_map(|b| match b {
            BackendKind::Embree => vec![
                ("embree", "single"),
                ("embree", "packets8"),
                ("embree", "packets16"),
                ("embree", "single (fast)"),
                ("embree", "packets8 (fast)"),
                ("embree", "packets16 (fast)"),
            ],
            BackendKind::Obvhs => vec![("obvhs", "single")],
        })
        .collect();
    let got: Vec<(&str, &str)> = rows.iter().map(|r| (r.backend, r.mode.as_str())).collect();
    assert_eq!(got, expected);
    for r in &rows {
        for (what, ns) in
            [("camera", r.camera_ns), ("bounce", r.bounce_ns), ("shadow", r.shadow_ns)]
        {
            // A ray query costs more than a nanosecond and less than a millisecond.
            assert!(ns.is_finite() && ns > 1.0 && ns < 1e6, "{r:?}: {what} {ns} ns");
        }
    }
    assert!(queries::markdown(&rows).lines().count() == rows.len() + 2);
}
