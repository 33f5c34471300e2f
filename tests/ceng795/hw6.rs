//! Fall 2022 hw6 and hw5 against the instructor's references: BRDF scenes, direct-lighting
//! and path-traced boxes (EXR means), and the photographic tone mapping of every EXR/PNG pair.

use super::reference_scenes::*;
use super::*;
use embray::choice::Choice;
use embray::shading::bsdf::Energy;

/// hw6's BRDF scenes (`2022/hw6/brdf`): one gold sphere lit by two point lights under each of
/// the course's reflectance models. Some references are kept aside from the data set (see
/// SOURCES-2022.md); those scenes still render on every backend and their images must agree.
#[test]
#[cfg_attr(not(course_data), ignore = "needs the CENG795 packs at ../shared/data/ceng795")]
fn hw6_brdf_scenes_match_the_course_images() {
    let data = data_dir();
    let outputs = data.join("2022/hw6/brdf/outputs");
    let (mut rows, mut failures, mut compared) = (Vec::new(), Vec::new(), 0);
    for xml in xml_files(&data.join("2022/hw6/brdf/inputs")) {
        let name = relative(&data, &xml);
        let cameras = ceng795::load(&xml).unwrap_or_else(|e| panic!("{name}: {e}"));
        for camera in &cameras {
            let tag = format!("{name} → {}", camera.image_name);
            let scene = &camera.scene;
            let images = render_on_every_backend(&tag, scene);
            let Ok(reference) = read_rgb(&outputs.join(&camera.image_name)) else {
                println!(
                    "{tag}: reference kept aside from the data set; rendered on every backend"
                );
                continue;
            };
            compared += 1;
            let mut row = Row {
                name: tag.clone(),
                resolution: (scene.camera.width, scene.camera.height),
                spp: scene.settings.spp,
                results: Vec::new(),
                note: "",
            };
            for (backend, image, seconds) in images {
                let c = compare_images(&image, &reference, 3).unwrap();
                if c.fraction_within() < MIN_WITHIN {
                    let kept = keep(&format!("{tag}_{}", backend.name()), &image, &c);
                    failures.push(format!(
                        "{tag} on {}: {:.3} % within 3/255, mean abs error {:.3}/255; render and \
                         heat map in {}",
                        backend.name(),
                        100.0 * c.fraction_within(),
                        c.mean_abs_error,
                        kept.display()
                    ));
                }
                row.results.push((backend, seconds, c));
            }
            rows.push(row);
        }
    }
    print_table(&rows);
    assert!(compared >= 5, "expected the five BRDF references, compared {compared}");
    assert!(failures.is_empty(), "BRDF scenes below the threshold:\n{}", failures.join("\n"));
}

/// hw6's direct-lighting Cornell boxes (point, mesh, sphere and ellipsoid lights; diffuse and
/// normalized-Phong walls) against the instructor's linear EXRs (100 spp). Rendered at 4 spp
/// to stay quick: the mean of each channel must lie within 1 % of the reference's. (At the
/// reference's 100 spp ours differs from itself by RMSE 0.002 across seeds while it differs
/// from the reference by 0.13: the reference's own noise, fireflies up to 38 next to the
/// ceiling light, dominates any per-pixel comparison.)
#[test]
#[cfg_attr(not(course_data), ignore = "needs the CENG795 packs at ../shared/data/ceng795")]
fn hw6_direct_lighting_means_match_the_course_exrs() {
    let compared =
        exr_means_match("2022/hw6/directLighting", |_| false, |_| 0.01, Energy::Conserving);
    assert!(compared >= 4, "expected the direct-lighting references, compared {compared}");
}

