//! Light types and their fields.

use super::*;

#[test]
fn directional_light_needs_a_direction() {
    let light = format!("{CAMERA}[[lights]]\ntype = \"directional\"\n");
    let err = load_err(&format!("{light}direction = [0, 0, 0]\nirradiance = [1, 1, 1]\n"));
    assert_contains(
        &err,
        &["scene.toml: lights[0].direction is [0, 0, 0], but must be a non-zero vector (line 8)"],
    );
    let err = load_err(&format!("{light}direction = [0, -1, 0]\nirradiance = [1, 1, -1]\n"));
    assert_contains(&err, &["lights[0].irradiance[2] is -1, but must be >= 0 (line 9)"]);
    let err = load_err(&format!("{light}irradiance = [1, 1, 1]\n"));
    assert_contains(&err, &["lights[0] (directional light) is missing the field `direction`"]);
}

#[test]
fn light_fields_of_another_type_are_rejected() {
    let err = load_err(&format!(
        "{CAMERA}[[lights]]\ntype = \"ambient\"\nradiance = [0.1, 0.1, 0.1]\nemission = [1, 1, 1]\n"
    ));
    assert_contains(
        &err,
        &[
            "scene.toml: lights[0] (ambient light) does not take the field `emission` (it takes: type, radiance) (line 9)",
        ],
    );
    let err = load_err(&format!(
        "{CAMERA}[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\nintensity = [1, 1, 1]\ntransform = []\n"
    ));
    assert_contains(&err, &["lights[0] (point light) does not take the field `transform`"]);
}

#[test]
fn sphere_light_needs_a_positive_radius() {
    let light = format!(
        "{CAMERA}[[lights]]\ntype = \"sphere\"\ncenter = [0, 3, 0]\nemission = [5, 5, 5]\n"
    );
    let err = load_err(&light);
    assert_contains(
        &err,
        &["scene.toml: lights[0] (sphere light) is missing the field `radius` (line 6)"],
    );
    let err = load_err(&format!("{light}radius = 0\n"));
    assert_contains(&err, &["lights[0].radius is 0, but must be > 0 (line 10)"]);
    let err = load_err(&format!("{light}radius = 0.5\ntransform = [{{ scale = 0 }}]\n"));
    assert_contains(&err, &["lights[0].transform[0]: scale [0, 0, 0] is singular"]);
}

#[test]
fn mesh_light_needs_a_file_and_emission() {
    let err = load_err(&format!("{CAMERA}[[lights]]\ntype = \"mesh\"\nemission = [1, 1, 1]\n"));
    assert_contains(&err, &["lights[0] (mesh light) is missing the field `file`"]);
    let err = load_err(&format!("{CAMERA}[[lights]]\ntype = \"mesh\"\nfile = \"cube.ply\"\n"));
    assert_contains(&err, &["lights[0] (mesh light) is missing the field `emission`"]);
    let err = load_err(&format!(
        "{CAMERA}[[lights]]\ntype = \"mesh\"\nfile = \"absent.ply\"\nemission = [1, 1, 1]\n"
    ));
    assert_contains(&err, &["PLY file '", "absent.ply'", "named by lights[0].file", "(line 8)"]);
}
