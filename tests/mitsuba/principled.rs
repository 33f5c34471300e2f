//! `principled` and `principledthin` from the XML to the BSDF: the reader's defaults,
//! conversions and refusals, and the BSDF's values against Mitsuba's own
//! (`tests/data/mitsuba/principled_values.txt`, made by
//! `scripts/mitsuba_principled_values.py` with Mitsuba 3.9.1's `llvm_ad_rgb`).

use super::bsdfs::material_of;
use super::common::{assert_contains, repo_path};
use embray::scene::{ParamDesc, Specular, eta_from_specular};
use embray::shading::bsdf::Bsdf;
use embray::shading::material::Material;
use glam::{Mat3, Vec3};

#[test]
fn the_reader_gives_mitsubas_defaults_and_conversions() {
    let m = material_of("p-default", "<bsdf type=\"principled\"/>").unwrap();
    let p = m.principled.as_deref().unwrap();
    assert_eq!((m.albedo, m.specular, m.one_sided), (Vec3::splat(0.5), Specular::None, true));
    assert!(!p.thin && p.roughness == ParamDesc::Constant(0.5));
    // specular 0.5 ↔ R₀ 0.04 ↔ η 1.5.
    assert_eq!(p.eta, ParamDesc::Constant(eta_from_specular(0.5)));
    assert!((eta_from_specular(0.5) - 1.5).abs() < 1e-6);

    // A transmitting interface must bend: specular 0 becomes 10⁻³, η 1 becomes 1.001.
    let no_bend = material_of(
        "p-bend",
        "<bsdf type=\"principled\"><float name=\"specular\" value=\"0\"/>\
         <float name=\"spec_trans\" value=\"0.5\"/></bsdf>",
    )
    .unwrap();
    let eta = no_bend.principled.unwrap().eta;
    assert_eq!(eta, ParamDesc::Constant(eta_from_specular(1e-3)));
    let index_one = material_of(
        "p-eta1",
        "<bsdf type=\"principled\"><float name=\"eta\" value=\"1\"/>\
         <texture name=\"spec_trans\" type=\"checkerboard\"/></bsdf>",
    )
    .unwrap();
    let p = index_one.principled.unwrap();
    assert_eq!(p.eta, ParamDesc::Constant(1.001));
    assert!(matches!(p.spec_trans, ParamDesc::Texture(_)));

    let thin = material_of(
        "p-thin",
        "<bsdf type=\"principledthin\"><texture name=\"base_color\" type=\"checkerboard\"/>\
         <texture name=\"eta\" type=\"checkerboard\"/></bsdf>",
    )
    .unwrap();
    let p = thin.principled.as_deref().unwrap();
    assert!(p.thin && p.transmits() && thin.texture.is_some());
    assert!(matches!(p.eta, ParamDesc::Texture(_)));
}

#[test]
fn out_of_range_and_unknown_parameters_are_refused_with_their_line() {
    let cases = [
        ("<float name=\"roughness\" value=\"1.5\"/>", "roughness is 1.5, but must be in [0, 1]"),
        ("<float name=\"eta\" value=\"0\"/>", "eta is 0, but must be above 0"),
        ("<float name=\"eta\" value=\"1.5\"/><float name=\"specular\" value=\"0.5\"/>", "either"),
        ("<float name=\"diff_trans\" value=\"1\"/>", "does not take `diff_trans`"),
        ("<texture name=\"eta\" type=\"checkerboard\"/>", "principled's eta is a <float>"),
        ("<rgb name=\"base_color\" value=\"1.5, 0, 0\"/>", "a reflectance must be in [0, 1]"),
    ];
    for (i, (inside, expected)) in cases.iter().enumerate() {
        let bsdf = format!("<bsdf type=\"principled\">{inside}</bsdf>");
        let message = material_of(&format!("p-bad-{i}"), &bsdf).unwrap_err();
        assert_contains(&message, &[expected, "(line "]);
    }
    let thin = [
        ("<float name=\"diff_trans\" value=\"2.5\"/>", "diff_trans is 2.5, but must be in [0, 2]"),
        ("<float name=\"metallic\" value=\"0.5\"/>", "does not take `metallic`"),
        ("<float name=\"diffuse_transmittance_sampling_rate\" value=\"-1\"/>", "at least 0"),
    ];
    for (i, (inside, expected)) in thin.iter().enumerate() {
        let bsdf = format!("<bsdf type=\"principledthin\">{inside}</bsdf>");
        let message = material_of(&format!("pt-bad-{i}"), &bsdf).unwrap_err();
        assert_contains(&message, &[expected, "(line "]);
    }
    // Mitsuba's twosided refuses what transmits: the back would be a second front.
    for (i, inner) in ["<bsdf type=\"principledthin\"/>", {
        "<bsdf type=\"principled\"><float name=\"spec_trans\" value=\"0.2\"/></bsdf>"
    }]
    .iter()
    .enumerate()
    {
        let message =
            material_of(&format!("p-2s-{i}"), &format!("<bsdf type=\"twosided\">{inner}</bsdf>"))
                .unwrap_err();
        assert_contains(&message, &["twosided cannot hold a transmitting BSDF", "(line "]);
    }
    let opaque = "<bsdf type=\"twosided\"><bsdf type=\"principled\"/></bsdf>";
    assert!(!material_of("p-2s-ok", opaque).unwrap().one_sided);
}

