//! Transforms (singular, malformed), motion, `repeat` and `smooth`.

use super::*;

#[test]
fn zero_scale_is_a_singular_transform() {
    let err = load_err(&scene_with(&format!(
        "{BOX}transform = [{{ translate = [1, 2, 3] }}, {{ scale = [1, 0, 1] }}]\n"
    )));
    assert_contains(
        &err,
        &["scene.toml: objects[0].transform[1]: scale [1, 0, 1] is singular", "(line 13)"],
    );
}

#[test]
fn singular_matrix_is_rejected() {
    let err = load_err(&scene_with(&format!(
        "{BOX}transform = [{{ matrix = [[1, 2, 3, 0], [2, 4, 6, 0], [0, 0, 1, 0], [0, 0, 0, 1]] }}]\n"
    )));
    assert_contains(
        &err,
        &["scene.toml: objects[0].transform[0]: matrix is singular (determinant 0)"],
    );
}

#[test]
fn matrix_last_row_must_be_0001() {
    let err = load_err(&scene_with(&format!(
        "{BOX}transform = [{{ matrix = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0.5, 1]] }}]\n"
    )));
    assert_contains(
        &err,
        &["objects[0].transform[0]: matrix last row is [0, 0, 0.5, 1], but must be [0, 0, 0, 1]"],
    );
}

#[test]
fn zero_rotation_axis_is_rejected() {
    let err = load_err(&scene_with(&format!(
        "{BOX}transform = [{{ rotate = {{ axis = [0, 0, 0], degrees = 30 }} }}]\n"
    )));
    assert_contains(&err, &["objects[0].transform[0]: rotate axis [0, 0, 0] has zero length"]);
}

#[test]
fn transform_entry_with_two_keys_is_rejected() {
    let err = load_err(&scene_with(&format!(
        "{BOX}transform = [{{ scale = 2.0, translate = [1, 0, 0] }}]\n"
    )));
    assert_contains(
        &err,
        &[
            "scene.toml: objects[0].transform[0] must have exactly one of the keys scale, rotate, \
             translate, matrix; it has scale, translate",
            "(line 13)",
        ],
    );
}

#[test]
fn unknown_transform_kind_is_named() {
    let err = load_err(&scene_with(&format!("{BOX}transform = [{{ shear = 2.0 }}]\n")));
    assert_contains(&err, &["scene.toml", "unknown field `shear`", "line 13"]);
}

#[test]
fn singular_quad_light_transform_names_the_light() {
    let err = load_err(&format!(
        "{CAMERA}[[lights]]\ntype = \"quad\"\ncorner = [0, 1, 0]\nu = [1, 0, 0]\nv = [0, 0, 1]\nemission = [1, 1, 1]\ntransform = [{{ scale = 0.0 }}]\n"
    ));
    assert_contains(&err, &["scene.toml: lights[0].transform[0]: scale [0, 0, 0] is singular"]);
}

#[test]
fn non_uniformly_scaled_sphere_is_an_ellipsoid_but_singular_is_rejected() {
    let sphere =
        "[[objects]]\ntype = \"sphere\"\nmaterial = \"white\"\ncenter = [0, 0, 0]\nradius = 1.0\n";
    let scene = load(&scene_with(&format!("{sphere}transform = [{{ scale = [1, 2, 1] }}]\n")));
    let stretched = scene.objects[0].world_from_object.transform_vector3(DVec3::Y);
    assert_eq!(stretched, DVec3::new(0.0, 2.0, 0.0));
    let err = load_err(&scene_with(&format!(
        "{sphere}transform = [{{ matrix = [[1, 0, 0, 0], [0, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]] }}]\n"
    )));
    assert_contains(
        &err,
        &["scene.toml: objects[0].transform[0]: matrix is singular (determinant 0)", "(line 13)"],
    );
}

/// Invertible in f64 but not in f32, which render space and both backends hold it in: a
/// scale of 1e-200 along one axis (Embree used to refuse it with no file or line, and obvhs
/// rendered it).
#[test]
fn a_transform_singular_in_f32_is_named() {
    let err = load_err(&scene_with(&format!("{BOX}transform = [{{ scale = [1e-200, 1, 1] }}]\n")));
    assert_contains(
        &err,
        &["objects[0].transform: the composed transform is singular in f32", "(line 13)"],
    );
}

