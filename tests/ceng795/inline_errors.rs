//! Broken XML: every error names the file, the element and the line; the CLI writes nothing.

use super::*;

#[test]
fn malformed_xml_names_the_line() {
    let text = scene_xml(TRIANGLE).replace("</Faces>", "</Face>");
    assert_contains(&error_of(&text), &["inline.xml", "malformed XML", "(line 35)"]);
}

#[test]
fn missing_ply_names_the_file_the_mesh_and_the_line() {
    let body = TRIANGLE.replace(
        "<Faces>\n                1 2 3\n            </Faces>",
        r#"<Faces plyFile="nothere.ply" />"#,
    );
    let path = temp_scene("missing-ply", &scene_xml(&body));
    let message = ceng795::load_with_warnings(&path).unwrap_err().to_string();
    assert_contains(&message, &["nothere.ply", "<Objects > Mesh id=\"1\">", "(line 33)"]);
}

#[test]
fn out_of_range_vertex_index_names_the_index_and_its_line() {
    let text = scene_xml(&TRIANGLE.replace("1 2 3", "1 2\n                9"));
    assert_contains(
        &error_of(&text),
        &[
            "<Objects > Mesh id=\"1\" > Faces>",
            "vertex index 9 is out of range: the scene has 3 vertices",
            "(line 35)",
        ],
    );
}

#[test]
fn unknown_material_names_the_id_the_element_and_the_line() {
    let text = scene_xml(&TRIANGLE.replace("<Material>1</Material>", "<Material>7</Material>"));
    assert_contains(
        &error_of(&text),
        &["<Objects > Mesh id=\"1\" > Material>", "'7' is not defined; defined: 1", "(line 32)"],
    );
}

#[test]
fn other_errors_name_the_element() {
    let cases: &[(&str, &str, &[&str])] = &[
        ("<Gaze>0 0 -1</Gaze>", "<Gaze>0 0</Gaze>", &["Camera id=\"1\" > Gaze", "expected 3"]),
        ("<Gaze>0 0 -1</Gaze>", "<Gaze>0 x -1</Gaze>", &["'x' is not a finite number"]),
        ("<Gaze>0 0 -1</Gaze>", "<Gazer>0 0 -1</Gazer>", &["unsupported element <Gazer>"]),
        (
            "<Material id=\"1\">",
            "<Material id=\"1\" type=\"glossy\">",
            &["material type \"glossy\""],
        ),
        ("<Mesh id=\"1\">", "<Mesh id=\"1\" shadingMode=\"phong\">", &["shadingMode \"phong\""]),
    ];
    for (from, to, needles) in cases {
        let text = scene_xml(TRIANGLE).replace(from, to);
        assert_contains(&error_of(&text), needles);
    }
    let bad_transform = TRIANGLE.replace(
        "<Material>1</Material>",
        "<Material>1</Material><Transformations>s1 t4</Transformations>",
    );
    let text = scene_xml(&format!(
        "<Transformations><Scaling id=\"1\">2 2 2</Scaling></Transformations>{bad_transform}"
    ));
    assert_contains(&error_of(&text), &["transformation 't4' is not defined; defined: s1"]);
}

