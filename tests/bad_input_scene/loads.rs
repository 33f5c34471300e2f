//! Scenes that load: the documented example, every bundled scene, and what they hold.

use super::*;
use embray::scene::Point;

/// The example of the format documentation, with every object type, light type and
/// transform kind.
const EXAMPLE: &str = r#"
[camera]
lookfrom = [278.0, 273.0, -800.0]
lookat = [278.0, 273.0, 0.0]
up = [0.0, 1.0, 0.0]
vfov = 39.3
resolution = [256, 256]
aperture = 0.0
focus_distance = 800.0

[render]
spp = 16
max_depth = 5
background = [0.0, 0.0, 0.0]

[materials.white]
albedo = [0.73, 0.73, 0.73]
emission = [0.0, 0.0, 0.0]

[materials.light]
emission = [4.0, 4.0, 4.0]

[[objects]]
type = "quad"
material = "white"
corner = [0.0, 0.0, 0.0]
u = [555.0, 0.0, 0.0]
v = [0.0, 0.0, 555.0]
transform = [
  { scale = [1.0, 2.0, 1.0] },
  { scale = 2.0 },
  { rotate = { axis = [0.0, 1.0, 0.0], degrees = 15.0 } },
  { translate = [265.0, 0.0, 295.0] },
  { matrix = [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]] },
]

[[objects]]
type = "sphere"
material = "light"
center = [0.0, 0.0, 0.0]
radius = 1.0

[[objects]]
type = "box"
material = "white"
min = [0.0, 0.0, 0.0]
max = [1.0, 1.0, 1.0]

[[objects]]
type = "mesh"
file = "two_materials.obj"

[[lights]]
type = "point"
position = [278.0, 500.0, 278.0]
intensity = [1000.0, 1000.0, 1000.0]

[[lights]]
type = "quad"
corner = [213.0, 548.7, 227.0]
u = [130.0, 0.0, 0.0]
v = [0.0, 0.0, 105.0]
emission = [17.0, 12.0, 4.0]
transform = [{ translate = [0.0, -0.1, 0.0] }]
"#;

#[test]
fn example_scene_with_every_feature_loads() {
    let scene = load(EXAMPLE);
    assert_eq!(scene.source, source());
    assert_eq!((scene.camera.width, scene.camera.height), (256, 256));
    assert_eq!(scene.camera.focus_distance, Some(800.0));
    assert_eq!((scene.settings.spp, scene.settings.max_depth), (16, 5));
    // quad, sphere, box, 2 OBJ models (one per MTL material), quad light.
    let names: Vec<&str> = scene.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "objects[0] (quad)",
            "objects[1] (sphere)",
            "objects[2] (box)",
            "objects[3] (two_materials.obj: Panel)",
            "objects[3] (two_materials.obj: Panel)",
            "lights[1] (quad light)",
        ]
    );
    assert_eq!(
        scene.lights,
        [LightDesc::Point(Point {
            position: DVec3::new(278.0, 500.0, 278.0),
            intensity: Vec3::splat(1000.0)
        })]
    );
    // light, white (the table, sorted by name), the two MTL materials, the quad light's.
    let materials: Vec<&str> = scene.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(
        materials,
        [
            "light",
            "white",
            "two_materials.obj: Red",
            "two_materials.obj: Glow",
            "lights[1] (quad light)"
        ]
    );
    let quad_light = &scene.objects[5];
    let light_material = &scene.materials[quad_light.material as usize];
    assert_eq!(
        (light_material.albedo, light_material.emission),
        (Vec3::ZERO, Vec3::new(17.0, 12.0, 4.0))
    );
    assert_eq!(mesh_of(&scene, 2).indices.len(), 12);
    assert_eq!(mesh_of(&scene, 0).indices.len(), 2);
    assert_eq!(scene.objects[1].shape, ShapeDesc::Sphere { center: DVec3::ZERO, radius: 1.0 });
}

#[test]
fn transform_list_applies_in_listed_order() {
    // Scale y by 2, rotate 90° about +y, translate: the quad's corner+v = (0, 0, 1)
    // → scale (0, 0, 1) → rotate (1, 0, 0) → translate (11, 20, 30).
    let scene = load(&scene_with(
        "[[objects]]\ntype = \"quad\"\nmaterial = \"white\"\ncorner = [0, 0, 0]\nu = [0, 1, 0]\nv = [0, 0, 1]\n\
         transform = [{ scale = [1, 2, 1] }, { rotate = { axis = [0, 1, 0], degrees = 90 } }, { translate = [10, 20, 30] }]\n",
    ));
    let object = &scene.objects[0];
    let mesh = mesh_of(&scene, 0);
    let world = |i: usize| object.world_from_object.transform_point3(mesh.positions[i]);
    assert!((world(3) - DVec3::new(11.0, 20.0, 30.0)).length() < 1e-12, "{}", world(3));
    // corner+u = (0, 1, 0) → (0, 2, 0) → (0, 2, 0) → (10, 22, 30).
    assert!((world(1) - DVec3::new(10.0, 22.0, 30.0)).length() < 1e-12, "{}", world(1));
}

