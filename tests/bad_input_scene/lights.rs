//! Light types and their fields.

use super::*;
use embray::scene::Environment;

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
    assert_contains(
        &err,
        &[
            "lights[0].radius is 0, but must be > 0 and at least 1.0842021724855044e-19",
            "(line 10)",
        ],
    );
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

#[test]
fn environment_light_takes_a_file_or_a_radiance() {
    let light = format!("{CAMERA}[[lights]]\ntype = \"environment\"\n");
    let err = load_err(&light);
    assert_contains(
        &err,
        &["lights[0] (environment light) is missing the field `file (or radiance)`"],
    );
    let err = load_err(&format!("{light}file = \"sky.exr\"\nradiance = [1, 1, 1]\n"));
    assert_contains(&err, &["lights[0]", "file", "radiance"]);
    let err = load_err(&format!("{light}radiance = [1, -1, 1]\n"));
    assert_contains(&err, &["lights[0].radiance[1] is -1, but must be >= 0 (line 8)"]);
    let err = load_err(&format!("{light}radiance = [1, 1, 1]\nencoding = \"raw\"\n"));
    assert_contains(&err, &["lights[0].encoding", "given only with file"]);
    let err = load_err(&format!("{light}radiance = [1, 1, 1]\nposition = [0, 0, 0]\n"));
    assert_contains(
        &err,
        &[
            "does not take the field `position` (it takes: type, file, radiance, scale, encoding, mapping, to_world, interpolation)",
        ],
    );
    let err = load_err(&format!("{light}radiance = [1, 1, 1]\nscale = [1, 1, -2]\n"));
    assert_contains(&err, &["lights[0].scale[2] is -2"]);
    let two = format!(
        "{light}radiance = [1, 1, 1]\n\n[[lights]]\ntype = \"environment\"\nradiance = [1, 1, 1]\n"
    );
    assert_contains(&load_err(&two), &["lights[1].type", "at most one environment light"]);
    let scene = load(&format!("{light}radiance = [1, 2, 3]\nscale = [2, 2, 2]\n"));
    assert!(matches!(
        &scene.lights[0],
        LightDesc::Environment(Environment { map: embray::scene::EnvironmentMap::Constant(c), scale, .. })
            if *c == Vec3::new(1.0, 2.0, 3.0) && *scale == Vec3::splat(2.0)
    ));
}

#[test]
fn environment_maps_are_checked_when_read() {
    let dir = common::command::temp_dir("bad-environment-maps");
    let light = format!("{CAMERA}[[lights]]\ntype = \"environment\"\n");
    let missing = dir.join("missing.exr");
    let err = load_err(&format!("{light}file = \"{}\"\n", missing.display()));
    assert_contains(&err, &["missing.exr", "lights[0].file", "line 8"]);
    // A map with a NaN texel is refused, naming the texel.
    let mut film = embray::film::Film::new(3, 2);
    film.color.iter_mut().for_each(|c| *c = Vec3::ONE);
    film.color[4] = Vec3::new(1.0, f32::NAN, 1.0);
    let nan = dir.join("nan.exr");
    embray::output::write_exr(&film, &nan).unwrap();
    let err = load_err(&format!("{light}file = \"{}\"\n", nan.display()));
    assert_contains(&err, &["nan.exr", "texel (1, 1) is not finite", "lights[0].file"]);
    // EXR values are linear: an encoding makes no sense for them.
    film.color[4] = Vec3::ONE;
    let good = dir.join("good.exr");
    embray::output::write_exr(&film, &good).unwrap();
    let err = load_err(&format!("{light}file = \"{}\"\nencoding = \"srgb\"\n", good.display()));
    assert_contains(&err, &["lights[0].encoding", "only for PNG and JPEG"]);
    // Not an image at all.
    let text = dir.join("sky.png");
    std::fs::write(&text, "not an image").unwrap();
    let err = load_err(&format!("{light}file = \"{}\"\n", text.display()));
    assert_contains(&err, &["sky.png", "lights[0].file"]);
    let err = load_err(&format!("{light}radiance = [1, 1, 1]\nmapping = \"probe\"\n"));
    assert_contains(&err, &["lights[0].mapping", "given only with file"]);
    let err = load_err(&format!("{light}file = \"{}\"\nmapping = \"cube\"\n", good.display()));
    assert_contains(&err, &["mapping", "cube"]);
    let scene = load(&format!("{light}file = \"{}\"\nmapping = \"probe\"\n", good.display()));
    assert!(matches!(
        scene.lights[0],
        LightDesc::Environment(Environment {
            mapping: embray::scene::EnvironmentMapping::Probe,
            ..
        })
    ));
    let scene = load(&format!("{light}file = \"{}\"\n", good.display()));
    match &scene.lights[0] {
        LightDesc::Environment(Environment {
            map: embray::scene::EnvironmentMap::Image(image),
            ..
        }) => {
            assert_eq!((image.width, image.height, image.hdr), (3, 2, true));
        }
        other => panic!("an environment light, got {other:?}"),
    }
}

#[test]
fn a_light_field_of_the_wrong_type_names_the_field_and_line() {
    let light = format!("{CAMERA}[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\n");
    let err = load_err(&format!("{light}intensity = \"bright\"\n"));
    assert_contains(
        &err,
        &["scene.toml: lights[0].intensity is \"bright\", but must be 3 numbers (line 9)"],
    );
    let err = load_err(&format!("{light}intensity = [1, 1]\n"));
    assert_contains(&err, &["lights[0].intensity is [1, 1], but must be 3 numbers (line 9)"]);
}

#[test]
fn an_unknown_light_type_lists_the_kinds() {
    let err = load_err(&format!("{CAMERA}[[lights]]\ntype = \"laser\"\n"));
    assert_contains(
        &err,
        &[
            "lights[0].type is \"laser\", but must be one of point, spot, projector, directional, ambient, area, environment, quad, sphere, mesh (line 7)",
        ],
    );
    let err = load_err(&format!("{CAMERA}[[lights]]\nposition = [0, 1, 0]\n"));
    assert_contains(&err, &["lights[0] is missing the field `type`"]);
}
