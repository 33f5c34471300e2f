//! The `<film>` and `<sampler>` of a sensor: what they ask of the render is read (the
//! sampler's seed too), and what embray would otherwise drop unseen is refused with its
//! line, as Mitsuba refuses a property it does not read.

use super::common::assert_contains;
use super::load_mitsuba;
use super::reader::{SENSOR, files};
use embray::scene::SceneDesc;

/// The scene of `SENSOR` with `film` added to its film and `sampler` to its sampler.
fn with(name: &str, film: &str, sampler: &str) -> Result<SceneDesc, String> {
    with_kinds(name, ("hdrfilm", film), ("independent", sampler))
}

/// `with`, the film and the sampler of the types given.
fn with_kinds(
    name: &str,
    (film_kind, film): (&str, &str),
    (sampler_kind, sampler): (&str, &str),
) -> Result<SceneDesc, String> {
    let sensor = SENSOR
        .replace("hdrfilm", film_kind)
        .replace("\"independent\"", &format!("\"{sampler_kind}\""))
        .replace("<rfilter", &format!("{film}<rfilter"))
        .replace("</sampler>", &format!("{sampler}</sampler>"));
    let main = format!(
        "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" \
         value=\"40\"/>{sensor}\n</scene>"
    );
    load_mitsuba(&files(name, &main, &[]), &[])
}

/// The sampler's seed is the scene's (what `--seed` overrides); without one it is 0.
#[test]
fn the_samplers_seed_is_the_scenes() {
    assert_eq!(with("m-seed-none", "", "").unwrap().settings.seed, 0);
    let seeded = with("m-seed", "", "<integer name=\"seed\" value=\"7\"/>").unwrap();
    assert_eq!(seeded.settings.seed, 7);
    let options = embray::render::RenderOptions::for_scene(&seeded);
    assert_eq!(options.seed, 7, "the render's seed");
    let message = with("m-seed-neg", "", "<integer name=\"seed\" value=\"-1\"/>").unwrap_err();
    assert_contains(&message, &["seed is -1, but must be 0 to 4294967295", "(line 9)"]);
}

/// Every sampler Mitsuba has is read, with its own parameters (`jitter` false: samples at
/// their strata's centres, as `--no-jitter`); another type, or a parameter the type does
/// not take, is refused.
#[test]
fn sampler_types_and_parameters_are_read_or_refused() {
    for (kind, extra) in [
        ("stratified", "<boolean name=\"jitter\" value=\"false\"/>"),
        ("multijitter", "<boolean name=\"jitter\" value=\"true\"/>"),
        ("orthogonal", "<integer name=\"strength\" value=\"2\"/>"),
        ("ldsampler", "<integer name=\"seed\" value=\"3\"/>"),
    ] {
        let name = format!("m-sampler-{kind}");
        let scene = with_kinds(&name, ("hdrfilm", ""), (kind, extra)).unwrap();
        let (seed, jitter) = (if kind == "ldsampler" { 3 } else { 0 }, kind != "stratified");
        let read = (scene.settings.spp, scene.settings.seed, scene.settings.jitter);
        assert_eq!(read, (1, seed, jitter), "{kind}");
        let options = embray::render::RenderOptions::for_scene(&scene);
        assert_eq!(options.jitter, jitter, "{kind}: the render's jitter");
    }
    let typo = with("m-sampler-typo", "", "<integer name=\"sead\" value=\"3\"/>").unwrap_err();
    assert_contains(
        &typo,
        &["the independent sampler does not take `sead` (it takes: sample_count, seed)"],
    );
    let jitter = with("m-sampler-jit", "", "<boolean name=\"jitter\" value=\"true\"/>");
    assert_contains(&jitter.unwrap_err(), &["does not take `jitter`", "(line 9)"]);
}

/// The sampler's type is Mitsuba's name for it.
#[test]
fn an_unknown_sampler_type_is_refused() {
    let message = with_kinds("m-sampler-sobol", ("hdrfilm", ""), ("sobol", "")).unwrap_err();
    assert_contains(&message, &["the sampler type 'sobol' is not one of Mitsuba's", "(line 9)"]);
}