#[test]
fn matrix_transform_is_row_major() {
    let scene = load(&scene_with(&format!(
        "{BOX}transform = [{{ matrix = [[0, -1, 0, 5], [1, 0, 0, 6], [0, 0, 1, 7], [0, 0, 0, 1]] }}]\n"
    )));
    let p = scene.objects[0].world_from_object.transform_point3(DVec3::X);
    assert_eq!(p, DVec3::new(5.0, 7.0, 7.0));
}

#[test]
fn defaults_apply_when_fields_are_absent() {
    let scene = load(&scene_with(BOX));
    assert_eq!(scene.camera.up, DVec3::Y);
    assert_eq!((scene.camera.aperture, scene.camera.focus_distance), (0.0, None));
    assert_eq!(scene.settings, embray::scene::RenderSettings::default());
    assert_eq!(scene.objects[0].world_from_object, glam::DAffine3::IDENTITY);
    let scene = load(&format!("{CAMERA}[materials.plain]\n"));
    assert_eq!(scene.materials[0].albedo, Vec3::splat(0.8));
    assert_eq!(scene.materials[0].emission, Vec3::ZERO);
}

#[test]
fn obj_with_mtl_colours_loads_one_object_per_material() {
    let scene = load(&scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"two_materials.obj\"\n"));
    assert_eq!(scene.objects.len(), 2);
    let material = |i: usize| &scene.materials[scene.objects[i].material as usize];
    assert_eq!(material(0).name, "two_materials.obj: Red");
    assert_eq!((material(0).albedo, material(0).emission), (Vec3::new(0.7, 0.1, 0.1), Vec3::ZERO));
    assert_eq!(material(1).name, "two_materials.obj: Glow");
    assert_eq!((material(1).albedo, material(1).emission), (Vec3::ZERO, Vec3::new(4.0, 3.0, 2.0)));
    for i in 0..2 {
        let mesh = mesh_of(&scene, i);
        assert_eq!(mesh.indices.len(), 1);
        assert_eq!(mesh.normals.as_ref().unwrap()[0], DVec3::Z);
        assert_eq!(mesh.uvs.as_ref().unwrap().len(), mesh.positions.len());
    }
}

#[test]
fn material_in_scene_overrides_the_obj_materials() {
    let scene = load(&scene_with(
        "[[objects]]\ntype = \"mesh\"\nfile = \"two_materials.obj\"\nmaterial = \"white\"\n",
    ));
    assert!(scene.objects.iter().all(|o| scene.materials[o.material as usize].name == "white"));
    assert_eq!(scene.materials.len(), 1);
}

#[test]
fn obj_naming_a_missing_mtl_loads_with_a_warning() {
    let (scene, warnings) = scene::load_str_with_warnings(
        &scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"missing_mtl.obj\"\n"),
        &source(),
    )
    .unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert_contains(&warnings[0], &["missing_mtl.obj", "does_not_exist.mtl"]);
    assert_eq!(scene.objects.len(), 1);
    let material = &scene.materials[scene.objects[0].material as usize];
    assert_eq!((material.albedo, material.emission), (Vec3::splat(0.8), Vec3::ZERO));
}

#[test]
fn scene_file_on_disk_loads_and_resolves_obj_paths() {
    let dir = std::env::temp_dir().join(format!("embray-scene-test-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("models")).unwrap();
    std::fs::copy(data_dir().join("two_materials.obj"), dir.join("models/two_materials.obj"))
        .unwrap();
    std::fs::copy(data_dir().join("two_materials.mtl"), dir.join("models/two_materials.mtl"))
        .unwrap();
    let path = dir.join("on_disk.toml");
    std::fs::write(
        &path,
        scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"models/two_materials.obj\"\n"),
    )
    .unwrap();
    let result = scene::load(&path);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(result.unwrap().objects.len(), 2);
}

#[test]
fn bundled_scenes_load() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let scene = scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
            assert!(!scene.objects.is_empty(), "{}", path.display());
            count += 1;
        }
    }
    assert!(count > 0, "no scenes in {}", dir.display());
}
