//! Mitsuba's render regression suite (`../shared/data/mitsuba/tests/scenes`): every scene
//! either passes Mitsuba's own rule on both backends at the suite's budget of 2·10⁶ samples
//! per image, or is refused with its unsupported plugin, file and line. And the Mitsuba
//! Cornell box against references Mitsuba rendered (`tests/data/mitsuba/README.md`).

use super::common::{backends, options, render_ok, repo_path};
use super::load_mitsuba;
use embray::bench::convergence::read_reference;
use embray::mitsuba_rule::judge;
use std::path::{Path, PathBuf};

/// The suite's scenes that embray renders; every other one must be refused.
const RENDERED: [&str; 19] = [
    "test_arealight_path",
    "test_bumpmap_path",
    "test_constant_path",
    "test_directional_direct",
    "test_envmap_path",
    "test_mesh_attributes_1_face_direct",
    "test_mesh_attributes_3_face_direct",
    "test_normalmap_identity_roughconductor_path",
    "test_normalmap_path",
    "test_orthographic_path",
    "test_pointlight_path",
    "test_projector_constant_direct",
    "test_roughdielectric_path",
    "test_roughplastic_linear_path",
    "test_spot_direct",
    "test_textured_diffuse_path",
    "test_textured_roughconductor_path",
    "test_texturedprincipled1_path",
    "test_texturedprincipledthin_path",
];

fn mitsuba_data() -> PathBuf {
    repo_path("../shared/data/mitsuba")
}

/// Renders `scene` at the suite's budget on every backend and judges each image.
fn assert_passes(name: &str, scene: &embray::scene::SceneDesc, reference: &Path, variance: &Path) {
    let pixels = scene.camera.width * scene.camera.height;
    let spp = 2_000_000 / pixels;
    let reference = read_reference(reference).unwrap();
    let variance = read_reference(variance).unwrap();
    for backend in backends() {
        let mut o = options(scene, backend, spp);
        o.seed = 0;
        let film = render_ok(scene, &o).film;
        let verdict = judge(&film.color, &reference.color, &variance.color, spp);
        assert!(
            verdict.passes(),
            "{name} on {backend:?}: {} of {} pixel channels pass ({:.3} %)",
            verdict.passing,
            verdict.channels,
            100.0 * verdict.fraction()
        );
    }
}

#[test]
#[cfg_attr(not(mitsuba_data), ignore = "needs Mitsuba's suite at ../shared/data/mitsuba")]
fn every_suite_scene_passes_mitsubas_rule_or_is_refused_by_name() {
    let mut scenes: Vec<PathBuf> = Vec::new();
    for group in std::fs::read_dir(mitsuba_data().join("tests/scenes")).unwrap() {
        for file in std::fs::read_dir(group.unwrap().path()).unwrap() {
            let path = file.unwrap().path();
            if path.extension().is_some_and(|e| e == "xml") {
                scenes.push(path);
            }
        }
    }
    scenes.sort();
    assert!(scenes.len() >= 19, "{} scenes", scenes.len());
    let mut rendered = 0;
    for path in &scenes {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        match load_mitsuba(path, &[]) {
            Ok(scene) => {
                assert!(RENDERED.contains(&name.as_str()), "{name} loads: list it in RENDERED");
                let stem = name.rsplit_once('_').unwrap().0;
                let refs = path.parent().unwrap().join("refs");
                let reference = refs.join(format!("{stem}_ref_rgb.exr"));
                let variance = refs.join(format!("{stem}_ref_rgb_var.exr"));
                assert_passes(&name, &scene, &reference, &variance);
                rendered += 1;
            }
            Err(message) => {
                assert!(!RENDERED.contains(&name.as_str()), "{name}: {message}");
                // The plugin, its file and line, and that it is not supported.
                assert!(
                    message.contains("not supported") && message.contains("(line "),
                    "{name}: {message}"
                );
            }
        }
    }
    assert_eq!(rendered, RENDERED.len());
}

#[test]
#[cfg_attr(not(mitsuba_data), ignore = "needs Mitsuba's Cornell box at ../shared/data/mitsuba")]
fn the_mitsuba_cornell_box_passes_mitsubas_rule() {
    for file in ["cbox", "cbox-rgb"] {
        let path = mitsuba_data().join(format!("scenes/cbox/{file}.xml"));
        let scene = load_mitsuba(&path, &[("res", "48")]).unwrap();
        let refs = repo_path("tests/data/mitsuba");
        let reference = refs.join(format!("{file}_48_ref_rgb.exr"));
        let variance = refs.join(format!("{file}_48_ref_rgb_var.exr"));
        assert_passes(file, &scene, &reference, &variance);
    }
}