/// Renders every camera of the XMLs in `pack`/inputs that has a reference EXR in
/// `pack`/outputs (and that `skip` does not name) at 4 spp on every backend, and checks the
/// mean of each channel within `tolerance(xml name)` of the reference's; returns how many
/// references were compared.
fn exr_means_match(
    pack: &str,
    skip: fn(&str) -> bool,
    tolerance: fn(&str) -> f64,
    energy: Energy,
) -> usize {
    let data = data_dir();
    let outputs = data.join(pack).join("outputs");
    let mut compared = 0;
    for xml in xml_files(&data.join(pack).join("inputs")) {
        let name = relative(&data, &xml);
        for camera in ceng795::load(&xml).unwrap_or_else(|e| panic!("{name}: {e}")) {
            let tag = format!("{name} → {}", camera.image_name);
            if skip(&camera.image_name) {
                continue;
            }
            let path = outputs.join(&camera.image_name);
            let Ok(reference) = embray::bench::convergence::read_reference(&path) else {
                println!("{tag}: reference kept aside from the data set");
                continue;
            };
            compared += 1;
            let mean =
                |c: &[glam::Vec3]| c.iter().map(|v| v.as_dvec3()).sum::<DVec3>() / c.len() as f64;
            let expected = mean(&reference.color);
            for backend in BackendKind::compiled() {
                let mut options = course_options(&camera.scene, backend);
                options.spp = 4;
                options.energy = energy;
                let start = Instant::now();
                let got = mean(&render(&camera.scene, &options).unwrap().film.color);
                let seconds = start.elapsed().as_secs_f64();
                let relative = (got - expected).abs() / expected;
                println!(
                    "{tag} on {}: mean {got:.4} vs {expected:.4}, off by {:.2} % ({} spp, \
                     {seconds:.2} s)",
                    backend.name(),
                    100.0 * relative.max_element(),
                    options.spp
                );
                let limit = tolerance(&name);
                assert!(relative.max_element() <= limit, "{tag} on {}", backend.name());
            }
        }
    }
    compared
}

/// Pairs of the 2022 packs whose PNG is not the photographic operator applied to its EXR
/// with its XML's parameters, with the fraction within 2/255 measured and why.
const TONEMAP_MISMATCH: &[(&str, f64, &str)] = &[
    ("glass.exr", 0.13, "matches 100 % with δ = 1e-7 and no burn-out, not its XML's 0.18 1"),
    ("glass_russian.exr", 0.85, "matches 100 % with δ = 3e-7, key 0.15, no burn-out"),
    ("glass_importance_russian.exr", 0.94, "like glass_russian: other parameters than its XML's"),
];

/// The value of the first `<tag>` after `from` in `text`, before `</Camera>`.
fn camera_field<'t>(text: &'t str, from: usize, tag: &str) -> Option<&'t str> {
    let camera = &text[from..text[from..].find("</Camera>").map_or(text.len(), |e| from + e)];
    let open = format!("<{tag}>");
    let start = camera.find(&open)? + open.len();
    Some(camera[start..].split('<').next()?.trim())
}

/// `embray tonemap`'s operator on every EXR/PNG pair of the 2022 packs, with each camera's
/// `<Tonemap>` parameters from its XML: ≥ 99 % of pixels within 2/255.
#[test]
#[cfg_attr(not(course_data), ignore = "needs the CENG795 packs at ../shared/data/ceng795")]
fn photographic_tone_mapping_reproduces_the_course_pngs() {
    use embray::output::Photographic;
    let data = data_dir().join("2022");
    let mut exrs: Vec<PathBuf> = Vec::new();
    let mut stack = vec![data.clone()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap().flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "exr")
                && path.with_extension("png").exists()
            {
                exrs.push(path);
            }
        }
    }
    exrs.sort();
    let xml_texts: Vec<String> =
        xml_files(&data).iter().map(|p| std::fs::read_to_string(p).unwrap()).collect();
    let mut failures = Vec::new();
    for exr in &exrs {
        let name = exr.file_name().unwrap().to_string_lossy().into_owned();
        let tag = format!("<ImageName>{name}</ImageName>");
        let (text, at) = xml_texts
            .iter()
            .find_map(|t| t.find(&tag).map(|at| (t, at)))
            .unwrap_or_else(|| panic!("{name}: no camera writes it"));
        // The camera element starts before its ImageName; its Tonemap follows or precedes
        // it, so search from the camera's start.
        let start = text[..at].rfind("<Camera").unwrap();
        let number = |tag| camera_field(text, start, tag).map(|v| v.parse::<f32>().unwrap());
        let options: Vec<f32> = camera_field(text, start, "TMOOptions")
            .unwrap()
            .split_whitespace()
            .map(|v| v.parse().unwrap())
            .collect();
        let p = Photographic {
            key: options[0],
            burn_out: options[1],
            saturation: number("Saturation").unwrap_or(1.0),
            gamma: number("Gamma").unwrap_or(2.2),
        };
        let film = embray::bench::convergence::read_reference(exr).unwrap();
        let ours = RgbImage::from_raw(film.width, film.height, p.to_rgb8(&film.color)).unwrap();
        let reference = read_rgb(&exr.with_extension("png")).unwrap();
        let c = compare_images(&ours, &reference, 2).unwrap();
        let within = c.fraction_within();
        let allowed = TONEMAP_MISMATCH.iter().find(|(n, _, _)| *n == name);
        println!(
            "{name}: {:.3} % within 2/255, mean abs error {:.3}/255 ({p:?}){}",
            100.0 * within,
            c.mean_abs_error,
            allowed.map_or(String::new(), |(_, _, why)| format!("; {why}"))
        );
        let required = allowed.map_or(0.99, |(_, floor, _)| *floor);
        if within < required {
            failures.push(format!("{name}: {:.3} % within 2/255", 100.0 * within));
        }
    }
    assert!(exrs.len() >= 20, "expected the packs' EXR/PNG pairs, found {}", exrs.len());
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// hw6's path-traced Cornell boxes (`<Renderer>PathTracing`) against the instructor's
/// 100-spp EXRs: the mean of each channel within 1 %, rendered at 4 spp. Cameras with
/// RussianRoulette are rendered but not compared: the course's roulette has no depth limit
/// and its references carry fireflies (RMSE 9–86 against means near 1) that make their
/// means unreliable. The glass sphere's material adds the course's specular term (ks 0.3,
/// normalized modified Phong) to Fresnel reflection and refraction. The course adds it on
/// top (its glass returns up to 1.3 times what arrives); by default ours takes the lobe's
/// share from Fresnel's, which keeps long paths finite and leaves the glass box 2.0–2.5 %
/// darker than the course's references (3 % allowed there). `Energy::Additive`, the
/// course's own model, matches all of them within 1 %.
#[test]
#[cfg_attr(not(course_data), ignore = "needs the CENG795 packs at ../shared/data/ceng795")]
fn hw6_path_tracing_means_match_the_course_exrs() {
    let pack = "2022/hw6/pathTracing";
    let roulette = |image: &str| image.contains("russian");
    let tolerance = |xml: &str| if xml.contains("glass") { 0.03 } else { 0.01 };
    let compared = exr_means_match(pack, roulette, tolerance, Energy::Conserving);
    assert!(compared >= 4, "expected the path-tracing references, compared {compared}");
    let compared = exr_means_match(pack, roulette, |_| 0.01, Energy::Additive);
    assert!(compared >= 4, "expected the path-tracing references, compared {compared}");
}

