//! The scene format's newer parts, parsed into the right `SceneDesc` values: lens and
//! render settings, material types, textures, motion, repeat grids, shared meshes, smooth
//! normals, PLY files, the new light types, and the bundled scenes that use them. (Errors
//! are tested in `bad_input_scene.rs`.)

use embray::scene::{
    self, IntegratorKind, LensShape, LightDesc, MaterialDesc, MeshData, PatternDesc, PhongDesc,
    SceneDesc, ShapeDesc, SpecularDesc,
};
use glam::{DAffine3, DVec3, Vec2, Vec3};
use std::path::{Path, PathBuf};
use std::sync::Arc;

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/scene")
}

/// The (virtual) file the test scenes come from; mesh paths resolve against its directory.
fn source() -> PathBuf {
    data_dir().join("scene.toml")
}

const CAMERA: &str = "\
[camera]
lookfrom = [0.0, 0.0, -5.0]
lookat = [0.0, 0.0, 0.0]
vfov = 40.0
resolution = [32, 24]
";

const WHITE: &str = "[materials.white]\nalbedo = [0.73, 0.73, 0.73]\n";

fn load(text: &str) -> SceneDesc {
    load_from(text, &source())
}

fn load_from(text: &str, source: &Path) -> SceneDesc {
    match scene::load_str(text, source) {
        Ok(scene) => scene,
        Err(e) => panic!("scene should load, got: {e}\n{text}"),
    }
}

fn scene_with(rest: &str) -> String {
    format!("{CAMERA}{WHITE}{rest}")
}

fn mesh_of(scene: &SceneDesc, object: usize) -> &Arc<MeshData> {
    match &scene.objects[object].shape {
        ShapeDesc::Mesh(mesh) => mesh,
        other => panic!("object {object} is not a mesh: {other:?}"),
    }
}

fn material<'a>(scene: &'a SceneDesc, name: &str) -> &'a MaterialDesc {
    scene.materials.iter().find(|m| m.name == name).unwrap_or_else(|| panic!("no {name}"))
}

#[track_caller]
fn assert_close(a: DVec3, b: DVec3) {
    assert!((a - b).length() < 1e-12, "{a} != {b}");
}

// ---------------------------------------------------------------------------------------
// Camera and render settings
// ---------------------------------------------------------------------------------------

#[test]
fn f_number_and_focal_length_give_the_aperture() {
    let scene =
        load(&format!("{CAMERA}f_number = 2.0\nfocal_length = 0.05\nfocus_distance = 4.5\n"));
    assert_eq!(scene.camera.aperture, 0.025);
    assert_eq!(scene.camera.focus_distance, Some(4.5));
    assert_eq!(scene.camera.lens_shape, LensShape::Disk);
}

#[test]
fn aperture_and_lens_shape() {
    let scene = load(&format!("{CAMERA}aperture = 0.2\nlens = \"square\"\n"));
    assert_eq!((scene.camera.aperture, scene.camera.lens_shape), (0.2, LensShape::Square));
    let scene = load(&format!("{CAMERA}lens = \"disk\"\n"));
    assert_eq!((scene.camera.aperture, scene.camera.lens_shape), (0.0, LensShape::Disk));
}

#[test]
fn light_samples_and_integrator() {
    let scene = load(CAMERA);
    assert_eq!(scene.settings.light_samples, 1);
    assert_eq!(scene.settings.integrator, IntegratorKind::Path);
    let scene = load(&format!("{CAMERA}[render]\nlight_samples = 4\nintegrator = \"whitted\"\n"));
    assert_eq!(scene.settings.light_samples, 4);
    assert_eq!(scene.settings.integrator, IntegratorKind::Whitted);
    let scene = load(&format!("{CAMERA}[render]\nintegrator = \"path\"\n"));
    assert_eq!(scene.settings.integrator, IntegratorKind::Path);
}

// ---------------------------------------------------------------------------------------
// Materials
// ---------------------------------------------------------------------------------------