/// The film's output settings are Mitsuba's names (checked, not used: the outputs are
/// embray's); a misspelt parameter or value, a second filter or another film type is
/// refused.
#[test]
fn film_parameters_are_checked() {
    let settings = "<string name=\"pixel_format\" value=\"RGBA\"/><string \
                    name=\"component_format\" value=\"float32\"/><string name=\"file_format\" \
                    value=\"openexr\"/><boolean name=\"sample_border\" value=\"true\"/>\
                    <boolean name=\"compensate\" value=\"true\"/><string name=\"banner\" \
                    value=\"no\"/>";
    let scene = with("m-film-ok", settings, "").unwrap();
    assert_eq!((scene.camera.width, scene.camera.height), (32, 24));
    let cases = [
        ("<integer name=\"widht\" value=\"8\"/>", "the hdrfilm film does not take `widht`"),
        ("<string name=\"pixel_format\" value=\"rgbw\"/>", "pixel_format must be one of"),
        ("<boolean name=\"sample_border\" value=\"1\"/>", "'1' is not true or false"),
        ("<rfilter type=\"tent\"/>", "a film takes one <rfilter>"),
        ("<integer name=\"file_format\" value=\"1\"/>", "`file_format` must be a <string>"),
        ("<bsdf type=\"diffuse\"/>", "the hdrfilm film does not take a <bsdf>"),
    ];
    for (i, (film, expected)) in cases.into_iter().enumerate() {
        let message = with(&format!("m-film-{i}"), film, "").unwrap_err();
        assert_contains(&message, &[expected, "main.xml"]);
    }
    let message = with_kinds("m-film-spec", ("specfilm", ""), ("independent", "")).unwrap_err();
    assert_contains(&message, &["the film type 'specfilm' is not supported (hdrfilm is)"]);
}

/// A nested filter may carry a name, as in Mitsuba; a second film or sampler is refused, as
/// Mitsuba refuses it (the last one won).
#[test]
fn one_film_and_one_sampler_a_sensor_and_a_named_filter() {
    let named = with("m-film-named", "", "").map(|_| ());
    assert_eq!(named, Ok(()));
    let main = |sensor: String| {
        format!(
            "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default \
             name=\"fov\" value=\"40\"/>{sensor}\n</scene>"
        )
    };
    let filter = SENSOR.replace("<rfilter type=\"box\"/>", "<rfilter type=\"tent\" name=\"f\"/>");
    let scene = load_mitsuba(&files("m-film-rfilter-name", &main(filter), &[]), &[]).unwrap();
    assert_eq!(scene.settings.filter, embray::sampling::filter::PixelFilter::Tent { radius: 1.0 });
    for tag in ["sampler", "film"] {
        let opening = format!("<{tag} type=");
        let end = SENSOR.find(&format!("</{tag}>")).unwrap() + tag.len() + 3;
        let start = SENSOR.find(&opening).unwrap();
        let twice = SENSOR.replacen(&SENSOR[start..end], &SENSOR[start..end].repeat(2), 1);
        let message = load_mitsuba(&files(&format!("m-two-{tag}"), &main(twice), &[]), &[]);
        assert_contains(&message.unwrap_err(), &[&format!("a sensor takes one <{tag}>")]);
    }
}

/// A mirroring `to_world` is read as a mirrored camera (its image: `mirrored_camera` in
/// `suite`), which `embray convert` writes and reads back.
#[test]
fn a_mirrored_camera_converts_to_toml_and_back() {
    let mirrored = SENSOR.replace("<lookat ", "<scale x=\"-1\"/><lookat ");
    assert_ne!(mirrored, SENSOR, "the sensor has a lookat to mirror");
    let main = format!(
        "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" \
         value=\"40\"/>{mirrored}\n<shape type=\"cube\"/>\n</scene>"
    );
    let path = files("m-mirrored-camera", &main, &[]);
    let scene = load_mitsuba(&path, &[]).unwrap();
    assert!(scene.camera.mirrored);
    assert_eq!(super::converted(&path, &scene).camera, scene.camera);
}
