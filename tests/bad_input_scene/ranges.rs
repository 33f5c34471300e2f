//! Values out of range, degenerate cameras, lens and render settings.

use super::*;

#[test]
fn zero_resolution_is_rejected() {
    let err = load_err(&CAMERA.replace("[32, 24]", "[32, 0]"));
    assert_contains(
        &err,
        &["scene.toml: camera.resolution[1] is 0, but must be between 1 and 16384", "(line 5)"],
    );
}

#[test]
fn resolution_above_16384_is_rejected() {
    let err = load_err(&CAMERA.replace("[32, 24]", "[16385, 24]"));
    assert_contains(&err, &["camera.resolution[0] is 16385", "between 1 and 16384"]);
}

#[test]
fn negative_resolution_is_a_type_error_with_line() {
    let err = load_err(&CAMERA.replace("[32, 24]", "[-32, 24]"));
    assert_contains(&err, &["scene.toml", "line 5", "integer `-32`"]);
}

#[test]
fn zero_spp_is_rejected() {
    let err = load_err(&format!("{CAMERA}[render]\nspp = 0\n"));
    assert_contains(
        &err,
        &["scene.toml: render.spp is 0, but must be between 1 and 1048576", "(line 7)"],
    );
}

#[test]
fn vfov_outside_0_180_is_rejected() {
    for vfov in ["0.0", "180.0", "-10", "200.0"] {
        let err = load_err(&CAMERA.replace("vfov = 40.0", &format!("vfov = {vfov}")));
        assert_contains(&err, &["scene.toml: camera.vfov is", "between 0 and 180", "(line 4)"]);
    }
}

#[test]
fn non_positive_radius_is_rejected() {
    // 1e-300 is > 0 in f64 but 0 in f32, which render space holds it in: shown short.
    for radius in ["0.0", "-1.5", "1e-300"] {
        let err = load_err(&scene_with(&format!(
            "[[objects]]\ntype = \"sphere\"\nmaterial = \"white\"\ncenter = [0, 0, 0]\nradius = {radius}\n"
        )));
        assert_contains(
            &err,
            &[
                &format!("scene.toml: objects[0].radius is {}", radius.trim_end_matches(".0")),
                "> 0",
            ],
        );
    }
}

#[test]
fn negative_albedo_is_rejected() {
    let err = load_err(&format!("{CAMERA}[materials.grey]\nalbedo = [0.5, -0.1, 0.5]\n"));
    assert_contains(
        &err,
        &["scene.toml: materials.grey.albedo[1] is -0.1, but must be in [0, 1]", "(line 7)"],
    );
}

#[test]
fn albedo_above_one_is_rejected() {
    let err = load_err(&format!("{CAMERA}[materials.grey]\nalbedo = [1.5, 0.5, 0.5]\n"));
    assert_contains(&err, &["materials.grey.albedo[0] is 1.5, but must be in [0, 1]"]);
}

#[test]
fn negative_emission_is_rejected() {
    let err = load_err(&format!("{CAMERA}[materials.lamp]\nemission = [1, 1, -2]\n"));
    assert_contains(&err, &["scene.toml: materials.lamp.emission[2] is -2, but must be >= 0"]);
}

#[test]
fn negative_light_intensity_is_rejected() {
    let err = load_err(&format!(
        "{CAMERA}[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\nintensity = [-1, 1, 1]\n"
    ));
    assert_contains(
        &err,
        &["scene.toml: lights[0].intensity[0] is -1, but must be >= 0", "(line 9)"],
    );
}

#[test]
fn negative_quad_light_emission_is_rejected() {
    let err = load_err(&format!(
        "{CAMERA}[[lights]]\ntype = \"quad\"\ncorner = [0, 1, 0]\nu = [1, 0, 0]\nv = [0, 0, 1]\nemission = [1, -1, 1]\n"
    ));
    assert_contains(&err, &["lights[0].emission[1] is -1"]);
}