const MATERIALS: &str = r#"
[materials.plain]

[materials.chrome]
type = "mirror"

[materials.tinted]
type = "mirror"
albedo = [0.1, 0.1, 0.1]
reflectance = [0.9, 0.8, 0.7]
roughness = 0.05
emission = [0.5, 0.0, 0.0]

[materials.metal]
type = "conductor"
eta = [0.2, 0.9, 1.1]
k = [3.9, 2.4, 2.1]
reflectance = [0.5, 0.5, 0.5]
roughness = 0.2

[materials.gold]
type = "conductor"
preset = "gold"

[materials.aluminum]
type = "conductor"
preset = "aluminum"

[materials.glass]
type = "dielectric"

[materials.green_glass]
type = "dielectric"
ior = 1.33
absorption = [0.5, 0.0, 0.5]
roughness = 0.1
"#;

#[test]
fn material_types_and_their_defaults() {
    let scene = load(&format!("{CAMERA}{MATERIALS}"));
    let plain = material(&scene, "plain");
    assert_eq!(*plain, MaterialDesc { name: "plain".to_owned(), ..MaterialDesc::default() });
    assert_eq!(plain.albedo, Vec3::splat(0.8));

    let chrome = material(&scene, "chrome");
    assert_eq!(chrome.albedo, Vec3::ZERO);
    assert_eq!(chrome.specular, SpecularDesc::Mirror { reflectance: Vec3::ONE });
    assert_eq!(chrome.roughness, 0.0);

    let tinted = material(&scene, "tinted");
    assert_eq!(tinted.albedo, Vec3::splat(0.1));
    assert_eq!(tinted.emission, Vec3::new(0.5, 0.0, 0.0));
    assert_eq!(tinted.specular, SpecularDesc::Mirror { reflectance: Vec3::new(0.9, 0.8, 0.7) });
    assert_eq!(tinted.roughness, 0.05);

    let metal = material(&scene, "metal");
    assert_eq!(
        metal.specular,
        SpecularDesc::Conductor {
            eta: Vec3::new(0.2, 0.9, 1.1),
            k: Vec3::new(3.9, 2.4, 2.1),
            reflectance: Vec3::splat(0.5)
        }
    );
    assert_eq!((metal.albedo, metal.roughness), (Vec3::ZERO, 0.2));

    let SpecularDesc::Conductor { eta, k, reflectance } = &material(&scene, "gold").specular else {
        panic!("gold is not a conductor");
    };
    assert!((*eta - Vec3::new(0.1431, 0.3750, 1.4425)).abs().max_element() < 1e-4, "{eta}");
    assert!((*k - Vec3::new(3.9832, 2.3857, 1.6032)).abs().max_element() < 1e-4, "{k}");
    assert_eq!(*reflectance, Vec3::ONE);
    let SpecularDesc::Conductor { eta, .. } = &material(&scene, "aluminum").specular else {
        panic!("aluminum is not a conductor");
    };
    assert!((eta.x - 1.6575).abs() < 1e-4, "{eta}");

    let glass = material(&scene, "glass");
    assert_eq!(glass.specular, SpecularDesc::Dielectric { ior: 1.5, absorption: Vec3::ZERO });
    assert_eq!(glass.albedo, Vec3::ZERO);
    let green = material(&scene, "green_glass");
    assert_eq!(
        green.specular,
        SpecularDesc::Dielectric { ior: 1.33, absorption: Vec3::new(0.5, 0.0, 0.5) }
    );
    assert_eq!(green.roughness, 0.1);
}