/// The rule is not a formality: the Cornell box with one bounce fewer than Mitsuba's
/// `max_depth` counts fails it.
#[test]
#[cfg_attr(not(mitsuba_data), ignore = "needs Mitsuba's Cornell box at ../shared/data/mitsuba")]
fn a_cornell_box_two_bounces_short_fails_the_rule() {
    let path = mitsuba_data().join("scenes/cbox/cbox-rgb.xml");
    let scene = load_mitsuba(&path, &[("res", "48"), ("max_depth", "4")]).unwrap();
    let refs = repo_path("tests/data/mitsuba");
    let reference = read_reference(&refs.join("cbox-rgb_48_ref_rgb.exr")).unwrap();
    let variance = read_reference(&refs.join("cbox-rgb_48_ref_rgb_var.exr")).unwrap();
    let spp = 2_000_000 / (48 * 48);
    let film = render_ok(&scene, &options(&scene, backends()[0], spp)).film;
    let verdict = judge(&film.color, &reference.color, &variance.color, spp);
    assert!(!verdict.passes(), "{verdict:?}");
}

/// Scenes written here with Mitsuba's own renders beside them (`tests/data/mitsuba`, so
/// these run everywhere): a GGX rough conductor with Mitsuba's measured gold under a point
/// light and a constant sky; the disk, the cylinder, a serialized mesh, flipped normals and
/// instances of a shapegroup; a projector, a textured spot light and hidden emitters; a
/// thin lens; a principal point offset on a non-square film, a blendbsdf weighted by a
/// checkerboard on an analytic sphere (Mitsuba's uv), a Beckmann gold, a bitmap mapped by
/// to_uv and mirrored, a spectrum file; area emitters whose radiance is a bitmap or a
/// checkerboard (a rectangle, an analytic sphere, a serialized mesh); an OBJ, a PLY and a
/// serialized mesh without normals, smooth (normals weighted by angle, as Mitsuba's); a
/// rough mirror of GGX α 0.8 in a white furnace (Mitsuba's separable G₁·G₁ shadowing: with
/// embray's height-correlated one, 4 % brighter on the sphere); a normal map seen from
/// behind a twosided rectangle and from inside a glass sphere (Mitsuba's frame on the
/// outward normal: the map was mirrored); a 32² height map's bumps (slopes exact in each
/// cell between texel centres, as Mitsuba's `eval_1_grad`); a coarse smooth sheet and glass
/// sphere whose shading normals lean away from their triangles (the shading normal alone
/// decides the side: 95.9 % of channels passed when the triangle had to agree); meshes
/// mirrored by `to_world`, inside out where Mitsuba computes their normals (49 % passed);
/// tinted glass, smooth, rough and a thin sheet (refused before); `null` surfaces, a bounce
/// on the path (69 % passed without them); an environment map from a Radiance `.hdr` file;
/// bump maps on a smooth low-polygon mesh and a scaled analytic sphere (81.4 % passed when
/// the bumped normal was the triangle's and the sphere's ∂p/∂u scaled twice); a camera
/// whose to_world mirrors, with a principal point offset (refused before; unmirrored, 42 %).
#[test]
fn scenes_written_here_pass_mitsubas_rule() {
    let refs = repo_path("tests/data/mitsuba");
    let names = [
        "rough_gold",
        "shapes",
        "emitters",
        "thinlens",
        "materials",
        "textured_emitters",
        "sdfgrid",
        "smooth_normals",
        "rough_furnace",
        "normalmap_sides",
        "bump_lowres",
        "smooth_sides",
        "mirrored_meshes",
        "glass_tints",
        "null_bsdf",
        "hdr_envmap",
        "bump_smooth_scaled",
        "mirrored_camera",
    ];
    for name in names {
        let scene = load_mitsuba(&refs.join(format!("{name}.xml")), &[]).unwrap();
        let reference = refs.join(format!("{name}_48_ref_rgb.exr"));
        let variance = refs.join(format!("{name}_48_ref_rgb_var.exr"));
        assert_passes(name, &scene, &reference, &variance);
    }
}
