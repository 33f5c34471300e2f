//! The new light types, and the bundled scenes that use the newer format.

use super::*;
use embray::scene::{Ambient, Directional};

#[test]
fn new_light_types() {
    let scene = load(&scene_with(
        "[[objects]]\ntype = \"mesh\"\nmaterial = \"white\"\nfile = \"cube.ply\"\n\
         [[lights]]\ntype = \"directional\"\ndirection = [0, -2, 0]\nirradiance = [3, 3, 3]\n\
         [[lights]]\ntype = \"ambient\"\nradiance = [0.1, 0.2, 0.3]\n\
         [[lights]]\ntype = \"sphere\"\ncenter = [0, 5, 0]\nradius = 0.5\nemission = [20, 20, 20]\n\
         two_sided = true\n\
         transform = [{ translate = [1, 0, 0] }]\n\
         [[lights]]\ntype = \"mesh\"\nfile = \"cube.ply\"\nemission = [2, 1, 0]\n\
         transform = [{ scale = 0.1 }]\n",
    ));
    assert_eq!(
        scene.lights,
        [
            LightDesc::Directional(Directional {
                direction: DVec3::NEG_Y,
                irradiance: Vec3::splat(3.0)
            }),
            LightDesc::Ambient(Ambient { radiance: Vec3::new(0.1, 0.2, 0.3) }),
        ]
    );
    assert_eq!(scene.objects.len(), 3);
    let sphere = &scene.objects[1];
    assert_eq!(sphere.name, "lights[2] (sphere light)");
    assert_eq!(sphere.shape, ShapeDesc::Sphere { center: DVec3::new(0.0, 5.0, 0.0), radius: 0.5 });
    assert_eq!(sphere.world_from_object, DAffine3::from_translation(DVec3::X));
    let lamp = &scene.materials[sphere.material as usize];
    assert_eq!((lamp.albedo, lamp.emission), (Vec3::ZERO, Vec3::splat(20.0)));
    assert!(lamp.two_sided_emission);
    let mesh_light = &scene.objects[2];
    assert_eq!(mesh_light.name, "lights[3] (mesh light) (cube.ply)");
    let mesh_lamp = &scene.materials[mesh_light.material as usize];
    assert_eq!(
        (mesh_lamp.emission, mesh_lamp.two_sided_emission),
        (Vec3::new(2.0, 1.0, 0.0), false)
    );
    // The same file as objects[0]: one mesh.
    assert!(Arc::ptr_eq(mesh_of(&scene, 0), mesh_of(&scene, 2)));
}

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
        .filter(|m| matches!(m.specular, Specular::Conductor { .. }))
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
        .filter(|m| matches!(m.specular, Specular::Dielectric { absorption, .. } if absorption != Vec3::ZERO))
        .collect();
    assert!(glass.len() >= 2);
    assert!(specular_objects(&scene).any(|m| matches!(
        m.texture.as_ref().map(|t| &t.pattern),
        Some(Pattern::Checker2d { .. })
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
                Some(Pattern::Checker3d { .. })
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

#[test]
fn a_two_sided_light_survives_the_toml_writer() {
    let scene = load(&scene_with(
        "[[lights]]\ntype = \"sphere\"\ncenter = [0, 5, 0]\nradius = 0.5\nemission = [2, 2, 2]\n\
         two_sided = true\n",
    ));
    let path = data_dir().join("two_sided_back.toml");
    let mut writer = embray::scene::toml_writer::TomlWriter::new(data_dir().join("meshes"));
    let text = writer.toml(&scene, &path, "round trip").unwrap();
    assert!(text.contains("two_sided_emission = true"), "{text}");
    let back = scene::load_str(&text, &path).unwrap();
    let lamp = |s: &SceneDesc| material(s, "lights[0] (sphere light)").clone();
    assert_eq!(lamp(&back), lamp(&scene));
}
