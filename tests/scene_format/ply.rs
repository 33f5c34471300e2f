//! PLY files: ASCII and both binary byte orders, and the course's PLY models.

use super::*;
use crate::common::command::temp_dir;

/// Numbers written in one byte order.
struct Writer {
    bytes: Vec<u8>,
    big_endian: bool,
}

impl Writer {
    fn put<const N: usize>(&mut self, mut le: [u8; N]) {
        if self.big_endian {
            le.reverse();
        }
        self.bytes.extend(le);
    }
}

/// The cube of `cube.ply` in binary.
fn binary_cube(big_endian: bool) -> Vec<u8> {
    let order = if big_endian { "big" } else { "little" };
    let header = format!(
        "ply\nformat binary_{order}_endian 1.0\nelement vertex 8\nproperty float x\n\
         property float y\nproperty float z\nelement face 6\n\
         property list uchar int vertex_index\nend_header\n"
    );
    let mut w = Writer { bytes: header.into_bytes(), big_endian };
    for v in ["000", "001", "011", "010", "100", "101", "111", "110"] {
        for c in v.chars() {
            w.put(if c == '1' { 1f32 } else { 0f32 }.to_le_bytes());
        }
    }
    for face in
        [[0i32, 1, 2, 3], [7, 6, 5, 4], [0, 4, 5, 1], [1, 5, 6, 2], [2, 6, 7, 3], [3, 7, 4, 0]]
    {
        w.put([4u8]);
        for i in face {
            w.put(i.to_le_bytes());
        }
    }
    w.bytes
}

/// `triangle_attributes.ply` in binary.
fn binary_triangle(big_endian: bool) -> Vec<u8> {
    let order = if big_endian { "big" } else { "little" };
    let header = format!(
        "ply\nformat binary_{order}_endian 1.0\nelement vertex 3\nproperty double x\n\
         property double y\nproperty double z\nproperty float nx\nproperty float ny\n\
         property float nz\nproperty float texture_u\nproperty float texture_v\n\
         property uchar red\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n"
    );
    let mut w = Writer { bytes: header.into_bytes(), big_endian };
    for (p, uv) in [([0.0, 0.0], [0.0, 0.0]), ([2.0, 0.0], [1.0, 0.0]), ([0.0, 2.0], [0.0, 1.0])] {
        for c in [p[0], p[1], 0.0f64] {
            w.put(c.to_le_bytes());
        }
        for c in [0.0f32, 0.0, 1.0, uv[0], uv[1]] {
            w.put(c.to_le_bytes());
        }
        w.put([255u8]);
    }
    w.put([3u8]);
    for i in 0..3u32 {
        w.put(i.to_le_bytes());
    }
    w.bytes
}

#[test]
fn ply_ascii_and_binary_give_the_same_mesh() {
    let dir = temp_dir("ply-test");
    for (name, bytes) in [
        ("cube_le.ply", binary_cube(false)),
        ("cube_be.ply", binary_cube(true)),
        ("triangle_le.ply", binary_triangle(false)),
        ("triangle_be.ply", binary_triangle(true)),
    ] {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
    let data = data_dir();
    let files = [
        data.join("cube.ply"),
        dir.join("cube_le.ply"),
        dir.join("cube_be.ply"),
        data.join("triangle_attributes.ply"),
        dir.join("triangle_le.ply"),
        dir.join("triangle_be.ply"),
    ];
    let objects: String = files.iter().map(|f| ply_scene(&f.display().to_string(), None)).collect();
    let result = scene::load_str(&scene_with(&objects), &source());
    let scene = result.unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.objects.len(), 6);
    let cube = mesh_of(&scene, 0);
    assert_eq!((cube.positions.len(), cube.indices.len()), (8, 12));
    assert_eq!(cube.indices[10..], [[3, 7, 4], [3, 4, 0]]);
    assert_eq!(**mesh_of(&scene, 1), **cube);
    assert_eq!(**mesh_of(&scene, 2), **cube);
    let triangle = mesh_of(&scene, 3);
    assert_eq!(triangle.positions[1], DVec3::new(2.0, 0.0, 0.0));
    assert_eq!(triangle.normals.as_ref().unwrap(), &[DVec3::Z; 3]);
    assert_eq!(triangle.uvs.as_ref().unwrap()[2], Vec2::new(0.0, 1.0));
    assert_eq!(**mesh_of(&scene, 4), **triangle);
    assert_eq!(**mesh_of(&scene, 5), **triangle);
    assert_eq!(scene.objects[0].name, format!("objects[0] ({})", files[0].display()));
}

#[test]
#[cfg_attr(not(course_data), ignore = "needs the CENG795 packs at ../shared/data/ceng795")]
fn course_ply_files_load() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/ceng795");
    // (file, vertices, triangles): binary little endian triangle meshes, and Greg Turk's
    // ASCII cube of quads.
    let cases = [
        ("2024/hw1/inputs/akif_uslu/trex_smooth_ply/mesh_1.ply", 32445, 63360),
        ("2024/hw1/inputs/akif_uslu/trex_smooth_ply/mesh_2.ply", 228, 448),
        ("2024/hw1/inputs/akif_uslu/ton_Roosendaal_smooth_ply/mesh_1.ply", 8190, 16384),
        ("2024/hw1/inputs/akif_uslu/ton_Roosendaal_smooth_ply/mesh_2.ply", 31072, 62160),
        ("2024/hw1/inputs/akif_uslu/ton_Roosendaal_smooth_ply/mesh_3.ply", 78, 76),
        ("2021/hw3/ply/cube.ply", 8, 12),
    ];
    for (file, vertices, triangles) in cases {
        let path = dir.join(file);
        assert!(path.exists(), "{} is missing from the course packs", path.display());
        let scene = load(&scene_with(&ply_scene(&path.display().to_string(), Some(true))));
        let mesh = mesh_of(&scene, 0);
        assert_eq!((mesh.positions.len(), mesh.indices.len()), (vertices, triangles), "{file}");
        assert!(mesh.positions.iter().all(|p| p.is_finite() && p.abs().max_element() < 1e4));
        let normals = mesh.normals.as_ref().unwrap();
        let unit = normals.iter().filter(|n| (n.length() - 1.0).abs() < 1e-9).count();
        assert!(unit * 100 >= normals.len() * 99, "{file}: {unit} of {} unit", normals.len());
    }
    let cube = load(&scene_with(&ply_scene(
        &dir.join("2021/hw3/ply/cube.ply").display().to_string(),
        None,
    )));
    let local = load(&scene_with(&ply_scene("cube.ply", None)));
    assert_eq!(**mesh_of(&cube, 0), **mesh_of(&local, 0));
}
