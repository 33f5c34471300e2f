//! Property tests of the scene loaders (TOML, OBJ, PLY, CENG795 XML) on mutated valid input:
//! whatever the bytes, loading returns a scene or an error naming the file; it never panics.
//!
//! `cargo test --test loader_proptest` runs 256 cases per loader from a fixed seed, so that
//! CI is reproducible. A longer run from fresh random seeds:
//! `EMBRAY_PROPTEST_CASES=100000 EMBRAY_PROPTEST_SEED=random cargo test --release --test
//! loader_proptest` (or a number to replay one).

mod common;

use embray::scene::{self, ceng795};
use proptest::prelude::*;
use std::path::{Path, PathBuf};

fn config() -> ProptestConfig {
    common::proptest_config(256, 795)
}

/// Tokens that have broken parsers: numbers at and past the limits, syntax characters,
/// keywords of the formats.
const TOKENS: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "-1",
    "0",
    "1e39",
    "1e308",
    "-0",
    "99999999999999999999",
    "4294967296",
    "\"",
    "'",
    "[",
    "]",
    "{",
    "}",
    "=",
    ",",
    "\n",
    "\r\n",
    " ",
    "#",
    "\\",
    "\0",
    "é",
    "v",
    "vt",
    "vn",
    "f",
    "usemtl",
    "mtllib",
    "o",
    "g",
    "1/2/3",
    "//",
    "-2",
    "ply",
    "element",
    "property",
    "list",
    "uchar",
    "float",
    "end_header",
    "format",
    "binary_little_endian",
    "<",
    ">",
    "</",
    "/>",
    "<Scene>",
    "<Camera>",
    "&amp;",
    "&bogus;",
    "<!--",
    "]]>",
    "[[objects]]",
    "type",
    "mesh",
    "sphere",
    "quad",
    "repeat",
    "transform",
    "matrix",
];

/// One change to a text: at a position (a fraction of its length) delete some bytes and
/// insert a token or random characters.
#[derive(Clone, Debug)]
struct Edit {
    at: f64,
    delete: usize,
    insert: String,
}

fn edit() -> impl Strategy<Value = Edit> {
    let token = prop_oneof![
        3 => proptest::sample::select(TOKENS).prop_map(str::to_owned),
        1 => "\\PC{0,12}",
    ];
    (0.0..1.0f64, 0..8usize, token).prop_map(|(at, delete, insert)| Edit { at, delete, insert })
}