#[test]
fn textures_and_phong_terms() {
    let scene = load(&format!(
        "{CAMERA}[materials.floor]\n\
         texture = {{ type = \"checker2d\", scale = 8.0, even = [0.9, 0.9, 0.9], odd = [0.1, 0.1, 0.1] }}\n\
         [materials.solid]\ntype = \"mirror\"\n\
         texture = {{ type = \"checker3d\", scale = 0.5, even = [1, 0, 0], odd = [0, 0, 1] }}\n\
         phong = {{ ambient = [0.1, 0.1, 0.1], specular = [1, 1, 1], exponent = 50 }}\n\
         [materials.course]\nphong = {{ specular = [0.5, 0.5, 0.5] }}\n"
    ));
    let floor = material(&scene, "floor").texture.clone().unwrap();
    assert_eq!(
        floor.pattern,
        PatternDesc::Checker2d { scale: 8.0, even: Vec3::splat(0.9), odd: Vec3::splat(0.1) }
    );
    assert_eq!(floor.texture_from_object, DAffine3::IDENTITY);
    let solid = material(&scene, "solid");
    assert_eq!(
        solid.texture.as_ref().unwrap().pattern,
        PatternDesc::Checker3d { scale: 0.5, even: Vec3::X, odd: Vec3::Z }
    );
    assert_eq!(
        solid.phong,
        Some(PhongDesc { ambient: Vec3::splat(0.1), specular: Vec3::ONE, exponent: 50.0 })
    );
    assert_eq!(
        material(&scene, "course").phong,
        Some(PhongDesc { ambient: Vec3::ZERO, specular: Vec3::splat(0.5), exponent: 1.0 })
    );
    assert_eq!(material(&scene, "floor").phong, None);
}

#[test]
fn with_texture_space_attaches_a_texture_to_an_instance() {
    let scene = load(&format!(
        "{CAMERA}[materials.solid]\n\
         texture = {{ type = \"checker3d\", scale = 1.0, even = [1, 1, 1], odd = [0, 0, 0] }}\n"
    ));
    let instance = DAffine3::from_scale(DVec3::splat(0.5));
    let attached = scene::with_texture_space(&scene.materials[0], instance);
    assert_eq!(attached.texture.as_ref().unwrap().texture_from_object, instance);
    assert_eq!(attached.name, "solid");
    // The original is unchanged.
    assert_eq!(
        scene.materials[0].texture.as_ref().unwrap().texture_from_object,
        DAffine3::IDENTITY
    );
}

// ---------------------------------------------------------------------------------------
// Motion and repeat
// ---------------------------------------------------------------------------------------

const BOX: &str =
    "[[objects]]\ntype = \"box\"\nmaterial = \"white\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n";

#[test]
fn transform_end_makes_a_moving_object() {
    let scene = load(&scene_with(&format!(
        "{BOX}transform = [{{ translate = [1, 0, 0] }}]\n\
         transform_end = [{{ rotate = {{ axis = [0, 1, 0], degrees = 90 }} }}, {{ translate = [1, 2, 0] }}]\n\
         {BOX}"
    )));
    let moving = &scene.objects[0];
    assert!(moving.is_moving());
    assert_eq!(moving.world_from_object, DAffine3::from_translation(DVec3::X));
    let end = moving.world_from_object_end.unwrap();
    assert_close(end.transform_point3(DVec3::X), DVec3::new(1.0, 2.0, -1.0));
    assert_eq!(scene.objects[1].world_from_object_end, None);
    assert!(!scene.objects[1].is_moving());
}

#[test]
fn repeat_places_copies_that_share_one_mesh() {
    let scene = load(&scene_with(&format!(
        "{BOX}transform = [{{ scale = 0.5 }}, {{ translate = [10, 0, 0] }}]\n\
         transform_end = [{{ translate = [10, 1, 0] }}]\n\
         repeat = {{ count = [3, 1, 2], spacing = [2.0, 5.0, 3.0] }}\n"
    )));
    assert_eq!(scene.objects.len(), 6);
    let first = mesh_of(&scene, 0);
    for (n, object) in scene.objects.iter().enumerate() {
        assert!(Arc::ptr_eq(first, mesh_of(&scene, n)), "copy {n} has its own mesh");
        assert_eq!(object.material, scene.objects[0].material);
    }
    // Copies in x-major order: (i, j, k) = (1, 0, 1) is the 4th.
    let copy = &scene.objects[3];
    assert_eq!(copy.name, "objects[0] (box) copy (1,0,1)");
    assert_close(copy.world_from_object.transform_point3(DVec3::ONE), DVec3::new(12.5, 0.5, 3.5));
    let end = copy.world_from_object_end.unwrap();
    assert_close(end.transform_point3(DVec3::ZERO), DVec3::new(12.0, 1.0, 3.0));
    assert_eq!(scene.objects[5].name, "objects[0] (box) copy (2,0,1)");
}