/// hw5's `cube_directional` (an ambient and a directional light on a cube and a floor):
/// the `DirectionalLight` import against the instructor's image.
#[test]
#[cfg_attr(not(course_data), ignore = "needs the CENG795 packs at ../shared/data/ceng795")]
fn hw5_directional_light_scene_matches_the_course_image() {
    let data = data_dir();
    let cameras = ceng795::load(&data.join("2022/hw5/inputs/cube_directional.xml")).unwrap();
    let reference = read_rgb(&data.join("2022/hw5/outputs/cube_directional.png")).unwrap();
    let scene = &cameras[0].scene;
    assert!(scene.lights.iter().any(|l| matches!(l, LightDesc::Directional(_))));
    for backend in BackendKind::compiled() {
        let (image, _) = render_rgb(scene, &course_options(scene, backend));
        let c = compare_images(&image, &reference, 3).unwrap();
        // Measured: 99.9989 % within 3/255 (7 of 640,000 pixels off, on the cube's edges).
        assert!(c.fraction_within() >= 0.999, "{}: {c:?}", backend.name());
    }
}

/// hw6's Veach Ajar (Bitterli's door scene, 382,624 triangles, an area light behind the
/// door): the direct-lighting camera (1280×720, 1 spp) against the instructor's image on every
/// backend, and the 2500-spp path-traced camera, which has no reference in the pack, rendered
/// small (160×90, 4 spp) on every backend, which must agree.
#[test]
#[cfg_attr(not(course_data), ignore = "needs the CENG795 packs at ../shared/data/ceng795")]
fn hw6_veach_ajar_direct_lighting_matches_and_the_path_camera_renders() {
    let data = data_dir().join("2022/hw6/veach-ajar");
    let cameras = ceng795::load(&data.join("inputs/scene.xml")).unwrap();
    assert_eq!(cameras.len(), 2, "the direct and the path-traced camera");
    let direct = &cameras[0];
    assert_eq!(direct.image_name, "VeachAjar_direct.png");
    let reference = read_rgb(&data.join("outputs/VeachAjar_direct.png")).unwrap();
    for (backend, image, seconds) in render_on_every_backend("VeachAjar_direct", &direct.scene) {
        let c = compare_images(&image, &reference, 3).unwrap();
        // Direct light reaches little of the room (a strip of floor and the door's edge), so
        // the image is mostly black, and at 1 spp each lit pixel sees one random point of the
        // area light in both renders: judge the lit region by the total light it receives
        // and by 16×16 block means.
        let total = |i: &RgbImage| {
            i.pixels().map(|p| p.0.iter().map(|&v| v as f64).sum::<f64>()).sum::<f64>()
        };
        let ratio = total(&image) / total(&reference);
        let blocks = |i: &RgbImage| embray::compare::downsample_box(i, 16);
        let b = compare_images(&blocks(&image), &blocks(&reference), 3).unwrap();
        println!(
            "VeachAjar_direct on {}: {:.3} % of pixels within 3/255, total light {ratio:.4} × \
             the reference's, 16×16 blocks {:.3} % within 3/255 (max {}), {seconds:.2} s",
            backend.name(),
            100.0 * c.fraction_within(),
            100.0 * b.fraction_within(),
            b.max_abs_error
        );
        assert!(c.fraction_within() >= MIN_WITHIN, "{}: {c:?}", backend.name());
        // Measured 0.933. Both images are single samples (our linear mean moves 3 % between
        // 1 and 64 spp), and truncation to integers takes more from a less noisy estimator:
        // our solid-angle light samples lose more to it than the course's area samples.
        assert!((ratio - 1.0).abs() < 0.15, "{}: total light {ratio}", backend.name());
        assert!(b.fraction_within() >= 0.99, "{}: {b:?}", backend.name());
    }
    let mut path = cameras[1].scene.clone();
    assert_eq!(path.settings.integrator, embray::scene::IntegratorKind::Path);
    path.camera.width = 160;
    path.camera.height = 90;
    path.settings.spp = 4;
    render_on_every_backend("VeachAjar_path (160×90, 4 spp)", &path);
    // Same viewpoint, same radiance units: indirect light only adds to the direct light.
    let mut small_direct = direct.scene.clone();
    small_direct.camera.width = 160;
    small_direct.camera.height = 90;
    small_direct.settings.spp = 4;
    let mean = |scene: &SceneDesc| {
        let film = render(scene, &course_options(scene, BackendKind::compiled()[0])).unwrap().film;
        film.color.iter().map(|c| c.as_dvec3()).sum::<DVec3>() / film.color.len() as f64
    };
    let (direct_mean, path_mean) = (mean(&small_direct), mean(&path));
    println!("VeachAjar means at 160×90: direct {direct_mean:.4}, path traced {path_mean:.4}");
    assert!(path_mean.cmpgt(direct_mean).all(), "{path_mean} vs {direct_mean}");
}