#[test]
fn cli_rejects_a_broken_scene_without_writing_anything() {
    let text = scene_xml(&TRIANGLE.replace("<Material>1</Material>", "<Material>7</Material>"));
    let path = temp_scene("cli-bad", &text);
    let dir = path.parent().unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_embray"))
        .args(["render", "scene.xml", "--out-dir", "images", "--quiet"])
        .current_dir(dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "should fail: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_contains(&stderr, &["scene.xml", "Mesh id=\"1\" > Material", "'7'", "(line 32)"]);
    assert!(!dir.join("images").exists(), "output written despite the error");
    let files: Vec<_> = std::fs::read_dir(dir).unwrap().flatten().map(|e| e.file_name()).collect();
    assert_eq!(files, ["scene.xml"], "{files:?}");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn cli_renders_every_camera_to_its_image_name() {
    let second = CAMERA
        .replace("<Camera id=\"1\">", "<Camera id=\"2\">")
        .replace("tiny.png", "second.png")
        .replace("<Cameras>", "")
        .replace("</Cameras>", "");
    let text = scene_xml(TRIANGLE).replace("    </Cameras>", &format!("{second}\n    </Cameras>"));
    let path = temp_scene("cli-two", &text);
    let dir = path.parent().unwrap();
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_embray"))
            .args(args)
            .current_dir(dir)
            .output()
            .unwrap()
    };
    let out = run(&["render", "scene.xml", "--out-dir", "images", "--quiet"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for file in ["tiny.png", "tiny.exr", "second.png", "second.exr"] {
        assert!(dir.join("images").join(file).exists(), "{file} missing");
    }
    // The 25/255 ambient light on a white surface, written without a tone curve.
    let png = image::open(dir.join("images/tiny.png")).unwrap().to_rgb8();
    assert_eq!(png.get_pixel(4, 3).0, [25, 25, 25]);
    assert_eq!(png.get_pixel(0, 0).0, [0, 0, 0]);
    // -o names one file: an error for two cameras.
    let out = run(&["render", "scene.xml", "-o", "one.exr", "--quiet"]);
    assert!(!out.status.success() && !dir.join("one.exr").exists());
    assert_contains(&String::from_utf8_lossy(&out.stderr), &["2 cameras", "--out-dir"]);
    // convert writes one TOML per camera, sharing the meshes.
    let out = run(&["convert", "scene.xml", "-o", "conv.toml"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for file in ["conv_tiny.toml", "conv_second.toml", "conv_meshes/mesh_0.obj"] {
        assert!(dir.join(file).exists(), "{file} missing");
    }
    let out = run(&["compare", "images/tiny.png", "images/second.png", "--heatmap", "heat.png"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && dir.join("heat.png").exists(), "{stdout}");
    assert_contains(&stdout, &["mean abs error 0.0000/255", "0.0000 % of pixels"]);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn hw6_elements_report_their_errors() {
    let brdfs = r#"<BRDFs><ModifiedPhong id="1" normalized="true"><Exponent>20</Exponent></ModifiedPhong></BRDFs>
    <Materials>"#;
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "<Material id=\"1\">",
            "<Material id=\"1\" BRDF=\"4\">",
            &["BRDF=\"4\"", "defined: (none)"],
        ),
        (
            "<Camera id=\"1\">",
            "<Camera id=\"1\" handedness=\"left\">",
            &["handedness=\"left\"", "supported: right"],
        ),
        ("<Mesh id=\"1\">", "<LightMesh id=\"1\">", &["LightMesh", "Radiance"]),
    ];
    for (from, to, needles) in cases {
        let text = scene_xml(TRIANGLE)
            .replacen(from, to, 1)
            .replace("</Mesh>", if to.contains("LightMesh") { "</LightMesh>" } else { "</Mesh>" });
        assert_contains(&error_of(&text), needles);
    }
    // A BRDF element with a bad flag or exponent, and a material naming an undefined one.
    for (brdf, needles) in [
        (
            r#"<ModifiedPhong id="1" normalized="yes"><Exponent>20</Exponent></ModifiedPhong>"#,
            &["normalized=\"yes\"", "\"true\" or \"false\""][..],
        ),
        (
            r#"<ModifiedPhong id="1"><Exponent>0</Exponent></ModifiedPhong>"#,
            &["Exponent", "> 0"][..],
        ),
        (
            r#"<BlinnPhong id="1"><Exponent>2</Exponent></BlinnPhong>"#,
            &["unsupported element <BlinnPhong>", "TorranceSparrow"][..],
        ),
        (
            r#"<TorranceSparrow id="1"><Exponent>2</Exponent></TorranceSparrow>"#,
            &["RefractionIndex"][..],
        ),
    ] {
        let text = scene_xml(TRIANGLE)
            .replace("<Materials>", &brdfs.replace(r#"<ModifiedPhong id="1" normalized="true"><Exponent>20</Exponent></ModifiedPhong>"#, brdf))
            .replace("<Material id=\"1\">", "<Material id=\"1\" BRDF=\"1\">");
        assert_contains(&error_of(&text), needles);
    }
}
