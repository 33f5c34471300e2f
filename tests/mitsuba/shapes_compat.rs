//! Mitsuba's shapes as Mitsuba builds them: texture coordinates, sides and transforms;
//! what embray would render otherwise is refused by name.

use super::common::{assert_contains, backends, options, render_ok};
use super::load_mitsuba;
use super::reader::{SENSOR, files};
use embray::scene::{SceneDesc, ShapeDesc};
use glam::{DVec3, Vec2};

/// A scene of the reader tests' sensor under a constant sky, with `body`.
fn scene_text(body: &str) -> String {
    format!(
        "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" \
         value=\"40\"/>{SENSOR}\n<emitter type=\"constant\"><rgb name=\"radiance\" \
         value=\"1\"/></emitter>\n{body}\n</scene>"
    )
}

/// The scene and its warnings, or the error's message.
fn load(
    name: &str,
    body: &str,
    extra: &[(&str, &str)],
) -> Result<(SceneDesc, Vec<String>), String> {
    let path = files(name, &scene_text(body), extra);
    let (mut scenes, warnings) =
        embray::scene::xml::load_with_warnings(&path, &[]).map_err(|e| e.to_string())?;
    Ok((scenes.remove(0).scene, warnings))
}

#[track_caller]
fn refused(name: &str, body: &str, extra: &[(&str, &str)]) -> String {
    match load(name, body, extra) {
        Ok(_) => panic!("{name}: expected an error"),
        Err(message) => message,
    }
}

fn mesh(scene: &SceneDesc, object: usize) -> &embray::scene::MeshData {
    match &scene.objects[object].shape {
        ShapeDesc::Mesh(mesh) => mesh,
        other => panic!("object {object} is {other:?}"),
    }
}

/// Mitsuba's cube is 24 vertices, four to a face, each face with its own normal and the uv
/// square (0,1), (1,1), (1,0), (0,0): a bitmap lands whole on every face (it had no texture
/// coordinates, and a texture smeared).
#[test]
fn a_cube_has_mitsubas_vertices_normals_and_a_uv_square_on_each_face() {
    let (scene, _) = load("m-cube-uv", "<shape type=\"cube\"/>", &[]).unwrap();
    let cube = mesh(&scene, 0);
    assert_eq!((cube.positions.len(), cube.indices.len()), (24, 12));
    let uvs = cube.uvs.as_ref().expect("texture coordinates");
    let square = [Vec2::Y, Vec2::ONE, Vec2::X, Vec2::ZERO];
    assert!(uvs.chunks(4).all(|face| face == square));
    let normals = cube.normals.as_ref().expect("face normals");
    assert_eq!(normals[0], DVec3::NEG_Y);
    assert_eq!(normals[23], DVec3::NEG_Z);
    assert_eq!(cube.positions[0], DVec3::new(1.0, -1.0, -1.0));
}

/// A quad at y = 1 facing the camera (+z) through its vertex normal, wound `corners`.
fn quad_obj(corners: &str) -> String {
    format!("v -1 0 0\nv 1 0 0\nv 1 2 0\nv -1 2 0\nvn 0 0 1\nf {corners}\n")
}

