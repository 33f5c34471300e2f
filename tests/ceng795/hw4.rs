//! Fall 2022 hw4 (textures) against the instructor's references: image textures (nearest
//! and bilinear, every decal mode that colours a surface), normal maps, the checkerboard
//! and Perlin noise, on meshes and transformed spheres.

use super::reference_scenes::*;
use super::*;
use embray::choice::Choice;

/// Scenes that need a texture kind not built yet, with the message the loader gives. The
/// test fails when one of them loads (update the list) or when another scene does not.
/// (Empty now: every hw4 scene in the pack loads.)
const NOT_YET: &[(&str, &str)] = &[];

/// Scenes that cannot match pixel for pixel, with the fraction within 3/255 measured (both
/// backends) and why; the test holds them at that level so that a regression shows.
const PARTIAL: &[(&str, f64, &str)] = &[
    (
        "cube_perlin.xml",
        0.63,
        "Perlin noise: the course fixes neither the permutation nor the gradients, so the \
         pattern is another instance of the same noise (measured 63.97 %)",
    ),
    ("sphere_perlin.xml", 0.72, "Perlin noise (measured 72.87 %)"),
    (
        "cube_perlin_bump.xml",
        0.60,
        "Perlin bump map: another instance of the noise, as cube_perlin (measured 61.07 %)",
    ),
    ("sphere_perlin_bump.xml", 0.72, "Perlin bump map (measured 72.99 %)"),
    (
        "ellipsoids_texture.xml",
        0.93,
        "two Perlin-textured ellipsoids; the four image-textured spheres match (measured \
         93.91 %)",
    ),
];

#[test]
#[cfg_attr(not(course_data), ignore = "needs the CENG795 packs at ../shared/data/ceng795")]
fn hw4_texture_scenes_match_the_course_images() {
    let data = data_dir();
    let inputs = data.join("2022/hw4/inputs");
    let outputs = data.join("2022/hw4/outputs");
    let (mut rows, mut failures, mut matched) = (Vec::new(), Vec::new(), 0);
    for xml in xml_files(&inputs) {
        let name = relative(&inputs, &xml);
        let not_yet = NOT_YET.iter().find(|(n, _)| *n == name);
        let cameras = match (ceng795::load(&xml), not_yet) {
            (Ok(cameras), None) => cameras,
            (Err(e), Some((_, why))) => {
                let message = e.to_string();
                assert!(message.contains(why), "{name}: {message}");
                println!("{name}: not rendered: {message}");
                continue;
            }
            (Ok(_), Some(_)) => panic!("{name} loads now: take it off NOT_YET"),
            (Err(e), None) => panic!("{name}: {e}"),
        };
        for camera in &cameras {
            let tag = format!("{name} → {}", camera.image_name);
            let mut scene = camera.scene.clone();
            // Multi-sample scenes (Veach Ajar 16 spp, sphere_normal 100) render at 4 spp
            // here and are compared on 8×8 block means; full-spp figures are in the notes.
            scene.settings.spp = scene.settings.spp.min(4);
            let images = render_on_every_backend(&tag, &scene);
            // References sit in `outputs/` under the scene's own sub-folder.
            let folder = Path::new(&name).parent().unwrap_or(Path::new(""));
            let Ok(reference) = read_rgb(&outputs.join(folder).join(&camera.image_name)) else {
                println!(
                    "{tag}: reference kept aside from the data set; rendered on every backend"
                );
                continue;
            };
            if scene.settings.spp > 1 {
                // A multi-sample reference is noisy: compare 8×8 block means.
                let ours = embray::compare::downsample_box(&images[0].1, 8);
                let theirs = embray::compare::downsample_box(&reference, 8);
                let c = compare_images(&ours, &theirs, 1).unwrap();
                println!(
                    "{tag}: {}×{} at {} spp: 8×8 block means off by {:.3}/255 on average, at most \
                     {}/255 ({:.2} s)",
                    scene.camera.width,
                    scene.camera.height,
                    scene.settings.spp,
                    c.mean_abs_error,
                    c.max_abs_error,
                    images[0].2
                );
                if c.mean_abs_error > 1.0 {
                    failures.push(format!("{tag}: block means off by {:.3}/255", c.mean_abs_error));
                }
                continue;
            }
            let partial = PARTIAL.iter().find(|(n, _, _)| *n == name);
            let mut row = Row {
                name: tag.clone(),
                resolution: (scene.camera.width, scene.camera.height),
                spp: scene.settings.spp,
                results: Vec::new(),
                note: partial.map_or("", |p| p.2),
            };
            for (backend, image, seconds) in images {
                let c = compare_images(&image, &reference, 3).unwrap();
                let required = partial.map_or(MIN_WITHIN, |p| p.1);
                if c.fraction_within() < required {
                    let kept = keep(&format!("{tag}_{}", backend.name()), &image, &c);
                    failures.push(format!(
                        "{tag} on {}: {:.3} % within 3/255 (required {:.1} %); kept in {}",
                        backend.name(),
                        100.0 * c.fraction_within(),
                        100.0 * required,
                        kept.display()
                    ));
                }
                row.results.push((backend, seconds, c));
            }
            matched += partial.is_none() as usize;
            rows.push(row);
        }
    }
    print_table(&rows);
    assert!(matched >= 7, "expected the seven exact texture scenes, matched {matched}");
    assert!(failures.is_empty(), "hw4 scenes below the threshold:\n{}", failures.join("\n"));
}

/// hw4's `bump_mapping_transformed` (its reference is kept aside): a cobblestone floor with
/// BumpFactor 30 under a uniform scale of 0.05 and a leather ellipsoid under a negative
/// scale. Bumps only tilt normals, so the lit image keeps about the brightness of the same
/// scene without them. With heights taken in scene units per unit of uv (the earlier
/// convention) the floor's bumps were far too steep and the image came out about 40 %
/// darker; with the course's texel convention it stays within a few %.
#[test]
#[cfg_attr(not(course_data), ignore = "needs the CENG795 packs at ../shared/data/ceng795")]
fn transformed_bump_maps_keep_the_scene_brightness() {
    let xml = data_dir().join("2022/hw4/inputs/bump_mapping_transformed.xml");
    let camera = ceng795::load(&xml).unwrap().remove(0);
    let mut bumped = camera.scene.clone();
    (bumped.camera.width, bumped.camera.height) = (200, 200);
    let mut flat = bumped.clone();
    let mut removed = 0;
    for material in &mut flat.materials {
        removed += material.bump_map.take().is_some() as usize;
    }
    assert_eq!(removed, 2, "the floor's and the ellipsoid's bump maps");
    let mean = |scene: &SceneDesc| {
        let film = render(scene, &course_options(scene, BackendKind::compiled()[0])).unwrap().film;
        film.color.iter().map(|c| c.as_dvec3()).sum::<DVec3>() / film.color.len() as f64
    };
    let (with_bumps, without) = (mean(&bumped), mean(&flat));
    let ratio = with_bumps / without;
    println!(
        "bump_mapping_transformed at 200²: mean {with_bumps:.3} with bumps, {without:.3} without"
    );
    assert!(ratio.min_element() > 0.9 && ratio.max_element() < 1.1, "ratio {ratio}");
}
