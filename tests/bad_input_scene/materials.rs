//! Material references and the fields of each material type.

use super::*;
use crate::common::command::temp_dir;

#[test]
fn unknown_material_lists_the_defined_ones() {
    let text = format!(
        "{CAMERA}{WHITE}[materials.light]\nemission = [4, 4, 4]\n\
         [[objects]]\ntype = \"sphere\"\nmaterial = \"white\"\ncenter = [0, 0, 0]\nradius = 1.0\n\
         [[objects]]\ntype = \"sphere\"\nmaterial = \"red\"\ncenter = [0, 0, 0]\nradius = 1.0\n"
    );
    let err = load_err(&text);
    assert_contains(
        &err,
        &[
            "scene.toml: objects[1].material 'red' is not defined; defined: light, white",
            "(line 17)",
        ],
    );
}

#[test]
fn object_without_material_is_rejected() {
    let err =
        load_err(&scene_with("[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1.0\n"));
    assert_contains(&err, &["objects[0] (sphere) is missing the field `material`"]);
}

#[test]
fn unknown_material_type_is_named() {
    let err = load_err(&format!("{CAMERA}[materials.m]\ntype = \"velvet\"\n"));
    assert_contains(&err, &["scene.toml", "line 7", "unknown variant `velvet`"]);
}

#[test]
fn field_of_another_material_type_is_rejected() {
    let err = load_err(&format!("{CAMERA}{WHITE}roughness = 0.1\n"));
    assert_contains(
        &err,
        &["scene.toml: materials.white (diffuse) does not take the field `roughness` \
             (it takes: type, albedo, emission, two_sided_emission, emission_texture, texture, specular_texture, normal_map, bump_map, phong, brdf, opacity, one_sided, bump_shadowing) (line 8)"],
    );
    let err =
        load_err(&format!("{CAMERA}[materials.glass]\ntype = \"dielectric\"\neta = [1, 1, 1]\n"));
    assert_contains(
        &err,
        &[
            "materials.glass (dielectric) does not take the field `eta`",
            "ior, absorption",
            "(line 8)",
        ],
    );
    let err = load_err(&format!("{CAMERA}[materials.chrome]\ntype = \"mirror\"\nior = 1.5\n"));
    assert_contains(&err, &["materials.chrome (mirror) does not take the field `ior`"]);
    let err = load_err(&format!(
        "{CAMERA}[materials.gold]\ntype = \"conductor\"\npreset = \"gold\"\nabsorption = [1, 1, 1]\n"
    ));
    assert_contains(&err, &["materials.gold (conductor) does not take the field `absorption`"]);
}

#[test]
fn mirror_reflectance_and_roughness_are_checked() {
    let mirror = format!("{CAMERA}[materials.chrome]\ntype = \"mirror\"\n");
    let err = load_err(&format!("{mirror}reflectance = [1.0, 1.2, 1.0]\n"));
    assert_contains(
        &err,
        &["scene.toml: materials.chrome.reflectance[1] is 1.2, but must be in [0, 1] (line 8)"],
    );
    let err = load_err(&format!("{mirror}roughness = -0.1\n"));
    assert_contains(&err, &["materials.chrome.roughness is -0.1, but must be >= 0 (line 8)"]);
}

#[test]
fn conductor_needs_eta_and_k_or_a_preset() {
    let metal = format!("{CAMERA}[materials.metal]\ntype = \"conductor\"\n");
    let err = load_err(&metal);
    assert_contains(
        &err,
        &["scene.toml: materials.metal (conductor) is missing the field `eta` (line 6)"],
    );
    let err = load_err(&format!("{metal}eta = [0.2, 0.9, 1.1]\n"));
    assert_contains(&err, &["materials.metal (conductor) is missing the field `k`"]);
    let err = load_err(&format!("{metal}preset = \"copper\"\neta = [0.2, 0.9, 1.1]\n"));
    assert_contains(
        &err,
        &["scene.toml: materials.metal (conductor) takes `preset` or `eta`, not both (line 9)"],
    );
    let err = load_err(&format!("{metal}preset = \"platinum\"\n"));
    assert_contains(&err, &["scene.toml", "line 8", "unknown variant `platinum`", "`gold`"]);
}

#[test]
fn conductor_eta_must_be_positive_and_k_non_negative() {
    let metal = format!("{CAMERA}[materials.metal]\ntype = \"conductor\"\n");
    let err = load_err(&format!("{metal}eta = [0.2, 0.0, 1.1]\nk = [3, 2, 2]\n"));
    assert_contains(&err, &["materials.metal.eta[1] is 0, but must be > 0 (line 8)"]);
    let err = load_err(&format!("{metal}eta = [0.2, 0.9, 1.1]\nk = [3, 2, -1]\n"));
    assert_contains(&err, &["materials.metal.k[2] is -1, but must be >= 0 (line 9)"]);
}

#[test]
fn dielectric_ior_and_absorption_are_checked() {
    let glass = format!("{CAMERA}[materials.glass]\ntype = \"dielectric\"\n");
    let err = load_err(&format!("{glass}ior = 0.0\n"));
    assert_contains(&err, &["scene.toml: materials.glass.ior is 0, but must be > 0 (line 8)"]);
    let err = load_err(&format!("{glass}absorption = [-1, 0, 0]\n"));
    assert_contains(&err, &["materials.glass.absorption[0] is -1, but must be >= 0 (line 8)"]);
}