fn mutate(seed: &str, edits: &[Edit]) -> String {
    let mut bytes = seed.as_bytes().to_vec();
    for edit in edits {
        let at = ((bytes.len() as f64) * edit.at) as usize;
        let end = (at + edit.delete).min(bytes.len());
        bytes.splice(at..end, edit.insert.bytes());
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

const TOML_SEED: &str = r#"[camera]
lookfrom = [0.0, 1.0, 4.0]
lookat = [0.0, 0.0, 0.0]
vfov = 40.0
resolution = [16, 12]
f_number = 2.8
focal_length = 50.0

[render]
spp = 4
max_depth = 3

[materials.white]
albedo = [0.8, 0.8, 0.8]

[materials.glass]
type = "dielectric"
ior = 1.5

[[objects]]
type = "sphere"
material = "white"
center = [0.0, 0.0, 0.0]
radius = 1.0
transform = [{ scale = 2.0 }, { rotate = { axis = [0.0, 1.0, 0.0], degrees = 30.0 } }]

[[objects]]
type = "box"
material = "glass"
min = [0.0, 0.0, 0.0]
max = [1.0, 1.0, 1.0]
repeat = { count = [2, 1, 2], spacing = [2.0, 0.0, 2.0] }

[[lights]]
type = "quad"
corner = [0.0, 3.0, 0.0]
u = [1.0, 0.0, 0.0]
v = [0.0, 0.0, 1.0]
emission = [4.0, 4.0, 4.0]
"#;

const OBJ_SEED: &str = "mtllib m.mtl\no tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\n\
    vt 0 1\nvn 0 0 1\nusemtl red\nf 1/1/1 2/2/1 3/3/1\nf -1 -2 -3\nf 1 2 3 4\n";

const MTL_SEED: &str = "newmtl red\nKd 0.8 0.1 0.1\nKe 0 0 0\n";

const PLY_SEED: &str = "ply\nformat ascii 1.0\ncomment seed\nelement vertex 4\nproperty float x\n\
    property float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n\
    element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0 0 0 1\n1 0 0 0 0 1\n\
    1 1 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n4 0 1 2 3\n";

const XML_SEED: &str = r#"<Scene>
  <MaxRecursionDepth>2</MaxRecursionDepth>
  <BackgroundColor>0 0 0</BackgroundColor>
  <Cameras>
    <Camera id="1">
      <Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>
      <NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance>
      <ImageResolution>8 8</ImageResolution><ImageName>a.png</ImageName>
    </Camera>
  </Cameras>
  <Lights><AmbientLight>25 25 25</AmbientLight>
    <PointLight id="1"><Position>0 2 0</Position><Intensity>1000 1000 1000</Intensity></PointLight>
  </Lights>
  <Materials>
    <Material id="1" type="mirror"><AmbientReflectance>1 1 1</AmbientReflectance>
      <DiffuseReflectance>1 1 1</DiffuseReflectance><SpecularReflectance>1 1 1</SpecularReflectance>
      <MirrorReflectance>0.5 0.5 0.5</MirrorReflectance><PhongExponent>10</PhongExponent></Material>
  </Materials>
  <Transformations><Translation id="1">0 0 -5</Translation><Scaling id="1">2 2 2</Scaling></Transformations>
  <VertexData>0 0 -3  1 0 -3  0 1 -3</VertexData>
  <Objects>
    <Mesh id="1"><Material>1</Material><Transformations>t1 s1</Transformations><Faces>1 2 3</Faces></Mesh>
    <MeshInstance id="2" baseMeshId="1"><Transformations>t1</Transformations></MeshInstance>
    <Sphere id="1"><Material>1</Material><Center>1</Center><Radius>0.5</Radius></Sphere>
  </Objects>
</Scene>
"#;

/// A folder of its own for each thread's mesh files.
fn folder() -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "embray-proptest-{}-{:?}",
        std::process::id(),
        std::thread::current().id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[track_caller]
fn assert_names(message: &str, file: &str) {
    assert!(message.contains(file), "the error does not name {file}: {message}");
    assert!(message.len() < 4000, "an overlong message ({} bytes)", message.len());
}

/// A scene naming one mesh file.
fn mesh_scene(file: &str) -> String {
    format!(
        "[camera]\nlookfrom = [0.0, 0.0, 4.0]\nlookat = [0.0, 0.0, 0.0]\nvfov = 40.0\n\
         resolution = [8, 8]\n\n[[objects]]\ntype = \"mesh\"\nfile = \"{file}\"\n"
    )
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn toml_scenes_load_or_name_the_file(edits in proptest::collection::vec(edit(), 1..6)) {
        let text = mutate(TOML_SEED, &edits);
        if let Err(e) = scene::load_str_with_warnings(&text, Path::new("fuzz.toml")) {
            assert_names(&e.to_string(), "fuzz.toml");
        }
    }

    #[test]
    fn obj_meshes_load_or_name_the_file(
        obj_edits in proptest::collection::vec(edit(), 1..6),
        mtl_edits in proptest::collection::vec(edit(), 0..3),
    ) {
        let dir = folder();
        std::fs::write(dir.join("m.obj"), mutate(OBJ_SEED, &obj_edits)).unwrap();
        std::fs::write(dir.join("m.mtl"), mutate(MTL_SEED, &mtl_edits)).unwrap();
        let source = dir.join("s.toml");
        if let Err(e) = scene::load_str_with_warnings(&mesh_scene("m.obj"), &source) {
            let message = e.to_string();
            assert!(message.contains("m.obj") || message.contains("m.mtl"), "{message}");
            assert!(message.len() < 4000);
        }
    }

    #[test]
    fn ply_meshes_load_or_name_the_file(
        edits in proptest::collection::vec(edit(), 1..6),
        binary_tail in proptest::collection::vec(any::<u8>(), 0..64),
        binary in any::<bool>(),
    ) {
        let dir = folder();
        let mut bytes = mutate(PLY_SEED, &edits).into_bytes();
        if binary {
            // A binary header over random bytes.
            let header = PLY_SEED.replace("ascii", "binary_little_endian");
            let end = header.find("end_header\n").unwrap() + "end_header\n".len();
            bytes = header.as_bytes()[..end].to_vec();
            bytes.extend(&binary_tail);
        }
        std::fs::write(dir.join("m.ply"), bytes).unwrap();
        let source = dir.join("s.toml");
        if let Err(e) = scene::load_str_with_warnings(&mesh_scene("m.ply"), &source) {
            assert_names(&e.to_string(), "m.ply");
        }
    }

    #[test]
    fn ceng795_scenes_load_or_name_the_file(edits in proptest::collection::vec(edit(), 1..6)) {
        let text = mutate(XML_SEED, &edits);
        if let Err(e) = ceng795::load_str_with_warnings(&text, Path::new("fuzz.xml")) {
            assert_names(&e.to_string(), "fuzz.xml");
        }
    }
}

#[test]
fn the_seeds_themselves_load() {
    scene::load_str_with_warnings(TOML_SEED, Path::new("seed.toml")).unwrap();
    ceng795::load_str_with_warnings(XML_SEED, Path::new("seed.xml")).unwrap();
    let dir = folder();
    std::fs::write(dir.join("m.obj"), OBJ_SEED).unwrap();
    std::fs::write(dir.join("m.mtl"), MTL_SEED).unwrap();
    std::fs::write(dir.join("m.ply"), PLY_SEED).unwrap();
    for file in ["m.obj", "m.ply"] {
        scene::load_str_with_warnings(&mesh_scene(file), &dir.join("s.toml")).unwrap();
    }
}
