//! `blendbsdf`: read with Mitsuba's conventions (its weight the second BSDF's share,
//! required; `twosided` reaching its parts), rendered as the weighted sum of its parts, and
//! kept by `embray convert` (TOML `type = "blend"`).

use super::common::{assert_contains, backends, options, render_ok};
use super::load_mitsuba;
use super::reader::{SENSOR, files};
use embray::scene::{Opacity, SceneDesc};
use glam::Vec3;

fn scene_with(name: &str, bsdf: &str) -> Result<SceneDesc, String> {
    let main = format!(
        "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" \
         value=\"40\"/>{SENSOR}\n<shape type=\"cube\">{bsdf}</shape>\n\
         <emitter type=\"constant\"><rgb name=\"radiance\" value=\"1\"/></emitter>\n</scene>"
    );
    load_mitsuba(&files(name, &main, &[]), &[])
}

fn diffuse(rgb: &str) -> String {
    format!("<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"{rgb}\"/></bsdf>")
}

const BLEND: &str = "<bsdf type=\"twosided\"><bsdf type=\"blendbsdf\">\
    <float name=\"weight\" value=\"0.25\"/>";

#[test]
fn a_blend_reads_its_weight_and_two_materials_and_twosided_reaches_them() {
    let bsdf =
        format!("{BLEND}{}{}</bsdf></bsdf>", diffuse("0.8, 0.2, 0.2"), diffuse("0.2, 0.2, 0.8"));
    let scene = scene_with("m-blend", &bsdf).unwrap();
    let material = &scene.materials[scene.objects[0].material as usize];
    let blend = material.blend.as_deref().expect("a blend");
    assert_eq!(blend.weight, Opacity::Constant(0.25));
    assert_eq!(blend.materials[0].albedo, Vec3::new(0.8, 0.2, 0.2));
    assert_eq!(blend.materials[1].albedo, Vec3::new(0.2, 0.2, 0.8));
    assert!(blend.materials.iter().all(|m| !m.one_sided), "twosided reaches the parts");
}

#[test]
fn a_blend_of_two_diffuse_materials_renders_as_their_weighted_mean() {
    let bsdf =
        format!("{BLEND}{}{}</bsdf></bsdf>", diffuse("0.8, 0.2, 0.2"), diffuse("0.2, 0.2, 0.8"));
    let blended = scene_with("m-blend-render", &bsdf).unwrap();
    let mean = format!("<bsdf type=\"twosided\">{}</bsdf>", diffuse("0.65, 0.2, 0.35"));
    let mixed = scene_with("m-blend-mean", &mean).unwrap();
    for backend in backends() {
        let image = |scene: &SceneDesc| render_ok(scene, &options(scene, backend, 16)).film.color;
        let (a, b) = (image(&blended), image(&mixed));
        let (sum_a, sum_b): (Vec3, Vec3) = (a.iter().sum(), b.iter().sum());
        assert!(sum_a.min_element() > 0.0, "the cube is lit");
        // Same random numbers, same directions: equal but for rounding.
        let difference =
            a.iter().zip(&b).map(|(p, q)| (*p - *q).abs().max_element()).fold(0.0, f32::max);
        assert!(difference < 1e-4, "{backend:?}: largest difference {difference}");
        assert!((sum_a - sum_b).abs().max_element() < 1e-4 * sum_b.max_element());
    }
}

#[test]
fn a_blend_without_weight_or_with_three_bsdfs_is_refused() {
    let missing = format!("<bsdf type=\"blendbsdf\">{}{}</bsdf>", diffuse("1"), diffuse("0"));
    let message = scene_with("m-blend-noweight", &missing).unwrap_err();
    assert_contains(&message, &["the property `weight` is missing", "(line 15)"]);
    let three = format!(
        "<bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"0.5\"/>{}{}{}</bsdf>",
        diffuse("1"),
        diffuse("0"),
        diffuse("0.5")
    );
    let message = scene_with("m-blend-three", &three).unwrap_err();
    assert_contains(&message, &["blendbsdf takes two nested <bsdf>s", "(line 15)"]);
}

#[test]
fn a_blend_converts_to_toml_and_back() {
    let bsdf =
        format!("{BLEND}{}{}</bsdf></bsdf>", diffuse("0.8, 0.2, 0.2"), diffuse("0.2, 0.2, 0.8"));
    let scene = scene_with("m-blend-convert", &bsdf).unwrap();
    let dir = super::common::command::temp_dir("blend-convert");
    let mut writer = embray::scene::toml_writer::TomlWriter::new(dir.join("meshes"));
    let toml = dir.join("scene.toml");
    writer.write(&scene, &toml, "round trip").unwrap();
    let back = embray::scene::load(&toml).unwrap_or_else(|e| panic!("{e}"));
    let material = |s: &SceneDesc| s.materials[s.objects[0].material as usize].clone();
    let (before, after) = (material(&scene), material(&back));
    let (before, after) = (before.blend.unwrap(), after.blend.unwrap());
    assert_eq!(after.weight, before.weight);
    for (a, b) in after.materials.iter().zip(&before.materials) {
        assert_eq!((a.albedo, a.specular, a.one_sided), (b.albedo, b.specular, b.one_sided));
    }
}

#[test]
fn a_toml_blend_that_contains_itself_is_refused() {
    let dir = super::common::command::temp_dir("blend-cycle");
    let toml = dir.join("scene.toml");
    let text = "[camera]\nlookfrom = [0, 0, 5]\nlookat = [0, 0, 0]\nvfov = 40\nresolution = [8, 8]\n\n\
                [materials.a]\ntype = \"blend\"\nweight = 0.5\nmaterials = [\"b\", \"red\"]\n\n\
                [materials.b]\ntype = \"blend\"\nweight = 0.5\nmaterials = [\"red\", \"a\"]\n\n\
                [materials.red]\nalbedo = [0.8, 0.1, 0.1]\n\n\
                [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"a\"\n";
    std::fs::write(&toml, text).unwrap();
    let message = embray::scene::load(&toml).unwrap_err().to_string();
    assert_contains(&message, &["a → b → a", "scene.toml", "line"]);
    let two = text.replace("materials = [\"b\", \"red\"]", "materials = [\"red\"]");
    std::fs::write(&toml, two).unwrap();
    let message = embray::scene::load(&toml).unwrap_err().to_string();
    assert_contains(&message, &["materials.a.materials", "1 names", "two names"]);
}