#[test]
fn repeated_spheres_are_spheres_placed_apart() {
    let scene = load(&scene_with(
        "[[objects]]\ntype = \"sphere\"\nmaterial = \"white\"\ncenter = [0, 1, 0]\nradius = 0.5\n\
         repeat = { count = [2, 2, 1], spacing = [1.5, 0, 0] }\n",
    ));
    assert_eq!(scene.objects.len(), 4);
    for object in &scene.objects {
        assert_eq!(object.shape, ShapeDesc::Sphere { center: DVec3::Y, radius: 0.5 });
        assert_eq!(object.world_from_object_end, None);
    }
    assert_eq!(scene.objects[3].world_from_object.translation, DVec3::new(1.5, 0.0, 0.0));
}

#[test]
fn textured_copies_keep_the_material_in_object_space() {
    let scene = load(&format!(
        "{CAMERA}[materials.checks]\n\
         texture = {{ type = \"checker3d\", scale = 4.0, even = [1, 1, 1], odd = [0, 0, 0] }}\n\
         [[objects]]\ntype = \"sphere\"\nmaterial = \"checks\"\ncenter = [0, 0, 0]\nradius = 1.0\n\
         transform = [{{ scale = [2, 1, 1] }}]\nrepeat = {{ count = [3, 1, 1], spacing = [5, 0, 0] }}\n"
    ));
    assert_eq!(scene.materials.len(), 1);
    let texture = scene.materials[0].texture.as_ref().unwrap();
    assert_eq!(texture.texture_from_object, DAffine3::IDENTITY);
    assert!(scene.objects.iter().all(|o| o.material == 0));
}

// ---------------------------------------------------------------------------------------
// Shared mesh files and smooth normals
// ---------------------------------------------------------------------------------------

#[test]
fn objects_naming_one_obj_share_its_meshes_and_materials() {
    let scene = load(&scene_with(
        "[[objects]]\ntype = \"mesh\"\nfile = \"two_materials.obj\"\n\
         [[objects]]\ntype = \"mesh\"\nfile = \"./two_materials.obj\"\ntransform = [{ translate = [3, 0, 0] }]\n\
         [[objects]]\ntype = \"mesh\"\nfile = \"two_materials.obj\"\nmaterial = \"white\"\n",
    ));
    assert_eq!(scene.objects.len(), 6);
    for model in 0..2 {
        assert!(Arc::ptr_eq(mesh_of(&scene, model), mesh_of(&scene, model + 2)));
        assert!(Arc::ptr_eq(mesh_of(&scene, model), mesh_of(&scene, model + 4)));
        assert_eq!(scene.objects[model].material, scene.objects[model + 2].material);
    }
    assert!(!Arc::ptr_eq(mesh_of(&scene, 0), mesh_of(&scene, 1)));
    // white, and the two MTL materials once.
    let names: Vec<&str> = scene.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["white", "two_materials.obj: Red", "two_materials.obj: Glow"]);
}