/// One of Mitsuba's parameter sets as XML, from its `config NAME PLUGIN key=value…` line.
fn bsdf_xml(config: &str) -> (String, String) {
    let mut words = config.split_whitespace().skip(1);
    let (name, plugin) = (words.next().unwrap(), words.next().unwrap());
    let mut xml = format!("<bsdf type=\"{plugin}\">");
    for word in words {
        let (key, value) = word.split_once('=').unwrap();
        let tag = if key == "base_color" { "rgb" } else { "float" };
        xml += &format!("<{tag} name=\"{key}\" value=\"{value}\"/>");
    }
    (name.to_owned(), xml + "</bsdf>")
}

#[track_caller]
fn close(what: &str, ours: f32, mitsubas: f32) {
    // f32 arithmetic in a different order (embray's GGX keeps its own isotropic form).
    let tolerance = 1e-4 * ours.abs().max(mitsubas.abs()) + 1e-6;
    assert!((ours - mitsubas).abs() <= tolerance, "{what}: {ours} vs Mitsuba's {mitsubas}");
}

#[test]
fn eval_and_pdf_match_mitsubas_own_values() {
    let text = std::fs::read_to_string(repo_path("tests/data/mitsuba/principled_values.txt"))
        .expect("tests/data/mitsuba/principled_values.txt");
    let mut current: Option<(String, Material)> = None;
    let mut checked = 0;
    let mut nonzero = 0;
    for line in text.lines() {
        if line.starts_with("config ") {
            let (name, xml) = bsdf_xml(line);
            let desc = material_of(&format!("p-values-{name}"), &xml).unwrap();
            current = Some((name, Material::from_desc(&desc)));
            continue;
        }
        let n: Vec<f32> = line.split_whitespace().map(|w| w.parse().unwrap()).collect();
        let (name, material) = current.as_ref().expect("a config line first");
        // Mitsuba's wi is the view (embray's wo), its wo the light (embray's wi). Render
        // space is Mitsuba's local frame; embray's shading frame faces the view, turned
        // over (a rotation) when the view is behind.
        let (view, light) = (Vec3::new(n[0], n[1], n[2]), Vec3::new(n[3], n[4], n[5]));
        let front_face = view.z > 0.0;
        let frame = if front_face {
            Mat3::IDENTITY
        } else {
            Mat3::from_diagonal(Vec3::new(1.0, -1.0, -1.0))
        };
        let principled = material.principled.as_deref().unwrap();
        let params = principled.at(material.albedo, |_| unreachable!("constants only"));
        let bsdf = Bsdf::principled(&params, frame, front_face, material.one_sided);
        let (value, pdf) = bsdf.eval(view, light);
        let what = format!("{name}: view {view}, light {light}");
        for c in 0..3 {
            close(&format!("{what}, channel {c}"), value[c], n[6 + c]);
        }
        close(&format!("{what}, pdf"), pdf, n[9]);
        checked += 1;
        nonzero += usize::from(n[6] > 0.0 && n[9] > 0.0);
    }
    assert!(checked >= 200 && nonzero >= 100, "{checked} pairs, {nonzero} lit");
}

/// `embray convert` keeps both models, textured weights (above 1 too) and rates included.
#[test]
fn principled_materials_convert_to_toml_and_back() {
    let checker = |name: &str, a: f32, b: f32| {
        format!(
            "<texture name=\"{name}\" type=\"checkerboard\"><float name=\"color0\" value=\"{a}\"/>\
             <float name=\"color1\" value=\"{b}\"/></texture>"
        )
    };
    let solid = format!(
        "<bsdf type=\"principled\"><rgb name=\"base_color\" value=\"0.2, 0.8, 0.1\"/>\
         <float name=\"roughness\" value=\"0.15\"/>{}{}<float name=\"specular\" value=\"0.7\"/>\
         <float name=\"clearcoat_sampling_rate\" value=\"0.5\"/></bsdf>",
        checker("metallic", 0.7, 0.1),
        checker("clearcoat", 0.9, 0.1),
    );
    let thin = format!(
        "<bsdf type=\"principledthin\">{}{}<float name=\"eta\" value=\"1.33\"/>\
         <float name=\"diffuse_transmittance_sampling_rate\" value=\"2\"/></bsdf>",
        checker("diff_trans", 0.4, 1.4),
        checker("base_color", 0.2, 0.6).replace("float", "rgb"),
    );
    for (name, bsdf) in [("p-toml-solid", solid), ("p-toml-thin", thin)] {
        let main = format!(
            "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" \
             value=\"40\"/>{}\n<shape type=\"cube\">{bsdf}</shape>\n</scene>",
            super::reader::SENSOR
        );
        let path = super::reader::files(name, &main, &[]);
        let scene = super::load_mitsuba(&path, &[]).unwrap();
        let back = super::converted(&path, &scene);
        let material =
            |s: &embray::scene::SceneDesc| s.materials[s.objects[0].material as usize].clone();
        assert!(material(&scene).principled.is_some());
        assert_eq!(
            material(&back),
            material(&scene),
            "{}",
            std::fs::read_to_string(path.with_file_name("scene.toml")).unwrap()
        );
    }
}