#[test]
fn negative_aperture_and_zero_focus_distance_are_rejected() {
    let err = load_err(&format!("{CAMERA}aperture = -0.5\n"));
    assert_contains(&err, &["camera.aperture is -0.5, but must be >= 0"]);
    let err = load_err(&format!("{CAMERA}focus_distance = 0.0\n"));
    assert_contains(&err, &["camera.focus_distance is 0, but must be > 0"]);
}

#[test]
fn lookfrom_equal_to_lookat_is_a_degenerate_camera() {
    let err = load_err(&CAMERA.replace("lookat = [0.0, 0.0, 0.0]", "lookat = [0.0, 0.0, -5.0]"));
    assert_contains(
        &err,
        &[
            "scene.toml: degenerate camera",
            "camera.lookfrom and camera.lookat are the same point [0, 0, -5]",
        ],
    );
}

#[test]
fn zero_up_vector_is_a_degenerate_camera() {
    let err = load_err(&format!("{CAMERA}up = [0, 0, 0]\n"));
    let says = "camera.up [0, 0, 0] has no direction";
    assert_contains(&err, &["scene.toml: degenerate camera", says, "(line 6)"]);
    // Too short to normalise is no direction either, and its number is shown short.
    let err = load_err(&format!("{CAMERA}up = [1e-300, 0, 0]\n"));
    assert_contains(&err, &["camera.up [1e-300, 0, 0] has no direction", "(line 6)"]);
}

#[test]
fn up_parallel_to_view_direction_is_allowed() {
    let scene = load(&format!("{CAMERA}up = [0, 0, 1]\n"));
    assert_eq!(scene.camera.up, DVec3::Z);
}

#[test]
fn aperture_and_f_number_together_are_rejected() {
    let err = load_err(&format!("{CAMERA}aperture = 0.1\nf_number = 2.0\nfocal_length = 0.05\n"));
    assert_contains(
        &err,
        &["scene.toml: camera takes `aperture` or `f_number`, not both (line 7)"],
    );
    let err = load_err(&format!("{CAMERA}aperture = 0.1\nfocal_length = 0.05\n"));
    assert_contains(&err, &["camera takes `aperture` or `focal_length`, not both (line 7)"]);
}

#[test]
fn f_number_and_focal_length_need_each_other() {
    let err = load_err(&format!("{CAMERA}f_number = 2.0\n"));
    assert_contains(
        &err,
        &["scene.toml: camera (with f_number) is missing the field `focal_length` (line 6)"],
    );
    let err = load_err(&format!("{CAMERA}focal_length = 0.05\n"));
    assert_contains(&err, &["camera (with focal_length) is missing the field `f_number` (line 6)"]);
}

#[test]
fn f_number_and_focal_length_must_be_positive() {
    let err = load_err(&format!("{CAMERA}f_number = 0.0\nfocal_length = 0.05\n"));
    assert_contains(
        &err,
        &["scene.toml: camera.f_number is 0, but must be at least 0.01", "(line 6)"],
    );
    let err = load_err(&format!("{CAMERA}f_number = 2.8\nfocal_length = -1\n"));
    assert_contains(&err, &["camera.focal_length is -1, but must be > 0 (line 7)"]);
}

#[test]
fn unknown_lens_shape_is_named() {
    let err = load_err(&format!("{CAMERA}lens = \"hexagon\"\n"));
    assert_contains(
        &err,
        &["scene.toml", "line 6", "unknown variant `hexagon`", "expected `disk` or `square`"],
    );
}

#[test]
fn zero_light_samples_and_unknown_integrator_are_rejected() {
    let err = load_err(&format!("{CAMERA}[render]\nlight_samples = 0\n"));
    assert_contains(
        &err,
        &["scene.toml: render.light_samples is 0, but must be between 1 and 65536 (line 7)"],
    );
    let err = load_err(&format!("{CAMERA}[render]\nintegrator = \"bdpt\"\n"));
    assert_contains(
        &err,
        &["scene.toml", "line 7", "unknown variant `bdpt`", "expected `path` or `whitted`"],
    );
}