/// Mitsuba takes a triangle's side from its vertex normals, not its winding: a one-sided
/// quad wound away from the camera whose normals face it is lit as the one wound towards
/// it (it was black).
#[test]
fn a_mesh_faces_the_side_of_its_vertex_normals_whatever_its_winding() {
    let shape = |file: &str| {
        format!(
            "<shape type=\"obj\"><string name=\"filename\" value=\"{file}\"/><bsdf \
             type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.6\"/></bsdf></shape>"
        )
    };
    let objs = [
        ("towards.obj", quad_obj("1//1 2//1 3//1 4//1")),
        ("away.obj", quad_obj("1//1 4//1 3//1 2//1")),
    ];
    let extra: Vec<(&str, &str)> = objs.iter().map(|(n, t)| (*n, t.as_str())).collect();
    let (towards, _) = load("m-sides-towards", &shape("towards.obj"), &extra).unwrap();
    let (away, _) = load("m-sides-away", &shape("away.obj"), &extra).unwrap();
    let quad = mesh(&away, 0);
    for &[a, b, c] in &quad.indices {
        let p = |i: u32| quad.positions[i as usize];
        assert!((p(b) - p(a)).cross(p(c) - p(a)).z > 0.0, "wound as its normals");
    }
    for backend in backends() {
        let image = |scene: &SceneDesc| render_ok(scene, &options(scene, backend, 4)).film.color;
        let (a, b) = (image(&towards), image(&away));
        let centre = a.len() / 2 + 16;
        assert!(b[centre].min_element() > 0.3, "{backend:?}: the quad is lit: {}", b[centre]);
        let difference =
            a.iter().zip(&b).map(|(p, q)| (*p - *q).abs().max_element()).fold(0.0, f32::max);
        assert!(difference < 1e-4, "{backend:?}: largest difference {difference}");
    }
}

/// Shapes that name one OBJ share its mesh as Mitsuba reads it (rewound to its vertex
/// normals, its v flipped): one copy, whatever their number (each had its own).
#[test]
fn shapes_naming_one_mesh_file_share_one_prepared_mesh() {
    let shape = |x: f64| {
        format!(
            "<shape type=\"obj\"><string name=\"filename\" value=\"away.obj\"/><transform \
             name=\"to_world\"><translate x=\"{x}\"/></transform></shape>"
        )
    };
    let obj = format!("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n{}", quad_obj("1/1/1 4/4/1 3/3/1 2/2/1"));
    let body = format!("{}{}{}", shape(-2.0), shape(0.0), shape(2.0));
    let (scene, _) = load("m-shared-prepared", &body, &[("away.obj", &obj)]).unwrap();
    let ShapeDesc::Mesh(first) = &scene.objects[0].shape else { panic!() };
    for object in &scene.objects[1..] {
        let ShapeDesc::Mesh(mesh) = &object.shape else { panic!() };
        assert!(std::sync::Arc::ptr_eq(first, mesh), "{}", object.name);
    }
    // Rewound and flipped all the same: v of the first vertex (vt 0 0) is 1.
    assert_eq!(first.uvs.as_ref().unwrap()[0], Vec2::Y);
    let p = |i: u32| first.positions[i as usize];
    let [a, b, c] = first.indices[0];
    assert!((p(b) - p(a)).cross(p(c) - p(a)).z > 0.0, "wound as its normals");
}

/// Mitsuba keeps one scale of a sphere's to_world (warning) and turns a mirrored sphere
/// inside out: embray drew an ellipsoid, and an outward sphere; both are refused by name.
#[test]
fn a_sphere_scaled_unevenly_or_mirrored_is_refused_at_its_transform() {
    let sphere = |transform: &str| {
        format!(
            "<shape type=\"sphere\">\n<transform name=\"to_world\">{transform}</transform></shape>"
        )
    };
    let uneven = refused("m-sphere-uneven", &sphere("<scale x=\"1.5\" y=\"0.6\"/>"), &[]);
    assert_contains(&uneven, &["main.xml", "line 17", "scales unevenly", "not this ellipsoid"]);
    let mirrored =
        refused("m-sphere-mirror", &sphere("<scale x=\"-0.8\" y=\"0.8\" z=\"0.8\"/>"), &[]);
    assert_contains(&mirrored, &["main.xml", "line 17", "mirrors it", "inside out"]);
    let turned = "<scale value=\"0.7\"/><rotate x=\"1\" angle=\"33\"/><translate y=\"1\"/>";
    assert!(load("m-sphere-uniform", &sphere(turned), &[]).is_ok());
}

