//! Every course scene converted to TOML renders as the XML does, meshes still shared.

use super::reference_scenes::{data_dir, render_rgb};
use super::*;
use crate::common::command::temp_dir;

/// Distinct meshes (by `Arc`) of a scene, and how many objects place them.
fn mesh_sharing(scene: &SceneDesc) -> Vec<usize> {
    let mut counts: Vec<(*const embray::scene::MeshData, usize)> = Vec::new();
    for object in &scene.objects {
        if let ShapeDesc::Mesh(mesh) = &object.shape {
            let key = std::sync::Arc::as_ptr(mesh);
            match counts.iter_mut().find(|(k, _)| *k == key) {
                Some((_, n)) => *n += 1,
                None => counts.push((key, 1)),
            }
        }
    }
    let mut out: Vec<usize> = counts.into_iter().map(|(_, n)| n).collect();
    out.sort();
    out
}

#[test]
#[cfg_attr(not(course_data), ignore = "needs the CENG795 packs at ../shared/data/ceng795")]
fn converted_toml_renders_like_the_xml() {
    let data = data_dir();
    let dir = temp_dir("ceng795-convert");
    let scenes = [
        "2021/hw1/simple.xml",
        "2021/hw2/cornellbox_recursive.xml",
        "2024/hw1/inputs/akif_uslu/berserker_smooth.xml",
        "2021/hw3/cornellbox_area.xml",
        "2021/hw3/cornellbox_boxes_dynamic.xml",
        "2021/hw3/ellipsoids.xml",
        "2021/hw3/metal_glass_plates.xml",
        "2021/hw3/spheres_dof.xml",
        "2022/hw4/inputs/wood_box_all.xml",
        "2022/hw4/inputs/cube_waves.xml",
        "2022/hw4/inputs/ellipsoids_texture.xml",
        "2022/hw4/inputs/sphere_nearest_bilinear.xml",
        "2022/hw4/inputs/galactica_static.xml",
        "2022/hw5/inputs/cube_directional.xml",
        "2022/hw6/brdf/inputs/brdf_torrancesparrow.xml",
        "2022/hw6/brdf/inputs/brdf_phong_modified_normalized.xml",
        "2022/hw6/directLighting/inputs/cornellbox_jaroslav_glossy_area.xml",
        "2022/hw6/pathTracing/inputs/cornellbox_jaroslav_path_glass.xml",
    ];
    let mut writer = embray::scene::toml_writer::TomlWriter::new(dir.join("meshes"));
    for name in scenes {
        let xml = data.join(name);
        let (cameras, _) = ceng795::load_with_warnings(&xml).unwrap();
        let mut scene = cameras[0].scene.clone();
        scene.camera.width /= 8;
        scene.camera.height /= 8;
        scene.settings.spp = scene.settings.spp.min(4);
        let toml = dir.join(format!("{}.toml", name.replace('/', "_")));
        writer.write(&scene, &toml, "round trip").unwrap();
        let back = embray::scene::load(&toml).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(back.camera, scene.camera, "{name}");
        assert_eq!(back.settings, scene.settings, "{name}");
        assert_eq!(back.lights, scene.lights, "{name}");
        assert_eq!(back.objects.len(), scene.objects.len(), "{name}");
        assert_eq!(mesh_sharing(&back), mesh_sharing(&scene), "{name}: instancing changed");
        for (a, b) in back.objects.iter().zip(&scene.objects) {
            assert_eq!(a.world_from_object, b.world_from_object, "{name}: {}", b.name);
            assert_eq!(a.world_from_object_end, b.world_from_object_end, "{name}: {}", b.name);
            let (ma, mb) =
                (&back.materials[a.material as usize], &scene.materials[b.material as usize]);
            assert_eq!(
                (ma.albedo, &ma.specular, ma.roughness, ma.emission, &ma.phong),
                (mb.albedo, &mb.specular, mb.roughness, mb.emission, &mb.phong)
            );
            assert_eq!(
                (&ma.texture, &ma.specular_texture, &ma.normal_map, &ma.bump_map),
                (&mb.texture, &mb.specular_texture, &mb.normal_map, &mb.bump_map),
                "{name}: {}",
                b.name
            );
        }
        let backend = BackendKind::default_compiled();
        let (from_xml, _) = render_rgb(&scene, &course_options(&scene, backend));
        let (from_toml, _) = render_rgb(&back, &course_options(&back, backend));
        let c = compare_images(&from_xml, &from_toml, 3).unwrap();
        println!(
            "{name}: {:.3} % within 3/255, mean abs error {:.4}/255",
            100.0 * c.fraction_within(),
            c.mean_abs_error
        );
        // Mesh vertices come back through tobj in f32 (the course data is f32 already, so
        // the images are identical); nothing else changes.
        assert!(c.fraction_within() >= 0.999 && c.mean_abs_error < 0.05, "{name}: {c:?}");
    }
}