/// A motion whose scale changes sign (a mirror at one end only) would pass through a
/// singular transform: refused at the line of `transform_end`, for both backends.
#[test]
fn a_motion_that_mirrors_on_the_way_is_named() {
    let err = load_err(&scene_with(&format!(
        "{BOX}transform = [{{ translate = [0, 0, 0] }}]\ntransform_end = [{{ scale = [-1, 1, 1] }}]\n"
    )));
    assert_contains(
        &err,
        &["objects[0].transform_end: the scale is zero or changes sign", "(line 14)"],
    );
    // Mirrored at both ends, it does not change sign.
    let both = "transform = [{ scale = [-1, 1, 1] }]\ntransform_end = [{ scale = [-2, 1, 1] }]\n";
    scene::load_str(&scene_with(&format!("{BOX}{both}")), &source()).expect("mirrored throughout");
}

#[test]
fn singular_transform_end_is_named() {
    let err = load_err(&scene_with(&format!("{BOX}transform_end = [{{ scale = [1, 0, 1] }}]\n")));
    assert_contains(
        &err,
        &["scene.toml: objects[0].transform_end[0]: scale [1, 0, 1] is singular", "(line 13)"],
    );
    let err = load_err(&scene_with(&format!("{BOX}transform_end = [{{}}]\n")));
    assert_contains(
        &err,
        &[
            "objects[0].transform_end[0] must have exactly one of the keys",
            "it has none",
            "(line 13)",
        ],
    );
    let err = load_err(&scene_with(&format!(
        "{BOX}transform_end = [{{ scale = 1e-200 }}, {{ scale = 1e-200 }}]\n"
    )));
    assert_contains(&err, &["objects[0].transform_end: the composed transform is singular"]);
}

#[test]
fn repeat_counts_are_checked() {
    let err = load_err(&scene_with(&format!(
        "{BOX}repeat = {{ count = [2, 0, 2], spacing = [1, 1, 1] }}\n"
    )));
    assert_contains(
        &err,
        &["scene.toml: objects[0].repeat.count[1] is 0, but must be >= 1 (line 13)"],
    );
    let err = load_err(&scene_with(&format!(
        "{BOX}repeat = {{ count = [1000, 1000, 2], spacing = [1, 1, 1] }}\n"
    )));
    assert_contains(
        &err,
        &["objects[0].repeat.count is 1000 × 1000 × 2 = 2000000 copies, but must be at most \
             1000000 copies (line 13)"],
    );
    let err = load_err(&scene_with(&format!(
        "{BOX}repeat = {{ count = [-1, 1, 1], spacing = [1, 1, 1] }}\n"
    )));
    assert_contains(&err, &["scene.toml", "line 13", "integer `-1`"]);
    let err = load_err(&scene_with(&format!("{BOX}repeat = {{ count = [2, 1, 1] }}\n")));
    assert_contains(&err, &["scene.toml", "line 13", "missing field `spacing`"]);
}

#[test]
fn repeat_spacing_that_overflows_is_rejected() {
    let err = load_err(&scene_with(&format!(
        "{BOX}repeat = {{ count = [3, 1, 1], spacing = [1e308, 0, 0] }}\n"
    )));
    assert_contains(
        &err,
        &[
            "scene.toml: objects[0].repeat.spacing: the farthest copy's position overflows",
            "(line 13)",
        ],
    );
}

#[test]
fn smooth_is_for_meshes_only() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"sphere\"\nmaterial = \"white\"\ncenter = [0, 0, 0]\nradius = 1.0\nsmooth = true\n",
    ));
    assert_contains(
        &err,
        &["scene.toml: objects[0] (sphere) does not take the field `smooth`", "(line 13)"],
    );
}

#[test]
fn mesh_file_of_unknown_format_is_rejected() {
    let err = load_err(&scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"models/teapot.stl\"\n"));
    assert_contains(
        &err,
        &[
            "scene.toml: objects[0].file is '",
            "models/teapot.stl', but must be an OBJ (.obj) or PLY (.ply) file (line 10)",
        ],
    );
}
