//! Motion, repeat grids, shared mesh files and smooth normals.

use super::*;

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
    assert!(normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-12), "{normals:?}");
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