#[test]
fn repeated_obj_models_share_one_mesh_per_model() {
    let scene = load(&scene_with(
        "[[objects]]\ntype = \"mesh\"\nfile = \"two_materials.obj\"\n\
         repeat = { count = [2, 2, 2], spacing = [1, 1, 1] }\n",
    ));
    assert_eq!(scene.objects.len(), 16);
    let panels: Vec<_> = scene.objects.iter().map(|o| &o.shape).collect();
    for (n, shape) in panels.iter().enumerate() {
        let ShapeDesc::Mesh(mesh) = shape else { panic!() };
        let first = if n < 8 { mesh_of(&scene, 0) } else { mesh_of(&scene, 8) };
        assert!(Arc::ptr_eq(mesh, first), "object {n}");
    }
    assert_eq!(scene.objects[9].name, "objects[0] (two_materials.obj: Panel) copy (0,0,1)");
}

fn ply_scene(file: &str, smooth: Option<bool>) -> String {
    let smooth = smooth.map_or(String::new(), |s| format!("smooth = {s}\n"));
    format!("[[objects]]\ntype = \"mesh\"\nmaterial = \"white\"\nfile = \"{file}\"\n{smooth}")
}

#[test]
fn smooth_normals_are_area_weighted() {
    let scene = load(&scene_with(&format!(
        "{}{}{}{}",
        ply_scene("cube.ply", None),
        ply_scene("cube.ply", Some(true)),
        ply_scene("cube.ply", Some(false)),
        ply_scene("cube.ply", Some(true)),
    )));
    let (plain, smooth) = (mesh_of(&scene, 0), mesh_of(&scene, 1));
    assert!(plain.normals.is_none());
    assert!(Arc::ptr_eq(plain, mesh_of(&scene, 2)));
    assert!(Arc::ptr_eq(smooth, mesh_of(&scene, 3)));
    assert_eq!((smooth.positions.len(), smooth.indices.len()), (8, 12));
    let normals = smooth.normals.as_ref().unwrap();
    // The quads are fan-triangulated from their first vertex. Vertex 0 = (0,0,0) is in both
    // triangles of the x = 0 and y = 0 faces (weight 2 each) but in one triangle of the z = 0
    // face "3 7 4 0" (weight 1): (−2, −2, −1) / 3.
    assert_close(normals[0], DVec3::new(-2.0, -2.0, -1.0) / 3.0);
    // Vertex 6 = (1,1,1): both triangles of z = 1 ("1 5 6 2"), one of x = 1 and of y = 1.
    assert_close(normals[6], DVec3::new(1.0, 1.0, 2.0) / 6f64.sqrt());
    assert_eq!(embray::scene::area_weighted_normals(&smooth.positions, &smooth.indices), *normals);
}

#[test]
fn smooth_false_drops_the_file_normals() {
    let scene = load(&scene_with(
        "[[objects]]\ntype = \"mesh\"\nfile = \"two_materials.obj\"\nsmooth = false\n\
         [[objects]]\ntype = \"mesh\"\nfile = \"two_materials.obj\"\n\
         [[objects]]\ntype = \"mesh\"\nfile = \"two_materials.obj\"\nsmooth = true\n",
    ));
    assert!(mesh_of(&scene, 0).normals.is_none());
    assert_eq!(mesh_of(&scene, 2).normals.as_ref().unwrap()[0], DVec3::Z);
    // The file has normals: smooth = true is the file's mesh itself.
    assert!(Arc::ptr_eq(mesh_of(&scene, 2), mesh_of(&scene, 4)));
}

// ---------------------------------------------------------------------------------------
// PLY
// ---------------------------------------------------------------------------------------

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
    let dir = std::env::temp_dir().join(format!("embray-ply-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
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
    std::fs::remove_dir_all(&dir).unwrap();
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

/// The course's PLY files in `shared/` beside the repository; `None` (with a message) when
/// they are not there.
fn course_data() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/ceng795");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipping: the course data {} is absent", dir.display());
        None
    }
}