/// Mitsuba's OBJ reader ignores `mtllib`: a missing or broken MTL file is neither read nor
/// warned about (it was: "its materials fall back to the default").
#[test]
fn an_obj_in_a_mitsuba_scene_reads_no_mtl_file() {
    let obj =
        format!("mtllib missing.mtl\nmtllib broken.mtl\nusemtl paint\n{}", quad_obj("1 2 3 4"));
    let extra = [("q.obj", obj.as_str()), ("broken.mtl", "newmtl\nKd x y z\n")];
    let body = "<shape type=\"obj\"><string name=\"filename\" value=\"q.obj\"/></shape>";
    let (scene, warnings) = load("m-obj-no-mtl", body, &extra).unwrap();
    assert_eq!(scene.objects.len(), 1);
    assert!(warnings.is_empty(), "{warnings:?}");
}

const COLOURED_PLY: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n\
    property float y\nproperty float z\nproperty uchar red\nproperty uchar green\n\
    property uchar blue\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
    0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 128\n3 0 1 2\n";

/// 8-bit PLY colours read through `mesh_attribute` are 0–255 to Mitsuba (255 times too
/// bright) and were clamped to 1 by embray: refused, naming the file and the attribute; in
/// [0, 1] through the texture's scale they are accepted.
#[test]
fn a_mesh_attribute_reflectance_outside_0_1_is_refused_by_file_and_attribute() {
    let shape = |scale: &str| {
        format!(
            "<shape type=\"ply\"><string name=\"filename\" value=\"c.ply\"/><bsdf \
             type=\"diffuse\"><texture type=\"mesh_attribute\" name=\"reflectance\"><string \
             name=\"name\" value=\"vertex_color\"/>{scale}</texture></bsdf></shape>"
        )
    };
    let extra = [("c.ply", COLOURED_PLY)];
    let raw = refused("m-ply-colour-raw", &shape(""), &extra);
    assert_contains(&raw, &["main.xml", "line 16", "`vertex_color`", "'c.ply'", "reaches 255"]);
    let scaled = shape("<float name=\"scale\" value=\"0.00392156\"/>");
    assert!(load("m-ply-colour-scaled", &scaled, &extra).is_ok());
    // 1/255 to eight places takes 255 to 1.0000002 in f32: past 1 by rounding, accepted.
    let rounded = shape("<float name=\"scale\" value=\"0.00392157\"/>");
    assert!(load("m-ply-colour-rounded", &rounded, &extra).is_ok());
    let past =
        refused("m-ply-colour-past", &shape("<float name=\"scale\" value=\"0.004\"/>"), &extra);
    assert_contains(&past, &["reaches 1.02", "scale (1/255: 0.00392157)"]);
}

/// The bytes of Mitsuba's own single-mesh test file (a rectangle with normals and uvs).
fn rectangle_serialized() -> Vec<u8> {
    std::fs::read(super::common::repo_path("tests/data/mitsuba/rectangle_normals_uv.serialized"))
        .unwrap()
}

/// What Mitsuba would read past unseen in a `.serialized` mesh is refused naming the file:
/// bytes between the mesh and the table of meshes, a table that counts no mesh, flags no
/// mesh defines (all three were accepted for shape_index 0). The file as it is loads.
#[test]
fn a_serialized_mesh_with_data_it_does_not_declare_is_refused() {
    let body =
        "<shape type=\"serialized\"><string name=\"filename\" value=\"m.serialized\"/></shape>";
    let load_bytes = |name: &str, bytes: &[u8]| {
        let path = files(name, &scene_text(body), &[]);
        std::fs::write(path.parent().unwrap().join("m.serialized"), bytes).unwrap();
        load_mitsuba(&path, &[])
    };
    let good = rectangle_serialized();
    assert!(load_bytes("m-ser-good", &good).is_ok());
    let table = good.len() - 12;
    let gap = [&good[..table], b"junk", &good[table..]].concat();
    let message = load_bytes("m-ser-gap", &gap).unwrap_err();
    assert_contains(&message, &["m.serialized", "main.xml", "line 16", "but the table starts"]);
    let mut none = good.clone();
    none[good.len() - 4] = 0;
    assert_contains(&load_bytes("m-ser-none", &none).unwrap_err(), &["counts 0 meshes"]);
}
