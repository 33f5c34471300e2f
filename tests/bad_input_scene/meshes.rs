//! Mesh files (OBJ, PLY) and shapes with no area.

use super::*;
use crate::common::command::temp_dir;

#[test]
fn missing_obj_file_names_the_obj_and_the_scene() {
    let err = load_err(&scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"models/absent.obj\"\n"));
    assert_contains(
        &err,
        &[
            "OBJ file '",
            "models/absent.obj'",
            "No such file or directory",
            "named by objects[0].file in '",
            "scene.toml' (line 10)",
        ],
    );
}

#[test]
fn obj_with_out_of_range_index_names_the_obj() {
    let err = load_err(&scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"bad_index.obj\"\n"));
    assert_contains(
        &err,
        &["bad_index.obj: a face refers to vertex 9, but the file has 3 vertices", "(line 5)"],
    );
}

#[test]
fn obj_without_triangles_is_rejected() {
    let err = load_err(&scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"no_triangles.obj\"\n"));
    assert_contains(&err, &["no_triangles.obj: the OBJ file has no triangles", "objects[0]"]);
}

#[test]
fn mtl_colour_with_two_numbers_is_an_error_not_a_panic() {
    let err = load_err(&scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"short_kd.obj\"\n"));
    assert_contains(&err, &["short_kd.mtl: Kd needs 3 numbers", "(line 2)"]);
}

/// Found by fuzzing the MTL reader: a statement tobj cannot parse was "invalid MTL file:
/// material parse error" naming the OBJ, with no line.
#[test]
fn mtl_statements_tobj_cannot_parse_name_the_mtl_and_the_line() {
    let dir = temp_dir("mtl-statements");
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
    std::fs::write(dir.join("m.obj"), obj).unwrap();
    let cases = [
        ("Ns shiny", "Ns needs a number"),
        ("d", "d needs a number"),
        ("illum 300", "illum needs a whole number from 0 to 255"),
        ("map_Kd", "map_Kd needs a file name"),
    ];
    for (statement, expected) in cases {
        std::fs::write(dir.join("m.mtl"), format!("newmtl red\nKd 1 1 1\n{statement}\n")).unwrap();
        let scene = scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"m.obj\"\n");
        let err = embray::scene::load_str(&scene, &dir.join("s.toml")).unwrap_err().to_string();
        assert_contains(&err, &[&format!("m.mtl: {expected}"), "(line 3)"]);
    }
}

fn ply_object(file: &str) -> String {
    scene_with(&format!("[[objects]]\ntype = \"mesh\"\nmaterial = \"white\"\nfile = \"{file}\"\n"))
}

#[test]
fn missing_ply_file_names_the_ply_and_the_scene() {
    let err = load_err(&ply_object("models/absent.ply"));
    assert_contains(
        &err,
        &[
            "PLY file '",
            "models/absent.ply': No such file or directory",
            "named by objects[0].file in '",
            "scene.toml' (line 11)",
        ],
    );
}

#[test]
fn ply_with_out_of_range_index_names_the_face_and_line() {
    let err = load_err(&ply_object("bad_index.ply"));
    assert_contains(
        &err,
        &[
            "bad_index.ply' (line 14): face 1 refers to vertex 3, but the file has 3 vertices",
            "named by objects[0].file",
        ],
    );
}

#[test]
fn ply_with_non_finite_vertex_names_the_vertex() {
    let err = load_err(&ply_object("nan_vertex.ply"));
    assert_contains(&err, &["nan_vertex.ply' (line 11): vertex 1 has a non-finite coordinate"]);
}

#[test]
fn ply_with_unsupported_property_type_names_it() {
    let err = load_err(&ply_object("bad_type.ply"));
    assert_contains(&err, &["bad_type.ply' (line 6): unsupported property type 'float16'"]);
}

#[test]
fn ply_without_faces_is_rejected() {
    let err = load_err(&ply_object("no_faces.ply"));
    assert_contains(&err, &["no_faces.ply': the PLY file has no faces (no face element)"]);
}

#[test]
fn truncated_binary_ply_is_reported() {
    let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n\
        property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n\
        end_header\n"
        .to_vec();
    for v in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for c in v {
            bytes.extend(c.to_le_bytes());
        }
    }
    bytes.push(3);
    bytes.extend(0i32.to_le_bytes());
    bytes.extend(1i32.to_le_bytes()); // the third index is missing
    let dir = temp_dir("truncated-ply");
    std::fs::write(dir.join("cut.ply"), &bytes).unwrap();
    let result = scene::load_str(
        &scene_with("[[objects]]\ntype = \"mesh\"\nmaterial = \"white\"\nfile = \"cut.ply\"\n"),
        &dir.join("scene.toml"),
    );
    let err = result.unwrap_err().to_string();
    assert_contains(
        &err,
        &["cut.ply': the data ends in face 0 of 1 (truncated file?)", "objects[0].file"],
    );
}

#[test]
fn quad_with_parallel_edges_has_no_area() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"quad\"\nmaterial = \"white\"\ncorner = [0, 0, 0]\nu = [1, 1, 0]\nv = [2, 2, 0]\n",
    ));
    assert_contains(
        &err,
        &[
            "scene.toml: objects[0] (quad): u [1, 1, 0] and v [2, 2, 0] are zero or parallel",
            "(line 8)",
        ],
    );
}

#[test]
fn quad_light_with_zero_edge_has_no_area() {
    let err = load_err(&format!(
        "{CAMERA}[[lights]]\ntype = \"quad\"\ncorner = [0, 1, 0]\nu = [0, 0, 0]\nv = [0, 0, 1]\nemission = [1, 1, 1]\n"
    ));
    assert_contains(
        &err,
        &["lights[0] (quad light): u [0, 0, 0] and v [0, 0, 1] are zero or parallel"],
    );
}

#[test]
fn box_with_min_not_below_max_is_rejected() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"box\"\nmaterial = \"white\"\nmin = [0, 2, 0]\nmax = [1, 1, 1]\n",
    ));
    assert_contains(
        &err,
        &[
            "scene.toml: objects[0] (box): min [0, 2, 0] must be less than max [1, 1, 1] on every axis, but not on y",
        ],
    );
}