#[test]
fn course_ply_files_load() {
    let Some(dir) = course_data() else { return };
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
        if !path.exists() {
            eprintln!("skipping {}: absent", path.display());
            continue;
        }
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

// ---------------------------------------------------------------------------------------
// Lights
// ---------------------------------------------------------------------------------------

#[test]
fn new_light_types() {
    let scene = load(&scene_with(
        "[[objects]]\ntype = \"mesh\"\nmaterial = \"white\"\nfile = \"cube.ply\"\n\
         [[lights]]\ntype = \"directional\"\ndirection = [0, -2, 0]\nirradiance = [3, 3, 3]\n\
         [[lights]]\ntype = \"ambient\"\nradiance = [0.1, 0.2, 0.3]\n\
         [[lights]]\ntype = \"sphere\"\ncenter = [0, 5, 0]\nradius = 0.5\nemission = [20, 20, 20]\n\
         transform = [{ translate = [1, 0, 0] }]\n\
         [[lights]]\ntype = \"mesh\"\nfile = \"cube.ply\"\nemission = [2, 1, 0]\n\
         transform = [{ scale = 0.1 }]\n",
    ));
    assert_eq!(
        scene.lights,
        [
            LightDesc::Directional { direction: DVec3::NEG_Y, irradiance: Vec3::splat(3.0) },
            LightDesc::Ambient { radiance: Vec3::new(0.1, 0.2, 0.3) },
        ]
    );
    assert_eq!(scene.objects.len(), 3);
    let sphere = &scene.objects[1];
    assert_eq!(sphere.name, "lights[2] (sphere light)");
    assert_eq!(sphere.shape, ShapeDesc::Sphere { center: DVec3::new(0.0, 5.0, 0.0), radius: 0.5 });
    assert_eq!(sphere.world_from_object, DAffine3::from_translation(DVec3::X));
    let lamp = &scene.materials[sphere.material as usize];
    assert_eq!((lamp.albedo, lamp.emission), (Vec3::ZERO, Vec3::splat(20.0)));
    let mesh_light = &scene.objects[2];
    assert_eq!(mesh_light.name, "lights[3] (mesh light) (cube.ply)");
    assert_eq!(scene.materials[mesh_light.material as usize].emission, Vec3::new(2.0, 1.0, 0.0));
    // The same file as objects[0]: one mesh.
    assert!(Arc::ptr_eq(mesh_of(&scene, 0), mesh_of(&scene, 2)));
}

// ---------------------------------------------------------------------------------------
// Bundled scenes
// ---------------------------------------------------------------------------------------

fn bundled(name: &str) -> SceneDesc {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes").join(name);
    let scene = scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.camera.width <= 320 && scene.camera.height <= 240, "{name}");
    assert!(scene.settings.spp <= 64, "{name}");
    scene
}

fn specular_objects(scene: &SceneDesc) -> impl Iterator<Item = &MaterialDesc> {
    scene.objects.iter().map(|o| &scene.materials[o.material as usize])
}

#[test]
fn every_bundled_scene_loads() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    names.sort();
    for name in [
        "dof_spheres.toml",
        "moving_boxes.toml",
        "glossy_plates.toml",
        "glass.toml",
        "instances.toml",
        "textured_instances.toml",
    ] {
        assert!(names.iter().any(|n| n == name), "{name} missing from {names:?}");
    }
    for name in &names {
        let scene = scene::load(&dir.join(name)).unwrap_or_else(|e| panic!("{e}"));
        assert!(!scene.objects.is_empty(), "{name}");
    }
}

#[test]
fn dof_spheres_focuses_with_an_f_number() {
    let scene = bundled("dof_spheres.toml");
    assert!(scene.camera.aperture > 0.0);
    let focus = scene.camera.focus_distance.unwrap();
    let spheres: Vec<f64> = scene
        .objects
        .iter()
        .filter_map(|o| match o.shape {
            ShapeDesc::Sphere { center, .. } => {
                Some(o.world_from_object.transform_point3(center).distance(scene.camera.lookfrom))
            }
            _ => None,
        })
        .collect();
    assert!(spheres.len() >= 5);
    // The focus is on one of the spheres' centres, with nearer and farther ones.
    assert!(spheres.iter().any(|d| (d - focus).abs() < 1e-6 * focus), "{spheres:?} {focus}");
    assert!(spheres.iter().any(|&d| d < focus * 0.7) && spheres.iter().any(|&d| d > focus * 1.4));
}