#[test]
fn texture_fields_are_checked() {
    let floor = format!("{CAMERA}[materials.floor]\n");
    let err = load_err(&format!(
        "{floor}texture = {{ type = \"checker2d\", scale = 0.0, even = [1, 1, 1], odd = [0, 0, 0] }}\n"
    ));
    assert_contains(
        &err,
        &["scene.toml: materials.floor.texture.scale is 0, but must be > 0 (line 7)"],
    );
    let err = load_err(&format!(
        "{floor}texture = {{ type = \"checker3d\", scale = 2.0, even = [1.5, 1, 1], odd = [0, 0, 0] }}\n"
    ));
    assert_contains(&err, &["materials.floor.texture.even[0] is 1.5, but must be in [0, 1]"]);
    let err = load_err(&format!(
        "{floor}texture = {{ type = \"marble\", scale = 2.0, even = [1, 1, 1], odd = [0, 0, 0] }}\n"
    ));
    assert_contains(&err, &["scene.toml", "line 7", "unknown variant `marble`"]);
    let err = load_err(&format!(
        "{floor}texture = {{ type = \"checker2d\", scale = 2.0, even = [1, 1, 1] }}\n"
    ));
    assert_contains(
        &err,
        &["scene.toml: materials.floor.texture (checker2d) is missing the field `odd` (line 7)"],
    );
    let err = load_err(&format!(
        "{floor}texture = {{ type = \"checker2d\", scale = 2.0, even = [1, 1, 1], odd = [0, 0, 0], rotation = 3 }}\n"
    ));
    assert_contains(&err, &["scene.toml", "line 7", "unknown field `rotation`"]);
    // Each texture type takes its own fields only, and a specular texture has no mode.
    let err = load_err(&format!(
        "{floor}texture = {{ type = \"perlin\", scale = 2.0, even = [1, 1, 1] }}\n"
    ));
    assert_contains(
        &err,
        &["materials.floor.texture (perlin) does not take the field `even` \
           (it takes: type, mode, scale, conversion) (line 7)"],
    );
    let err = load_err(&format!(
        "{floor}specular_texture = {{ type = \"checker\", mode = \"blend\" }}\n"
    ));
    assert_contains(
        &err,
        &["materials.floor.specular_texture (checker) does not take the field `mode`"],
    );
    let err = load_err(&format!("{floor}texture = {{ type = \"image\" }}\n"));
    assert_contains(
        &err,
        &["materials.floor.texture (image) is missing the field `file` (line 7)"],
    );
    let err = load_err(&format!(
        "{floor}texture = {{ type = \"image\", file = \"x.png\", normalizer = 30 }}\n"
    ));
    assert_contains(
        &err,
        &["materials.floor.texture.normalizer is given, but must be given only with \
           encoding = \"raw\" (line 7)"],
    );
}

#[test]
fn texture_images_that_cannot_be_read_name_the_file_and_the_field() {
    let dir = temp_dir("bad-texture");
    std::fs::write(dir.join("notes.png"), "not an image").unwrap();
    std::fs::write(dir.join("cut.png"), &b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR"[..]).unwrap();
    // A JPEG cut after part of its scan: the decoder alone would fill the rest with grey.
    let mut jpeg = Vec::new();
    let noise =
        image::RgbImage::from_fn(64, 64, |x, y| image::Rgb([(x * 7) as u8, (y * 5) as u8, 9]));
    noise.write_to(&mut std::io::Cursor::new(&mut jpeg), image::ImageFormat::Jpeg).unwrap();
    std::fs::write(dir.join("whole.jpg"), &jpeg).unwrap();
    std::fs::write(dir.join("cut.jpg"), &jpeg[..jpeg.len() * 2 / 3]).unwrap();
    let whole = format!(
        "{CAMERA}[materials.floor]\ntexture = {{ type = \"image\", file = \"whole.jpg\" }}\n"
    );
    std::fs::write(dir.join("whole.toml"), whole).unwrap();
    embray::scene::load(&dir.join("whole.toml")).expect("the whole JPEG loads");
    for (file, problem) in [
        ("missing.png", "No such file"),
        ("notes.png", "not a PNG, JPEG or BMP image"),
        ("cut.png", "unexpected end of file"),
        ("cut.jpg", "cut short"),
    ] {
        let text = format!(
            "{CAMERA}[materials.floor]\ntexture = {{ type = \"image\", file = \"{file}\" }}\n"
        );
        let scene = dir.join("scene.toml");
        std::fs::write(&scene, text).unwrap();
        let err = embray::scene::load(&scene).unwrap_err().to_string();
        assert_contains(
            &err,
            &[
                &format!("image file '{}'", dir.join(file).display()),
                problem,
                "named by materials.floor.texture.file",
                "(line 7)",
            ],
        );
    }
}

#[test]
fn phong_exponent_must_be_positive() {
    let err = load_err(&format!(
        "{CAMERA}[materials.m]\nphong = {{ specular = [1, 1, 1], exponent = 0 }}\n"
    ));
    assert_contains(
        &err,
        &["scene.toml: materials.m.phong.exponent is 0, but must be > 0 (line 7)"],
    );
    let err = load_err(&format!("{CAMERA}[materials.m]\nphong = {{ ambient = [-0.1, 0, 0] }}\n"));
    assert_contains(&err, &["materials.m.phong.ambient[0] is -0.1, but must be >= 0"]);
}
