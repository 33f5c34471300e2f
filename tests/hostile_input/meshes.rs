//! OBJ and PLY files that tobj or a naive reader would misreport: every problem with the
//! mesh file, its line and the scene item that names it.

use crate::harness::{Scratch, accepted_in, refused_cases, scene, with_mesh};

const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

fn ply(vertices: usize, faces: usize, body: &str) -> String {
    format!(
        "ply\nformat ascii 1.0\nelement vertex {vertices}\nproperty float x\nproperty float y\n\
         property float z\nelement face {faces}\nproperty list uchar int vertex_indices\n\
         end_header\n{body}"
    )
}

const PLY_BODY: &str = "0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n";

refused_cases! {
    obj_vertex_with_two_numbers: ["s.toml" => with_mesh("m.obj"), "m.obj" => "v 0 0\n"], ["render", "s.toml"]
        => ["m.obj", "vertex 1", "this one has 2", "(line 1)", "objects[1]"];
    obj_vertex_not_a_number: ["s.toml" => with_mesh("m.obj"), "m.obj" => format!("{TRIANGLE}v 0 abc 0\n")], ["render", "s.toml"]
        => ["m.obj", "'abc' is not a number", "(line 4)"];
    obj_face_index_overflowing: ["s.toml" => with_mesh("m.obj"), "m.obj" => format!("{TRIANGLE}f 1 2 99999999999999999999\n")], ["render", "s.toml"]
        => ["m.obj", "not a whole number", "(line 4)"];
    obj_face_index_out_of_range: ["s.toml" => with_mesh("m.obj"), "m.obj" => format!("{TRIANGLE}f 1 2 9\n")], ["render", "s.toml"]
        => ["m.obj", "vertex 9", "3 vertices", "(line 4)"];
    obj_vertex_with_junk_after_w: ["s.toml" => with_mesh("m.obj"), "m.obj" => "v 0 0 0 1 junk\n"], ["render", "s.toml"]
        => ["m.obj", "'junk' is not a number", "(line 1)"];
    obj_number_of_two_megabytes: ["s.toml" => with_mesh("m.obj"), "m.obj" => format!("v 0 {} 0\n", "7".repeat(2_000_000))], ["render", "s.toml"]
        => ["m.obj", "characters)", "(line 1)"];
    obj_non_finite: ["s.toml" => with_mesh("m.obj"), "m.obj" => "v 0 inf 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"], ["render", "s.toml"]
        => ["m.obj", "non-finite", "(line 1)"];
    obj_without_triangles: ["s.toml" => with_mesh("m.obj"), "m.obj" => TRIANGLE], ["render", "s.toml"]
        => ["m.obj", "no triangles"];
    obj_missing: ["s.toml" => with_mesh("m.obj")], ["render", "s.toml"]
        => ["m.obj", "No such file", "objects[1].file"];
    mtl_short_colour: ["s.toml" => with_mesh("m.obj"), "m.obj" => format!("mtllib m.mtl\n{TRIANGLE}usemtl a\nf 1 2 3\n"), "m.mtl" => "newmtl a\nKd 0.5\n"], ["render", "s.toml"]
        => ["m.mtl", "Kd needs 3 numbers", "(line 2)"];
    ply_header_counts_more_vertices: ["s.toml" => with_mesh("m.ply"), "m.ply" => ply(5, 2, PLY_BODY)], ["render", "s.toml"]
        => ["m.ply", "more values than", "line 14"];
    ply_values_shift_between_lines: ["s.toml" => with_mesh("m.ply"), "m.ply" => ply(4, 2, &PLY_BODY.replacen("1 0 0\n", "1 0\n0\n", 1))], ["render", "s.toml"]
        => ["m.ply", "line ends before", "line 11"];
    ply_header_counts_fewer_faces: ["s.toml" => with_mesh("m.ply"), "m.ply" => ply(4, 1, PLY_BODY)], ["render", "s.toml"]
        => ["m.ply", "goes on after the last element", "line 15"];
    ply_truncated: ["s.toml" => with_mesh("m.ply"), "m.ply" => ply(4, 3, PLY_BODY)], ["render", "s.toml"]
        => ["m.ply", "ends in face 2 of 3", "named by objects[1].file in 's.toml' (line 26)"];
    ply_huge_token: ["s.toml" => with_mesh("m.ply"), "m.ply" => ply(4, 2, &PLY_BODY.replacen("0 0 0", &format!("0 {} 0", "x".repeat(1_000_000)), 1))], ["render", "s.toml"]
        => ["m.ply", "characters)", "line 10"];
    ply_not_a_ply: ["s.toml" => with_mesh("m.ply"), "m.ply" => "solid stl\n"], ["render", "s.toml"]
        => ["m.ply", "not a PLY file"];
}

/// The scene renders `obj` as m.obj, warning with `says`.
fn assert_obj_warns(obj: &str, says: &[&str]) {
    let scratch = Scratch::new();
    scratch.write("s.toml", with_mesh("m.obj"));
    scratch.write("m.obj", obj);
    let run = accepted_in(&scratch, &["render", "s.toml", "-q"]);
    run.assert_says(&[&["warning", "m.obj"], says].concat());
}

#[test]
fn a_two_vertex_face_is_warned_about() {
    let obj = format!("{TRIANGLE}f 1 2 3\nf 1 2\n");
    assert_obj_warns(&obj, &["a face with 2 vertices is ignored", "(line 5)"]);
}

#[test]
fn an_undefined_usemtl_is_warned_about() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene("[[objects]]\ntype = \"mesh\"\nfile = \"m.obj\"\n"));
    scratch.write("m.obj", format!("mtllib m.mtl\n{TRIANGLE}usemtl nothing\nf 1 2 3\n"));
    scratch.write("m.mtl", "newmtl red\nKd 1 0 0\n");
    let run = accepted_in(&scratch, &["render", "s.toml", "-q"]);
    run.assert_says(&["warning", "m.obj", "usemtl 'nothing' names no material", "(line 5)"]);
}

/// Where one face lacks normals (or texture coordinates), the others' are not used either,
/// which is said.
#[test]
fn normals_on_some_faces_only_are_warned_about() {
    let obj = format!("{TRIANGLE}v 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 2 4 3\n");
    assert_obj_warns(&obj, &["some faces give normals and some do not"]);
}

/// A UTF-8 byte order mark made tobj drop the first statement (here a vertex, so the face
/// named one that was not there).
#[test]
fn a_byte_order_mark_before_an_obj_or_mtl_is_skipped() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene("[[objects]]\ntype = \"mesh\"\nfile = \"m.obj\"\n"));
    scratch.write("m.obj", format!("\u{feff}mtllib m.mtl\n{TRIANGLE}usemtl red\nf 1 2 3\n"));
    scratch.write("m.mtl", "\u{feff}newmtl red\nKd 1 0 0\n");
    let run = accepted_in(&scratch, &["info", "s.toml"]);
    // The quad's 2 triangles and the OBJ's one.
    assert!(run.stdout.contains("2 meshes (3 triangles)"), "{}", run.stdout);
    assert!(!run.stderr.contains("warning"), "{}", run.stderr);
}

#[test]
fn unknown_obj_statements_are_warned_about_once() {
    let obj = "v 0 0 0\nvv 1 0 0\nv 1 0 0\nv 0 1 0\nvv 0 1 0\nf 1 2 3\n";
    assert_obj_warns(
        obj,
        &["2 statement(s) of no OBJ kind are ignored, the first 'vv'", "(line 2)"],
    );
}
