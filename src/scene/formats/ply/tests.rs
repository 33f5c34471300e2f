//! The PLY reader on good and malformed ASCII and binary files.

use super::*;

/// `super::parse` with no memory limit.
fn parse(bytes: &[u8]) -> Result<(MeshData, Option<PlyProblem>), PlyProblem> {
    super::parse(bytes, None)
}

const CUBE_HEADER: &str = "ply\nformat ascii 1.0\ncomment a cube\nelement vertex 8\n\
    property float x\nproperty float y\nproperty float z\nelement face 6\n\
    property list uchar int vertex_indices\nend_header\n";
const CUBE_BODY: &str = "0 0 0\n0 0 1\n0 1 1\n0 1 0\n1 0 0\n1 0 1\n1 1 1\n1 1 0\n\
    4 0 1 2 3\n4 7 6 5 4\n4 0 4 5 1\n4 1 5 6 2\n4 2 6 7 3\n4 3 7 4 0\n";

fn cube() -> String {
    format!("{CUBE_HEADER}{CUBE_BODY}")
}

#[test]
fn ascii_cube_is_fan_triangulated() {
    let (mesh, warning) = parse(cube().as_bytes()).unwrap();
    assert_eq!(warning, None);
    assert_eq!(mesh.positions.len(), 8);
    assert_eq!(mesh.positions[6], DVec3::ONE);
    assert_eq!(mesh.indices.len(), 12);
    assert_eq!(mesh.indices[0..2], [[0, 1, 2], [0, 2, 3]]);
    assert!(mesh.normals.is_none() && mesh.uvs.is_none());
}

/// Faces of fewer than 3 vertices are skipped, as OBJ's are, and a warning says how many
/// and where the first is.
#[test]
fn short_faces_are_skipped_with_a_warning() {
    let text = cube().replace("4 0 4 5 1\n", "2 0 4\n").replace("4 3 7 4 0\n", "0\n");
    let (mesh, warning) = parse(text.as_bytes()).unwrap();
    assert_eq!(mesh.indices.len(), 8);
    let message = "2 faces of fewer than 3 vertices are ignored (the first: face 2, with 2)";
    assert_eq!(warning, Some(problem(Some(21), message)));
    let one = cube().replace("4 3 7 4 0\n", "1 3\n");
    let message = "face 5 has 1 vertex and is ignored (a face needs at least 3)";
    assert_eq!(parse(one.as_bytes()).unwrap().1, Some(problem(Some(24), message)));
}

#[test]
fn crlf_header_and_extra_properties() {
    let text = "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty double x\r\n\
        property double y\r\nproperty double z\r\nproperty uchar red\r\nproperty float s\r\n\
        property float t\r\nelement edge 1\r\nproperty int a\r\nproperty int b\r\n\
        element face 1\r\nproperty uchar flags\r\nproperty list int uint vertex_index\r\n\
        end_header\r\n0 0 0 255 0 0\r\n1 0 0 0 1 0\r\n0 1 0 7 0 1\r\n0 1\r\n9 3 0 1 2\r\n";
    let (mesh, _) = parse(text.as_bytes()).unwrap();
    assert_eq!(mesh.indices, [[0, 1, 2]]);
    assert_eq!(mesh.uvs.unwrap()[2], Vec2::new(0.0, 1.0));
}

#[test]
fn errors_name_the_problem_and_line() {
    let err = parse(cube().replace("4 2 6 7 3", "4 2 6 8 3").as_bytes()).unwrap_err();
    assert_eq!(err.line, Some(23));
    assert_eq!(err.message, "face 4 refers to vertex 8, but the file has 8 vertices");

    let err = parse(cube().replace("0 1 1\n", "0 nan 1\n").as_bytes()).unwrap_err();
    assert_eq!(err.line, Some(13));
    assert!(err.message.starts_with("vertex 2 has a non-finite coordinate"), "{err:?}");

    let err = parse(cube().replace("float y", "half y").as_bytes()).unwrap_err();
    assert_eq!((err.line, err.message.as_str()), (Some(6), "unsupported property type 'half'"));

    let err = parse(cube().replace("4 3 7 4 0\n", "4 3 7\n").as_bytes()).unwrap_err();
    assert!(err.message.contains("line ends before"), "{err:?}");
    let err = parse(cube().replace("4 3 7 4 0\n", "").as_bytes()).unwrap_err();
    assert!(err.message.contains("ends in face 5 of 6"), "{err:?}");

    let err = parse(cube().replace("4 3 7 4 0", "4 3 7 x 0").as_bytes()).unwrap_err();
    assert_eq!(err.message, "'x' is not a valid int (face 5, property 'vertex_indices')");

    let no_faces =
        format!("{}{}", CUBE_HEADER.replace("element face 6", "element face 0"), &CUBE_BODY[..48]);
    let err = parse(no_faces.as_bytes()).unwrap_err();
    assert!(err.message.contains("no faces"), "{err:?}");

    assert!(parse(b"solid stl\n").unwrap_err().message.contains("not a PLY file"));
    let err = parse(cube().replace("end_header\n", "").as_bytes()).unwrap_err();
    assert!(err.message.contains("unexpected header line '0 0 0'"), "{err:?}");
}

