//! Files, TOML syntax, unknown keys and types, and NaN or infinite numbers anywhere.

use super::*;

#[test]
fn missing_scene_file_names_the_file() {
    let err = scene::load(Path::new("no/such/dir/absent_scene.toml")).unwrap_err().to_string();
    assert_contains(
        &err,
        &["scene file 'no/such/dir/absent_scene.toml'", "No such file or directory"],
    );
}

#[test]
fn toml_syntax_error_names_the_line() {
    let err = load_err("# comment\n\n[camera\nlookfrom = [0, 0, 0]\n");
    assert_contains(&err, &["scene.toml", "line 3, column 8"]);
}

#[test]
fn unknown_key_names_the_key_and_line() {
    let err = load_err(&format!("{CAMERA}fov = 3.0\n"));
    assert_contains(&err, &["scene.toml", "unknown field `fov`", "line 6"]);
}

#[test]
fn unknown_key_in_an_object_names_its_line() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"sphere\"\nmaterial = \"white\"\ncenter = [0, 0, 0]\nradius = 1.0\ncolour = 3\n",
    ));
    assert_contains(&err, &["scene.toml", "unknown field `colour`", "line 13"]);
}

#[test]
fn unknown_key_in_a_transform_entry_is_named() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"box\"\nmaterial = \"white\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n\
         transform = [{ rotate = { axis = [0, 1, 0], degrees = 10, turns = 2 } }]\n",
    ));
    assert_contains(&err, &["scene.toml", "unknown field `turns`", "line 13, column 59"]);
}

#[test]
fn unknown_object_type_is_named() {
    let err = load_err(&scene_with("[[objects]]\ntype = \"cone\"\nmaterial = \"white\"\n"));
    assert_contains(&err, &["scene.toml", "unknown variant `cone`", "line 9"]);
}

#[test]
fn wrong_array_length_names_the_line() {
    let err = load_err("[camera]\nlookfrom = [1.0, 2.0]\n");
    assert_contains(&err, &["scene.toml", "line 2", "expected an array of length 3"]);
}

#[test]
fn missing_required_field_is_named() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"quad\"\nmaterial = \"white\"\ncorner = [0, 0, 0]\nu = [1, 0, 0]\n",
    ));
    assert_contains(&err, &["scene.toml: objects[0] (quad) is missing the field `v`", "(line 8)"]);
}

#[test]
fn field_of_another_type_is_rejected() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"quad\"\nmaterial = \"white\"\ncorner = [0, 0, 0]\nu = [1, 0, 0]\nv = [0, 1, 0]\nradius = 2.0\n",
    ));
    assert_contains(
        &err,
        &["scene.toml: objects[0] (quad) does not take the field `radius`", "(line 14)"],
    );
}

#[test]
fn nan_in_camera_names_the_field_and_line() {
    let err =
        load_err(&CAMERA.replace("lookfrom = [0.0, 0.0, -5.0]", "lookfrom = [0.0, nan, -5.0]"));
    assert_contains(&err, &["scene.toml: camera.lookfrom[1] is NaN", "(line 2)"]);
}

#[test]
fn inf_radius_names_the_object() {
    let sphere = "[[objects]]\ntype = \"sphere\"\nmaterial = \"white\"\ncenter = [0, 0, 0]\n";
    let err = load_err(&scene_with(&format!(
        "{sphere}radius = 1.0\n{sphere}radius = 1.0\n{sphere}radius = inf\n"
    )));
    assert_contains(&err, &["scene.toml: objects[2].radius is inf", "(line 22)"]);
}

#[test]
fn nan_in_material_is_named() {
    let err = load_err(&format!("{CAMERA}[materials.white]\nalbedo = [0.5, 0.5, -nan]\n"));
    assert_contains(&err, &["scene.toml: materials.white.albedo[2] is NaN", "(line 7)"]);
}

#[test]
fn infinite_transform_entry_is_named() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"box\"\nmaterial = \"white\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n\
         transform = [{ scale = 2.0 }, { rotate = { axis = [0, 1, 0], degrees = -inf } }]\n",
    ));
    assert_contains(
        &err,
        &["scene.toml: objects[0].transform[1].rotate.degrees is -inf", "(line 13)"],
    );
}

#[test]
fn nan_in_render_background_is_named() {
    let err = load_err(&format!("{CAMERA}[render]\nbackground = [nan, 0, 0]\n"));
    assert_contains(&err, &["scene.toml: render.background[0] is NaN"]);
}

#[test]
fn non_finite_obj_vertex_names_the_obj_and_vertex() {
    let err = load_err(&scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"nan_vertex.obj\"\n"));
    assert_contains(
        &err,
        &[
            "nan_vertex.obj: vertex 2 has a non-finite coordinate 'nan'",
            "(line 3)",
            "objects[0]",
            "scene.toml",
        ],
    );
}