#[test]
fn moving_boxes_move() {
    let scene = bundled("moving_boxes.toml");
    let moving: Vec<_> = scene.objects.iter().filter(|o| o.is_moving()).collect();
    assert_eq!(moving.len(), 3);
    let [translating, rotating, scaling] = moving[..] else { panic!() };
    let (a, b) = (translating.world_from_object, translating.world_from_object_end.unwrap());
    assert_eq!(a.matrix3, b.matrix3);
    assert_ne!(a.translation, b.translation);
    let (a, b) = (rotating.world_from_object, rotating.world_from_object_end.unwrap());
    assert!((a.matrix3.determinant() - b.matrix3.determinant()).abs() < 1e-9);
    assert_ne!(a.matrix3, b.matrix3);
    let (a, b) = (scaling.world_from_object, scaling.world_from_object_end.unwrap());
    assert!((a.matrix3.determinant() - b.matrix3.determinant()).abs() > 0.1);
}

#[test]
fn glossy_plates_are_conductors_of_increasing_roughness() {
    let scene = bundled("glossy_plates.toml");
    let mut roughness: Vec<f32> = specular_objects(&scene)
        .filter(|m| matches!(m.specular, SpecularDesc::Conductor { .. }))
        .map(|m| m.roughness)
        .collect();
    roughness.dedup();
    assert_eq!(roughness, [0.02, 0.08, 0.2, 0.4]);
    let emitters = specular_objects(&scene).filter(|m| m.emission != Vec3::ZERO).count();
    assert!(emitters >= 2);
}

#[test]
fn glass_has_absorbing_dielectrics_on_a_checker_floor() {
    let scene = bundled("glass.toml");
    let glass: Vec<_> = specular_objects(&scene)
        .filter(|m| matches!(m.specular, SpecularDesc::Dielectric { absorption, .. } if absorption != Vec3::ZERO))
        .collect();
    assert!(glass.len() >= 2);
    assert!(specular_objects(&scene).any(|m| matches!(
        m.texture.as_ref().map(|t| &t.pattern),
        Some(PatternDesc::Checker2d { .. })
    )));
}

#[test]
fn instances_share_one_mesh() {
    let scene = bundled("instances.toml");
    // Objects per distinct mesh.
    let mut uses: std::collections::HashMap<*const MeshData, usize> = Default::default();
    for object in &scene.objects {
        if let ShapeDesc::Mesh(mesh) = &object.shape {
            *uses.entry(Arc::as_ptr(mesh)).or_default() += 1;
        }
    }
    let shared = uses.values().copied().max().unwrap_or(0);
    assert!(shared >= 1000, "{shared}");
    assert!(scene.objects.iter().any(|o| matches!(o.shape, ShapeDesc::Sphere { .. })
        && scene.materials[o.material as usize].emission != Vec3::ZERO));
}

#[test]
fn textured_instances_use_a_solid_checker() {
    let scene = bundled("textured_instances.toml");
    let textured: Vec<_> = scene
        .objects
        .iter()
        .filter(|o| {
            matches!(
                scene.materials[o.material as usize].texture.as_ref().map(|t| &t.pattern),
                Some(PatternDesc::Checker3d { .. })
            )
        })
        .collect();
    assert!(textured.len() >= 10);
    // An ellipsoid (non-uniform scale) and a translated sphere.
    assert!(textured.iter().any(|o| {
        let m = o.world_from_object.matrix3;
        (m.x_axis.length() - m.y_axis.length()).abs() > 0.1
    }));
    assert!(textured.iter().any(|o| o.world_from_object.translation != DVec3::ZERO));
}