/// Per pixel against the course's path-traced glass box. Its two NextEventEstimation cameras
/// (glass_next, glass_next_importance: ImportanceSampling changes only the noise) are two
/// independent 100-spp renders of one integral, so their RMSE to each other is √2 × the
/// reference's own noise. Ours, at only 4 spp, must be closer to each of them than that.
/// (Two renders of ours cannot estimate the reference's noise, as the issue suggested: at
/// 100 spp ours differ by RMSE 0.14, the references by 1.26.)
#[test]
#[cfg_attr(not(course_data), ignore = "needs the CENG795 packs at ../shared/data/ceng795")]
fn hw6_glass_box_is_closer_to_each_reference_than_the_references_are_to_each_other() {
    use embray::bench::convergence::{read_reference, rmse};
    let data = data_dir().join("2022/hw6/pathTracing");
    let reference = |name: &str| read_reference(&data.join("outputs").join(name)).unwrap();
    let (next, next_importance) =
        (reference("glass_next.exr"), reference("glass_next_importance.exr"));
    let between_references = rmse(&next, &next_importance);
    let cameras = ceng795::load(&data.join("inputs/cornellbox_jaroslav_path_glass.xml")).unwrap();
    let camera = cameras.iter().find(|c| c.image_name == "glass_next.exr").unwrap();
    for backend in BackendKind::compiled() {
        let mut options = course_options(&camera.scene, backend);
        options.spp = 4;
        let film = render(&camera.scene, &options).unwrap().film;
        let (to_next, to_next_importance) = (rmse(&film, &next), rmse(&film, &next_importance));
        println!(
            "glass box on {} at 4 spp: RMSE {to_next:.4} to glass_next, {to_next_importance:.4} to \
             glass_next_importance; the references are {between_references:.4} apart",
            backend.name()
        );
        // Measured: 0.957 and 1.124 against 1.256.
        assert!(to_next < between_references && to_next_importance < between_references);
    }
}