#[test]
fn ascii_values_that_shift_between_lines_are_errors() {
    // Header says 8 vertices, the data has 7: the first face line is read as a vertex.
    let short = CUBE_HEADER.replace("element vertex 8", "element vertex 9");
    let err = parse(format!("{short}{CUBE_BODY}").as_bytes()).unwrap_err();
    assert!(err.message.contains("more values than"), "{}", err.message);
    assert_eq!(err.line, Some(19));
    // A vertex split over two lines.
    let split = CUBE_BODY.replacen("0 0 1\n", "0 0\n1\n", 1);
    let err = parse(format!("{CUBE_HEADER}{split}").as_bytes()).unwrap_err();
    assert!(err.message.contains("line ends before"), "{}", err.message);
    // Fewer faces declared than given.
    let few = CUBE_HEADER.replace("element face 6", "element face 5");
    let err = parse(format!("{few}{CUBE_BODY}").as_bytes()).unwrap_err();
    assert!(err.message.contains("goes on after the last element"), "{}", err.message);
    assert_eq!(err.line, Some(24));
}

/// Extra properties become attributes as Mitsuba groups them: `red green blue` is
/// `vertex_color`, `weight_0` is `face_weight`, `col_r col_g col_b` is `face_col_color`;
/// a two-field group and a lone name without a postfix are ignored. A polygon's values
/// repeat for each triangle of its fan.
#[test]
fn extra_properties_become_mitsubas_mesh_attributes() {
    let text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
        property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n\
        property float uv_x\nproperty float uv_y\nproperty float temperature\n\
        element face 2\nproperty list uchar int vertex_indices\nproperty float weight_0\n\
        property float col_r\nproperty float col_g\nproperty float col_b\nend_header\n\
        0 0 0 255 0 0 1 2 3\n1 0 0 0 255 0 1 2 3\n1 1 0 0 0 255 1 2 3\n0 1 0 9 9 9 1 2 3\n\
        4 0 1 2 3 0.25 0.1 0.2 0.3\n3 0 2 3 0.75 0.4 0.5 0.6\n";
    let (mesh, _) = parse(text.as_bytes()).unwrap();
    let names: Vec<&str> = mesh.attributes.iter().map(|a| a.name.as_str()).collect();
    assert_eq!(names, ["vertex_color", "face_weight", "face_col_color"]);
    // Mitsuba keeps integer colours as they are (it warns that [0, 1] is expected).
    assert_eq!(mesh.attributes[0].values[..6], [255.0, 0.0, 0.0, 0.0, 255.0, 0.0]);
    assert_eq!(mesh.indices.len(), 3, "a quad and a triangle");
    assert_eq!(mesh.attributes[1].values, [0.25, 0.25, 0.75]);
    assert_eq!(mesh.attributes[2].value(1), glam::Vec3::new(0.1, 0.2, 0.3));
    assert_eq!(mesh.attributes[2].value(2), glam::Vec3::new(0.4, 0.5, 0.6));
}

#[test]
fn a_non_finite_attribute_is_named() {
    let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
        property float z\nproperty float w_0\nelement face 1\n\
        property list uchar int vertex_indices\nend_header\n\
        0 0 0 1\n1 0 0 nan\n0 1 0 1\n3 0 1 2\n";
    let err = parse(text.as_bytes()).unwrap_err();
    assert_eq!((err.line, err.message.as_str()), (Some(12), "vertex 1 has a non-finite w_0"));
}

/// A property or element declared twice would leave one of its columns unread: refused at
/// the second declaration's line.
#[test]
fn a_property_or_element_declared_twice_is_an_error() {
    let text = cube().replace("property float z\n", "property float z\nproperty float x\n");
    let err = parse(text.as_bytes()).unwrap_err();
    assert_eq!(err.line, Some(8));
    assert_eq!(err.message, "property 'x' of 'vertex' is declared twice");

    let second = "element vertex 0\nproperty float x\nend_header\n";
    let err = parse(cube().replace("end_header\n", second).as_bytes()).unwrap_err();
    assert_eq!((err.line, err.message.as_str()), (Some(10), "element 'vertex' is declared twice"));
}
