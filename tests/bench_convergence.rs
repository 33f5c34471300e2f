//! `embray bench convergence`: the reference round-trips through EXR, the error falls with
//! spp, and a reference of the wrong size or with non-finite values is refused.

mod common;

use common::command::temp_dir;
use common::*;
use embray::bench::convergence::{ConvergenceError, measure, read_reference, spp_for_rmse};
use embray::output::write_exr;

#[test]
fn error_falls_with_spp_against_an_exr_reference() {
    let scene = cornell(12, 12);
    let backend = backends()[0];
    let mut reference_options = options(&scene, backend, 1024);
    reference_options.seed = 99;
    let reference = render_ok(&scene, &reference_options).film;
    let dir = temp_dir("convergence");
    let path = dir.join("reference.exr");
    write_exr(&reference, &path).unwrap();
    let read = read_reference(&path).unwrap();
    assert_eq!(read.color, reference.color, "the EXR keeps the linear colour exactly");
    let rows = measure(&scene, &options(&scene, backend, 1), &read, &[4, 64], &path).unwrap();
    println!("{}", embray::bench::convergence::markdown(&rows));
    assert_eq!(rows.iter().map(|r| r.spp).collect::<Vec<_>>(), [4, 64]);
    assert!(rows[1].rmse < 0.5 * rows[0].rmse, "{rows:?}");
    assert!(rows.iter().all(|r| r.seconds > 0.0 && r.mse_seconds > 0.0), "{rows:?}");
    let needed = spp_for_rmse(&rows, rows[1].rmse / 2.0).unwrap();
    assert!((needed - 256.0).abs() < 1e-6, "{needed}");
    let wrong = cornell(10, 12);
    let refused = measure(&wrong, &options(&wrong, backend, 1), &read, &[4], &path);
    assert!(matches!(refused, Err(ConvergenceError::Size { .. })), "{refused:?}");

    // A reference with a NaN or an infinity is refused before anything renders.
    let mut broken = reference.clone();
    broken.color[12 + 3].x = f32::NAN;
    broken.color[12 * 5 + 7].y = f32::INFINITY;
    let broken_path = dir.join("broken.exr");
    write_exr(&broken, &broken_path).unwrap();
    let broken = read_reference(&broken_path).unwrap();
    let refused = measure(&scene, &options(&scene, backend, 1), &broken, &[4], &broken_path);
    match refused {
        Err(e @ ConvergenceError::NonFinite { count: 2, x: 3, y: 1, .. }) => {
            assert!(e.to_string().contains("broken.exr"), "{e}")
        }
        other => panic!("{other:?}"),
    }
}
