//! Mitsuba's emitters, sensors, transforms and settings read as Mitsuba reads them: what
//! embray renders as Mitsuba does is accepted with Mitsuba's meaning, what it cannot is
//! refused by name.

use super::common::assert_contains;
use super::load_mitsuba;
use super::reader::{SENSOR, close, files};
use embray::scene::{LightDesc, SceneDesc};
use glam::{DVec3, Vec3};

/// A scene of the reader tests' sensor with `body` (and `integrator`).
fn scene_text(integrator: &str, body: &str) -> String {
    format!(
        "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" \
         value=\"40\"/>\n{integrator}{SENSOR}\n{body}\n</scene>"
    )
}

/// The scene and its warnings, or the error's message.
fn load(name: &str, text: &str) -> Result<(SceneDesc, Vec<String>), String> {
    let path = files(name, text, &[]);
    let (mut scenes, warnings) =
        embray::scene::xml::load_with_warnings(&path, &[]).map_err(|e| e.to_string())?;
    Ok((scenes.remove(0).scene, warnings))
}

#[track_caller]
fn refused(name: &str, text: &str) -> String {
    match load(name, text) {
        Ok(_) => panic!("{name}: expected an error"),
        Err(message) => message,
    }
}

#[test]
fn a_rotation_about_an_axis_not_of_unit_length_is_mitsubas_matrix_with_a_warning() {
    let body = "<shape type=\"cube\"><transform name=\"to_world\">\n\
                <rotate x=\"1\" y=\"1\" z=\"0\" angle=\"90\"/></transform></shape>";
    let (scene, warnings) = load("mitsuba-rotate-axis", &scene_text("", body)).unwrap();
    // Mitsuba's c·I + (1 − c)·a·aᵀ + s·[a]× with a = (1, 1, 0), not normalised: at 90° the
    // columns are (1, 1, −1), (1, 1, 1), (1, −1, 0).
    let m = scene.objects[0].world_from_object.matrix3;
    let near = |a: DVec3, b: DVec3| assert!((a - b).abs().max_element() < 1e-12, "{a} != {b}");
    near(m.col(0), DVec3::new(1.0, 1.0, -1.0));
    near(m.col(1), DVec3::new(1.0, 1.0, 1.0));
    near(m.col(2), DVec3::new(1.0, -1.0, 0.0));
    let [warning] = &warnings[..] else { panic!("one warning expected: {warnings:?}") };
    assert_contains(warning, &["main.xml", "line 17", "not of unit length"]);
    // A unit axis is the rotation, unwarned.
    let body = body.replace("y=\"1\" z=\"0\"", "y=\"0\" z=\"0\"");
    let (scene, warnings) = load("mitsuba-rotate-unit", &scene_text("", &body)).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    close(scene.objects[0].world_from_object.matrix3.col(1), DVec3::Z);
}

#[test]
fn a_directional_emitter_refuses_a_scale_and_takes_a_six_digit_rotation() {
    let emitter = |ops: &str| {
        format!(
            "<emitter type=\"directional\"><transform name=\"to_world\">{ops}</transform>\
             </emitter>"
        )
    };
    let scaled = emitter("<scale value=\"3\"/><lookat origin=\"0,0,0\" target=\"-1,-2,-0.5\"/>");
    let message = refused("mitsuba-dir-scaled", &scene_text("", &scaled));
    assert_contains(&message, &["main.xml", "(line 16)", "directional", "must not scale"]);
    let rotation = emitter(
        "<matrix value=\"0.707107 0 0.707107 0  0 1 0 0  -0.707107 0 0.707107 0  0 0 0 1\"/>",
    );
    let (scene, _) = load("mitsuba-dir-rotated", &scene_text("", &rotation)).unwrap();
    let [LightDesc::Directional(sun)] = &scene.lights[..] else { panic!("{:?}", scene.lights) };
    assert!((sun.direction - DVec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-6);
    // Without one, Mitsuba's irradiance of 1.
    assert_eq!(sun.irradiance, glam::Vec3::ONE);
}

#[test]
fn a_spot_takes_a_uniform_scale_and_refuses_a_stretch() {
    let spot = |scale: &str| {
        format!(
            "<emitter type=\"spot\"><transform name=\"to_world\"><scale {scale}/>\
             <lookat origin=\"1, 4, 2\" target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform>\
             <float name=\"cutoff_angle\" value=\"25\"/></emitter>"
        )
    };
    let message = refused("mitsuba-spot-stretch", &scene_text("", &spot("x=\"2\"")));
    assert_contains(&message, &["main.xml", "(line 16)", "spot", "not non-uniformly"]);
    let (scene, _) = load("mitsuba-spot-scaled", &scene_text("", &spot("value=\"2\""))).unwrap();
    let [LightDesc::Spot(light)] = &scene.lights[..] else { panic!("{:?}", scene.lights) };
    close(light.position, DVec3::new(1.0, 4.0, 2.0));
    close(light.direction, -DVec3::new(1.0, 4.0, 2.0).normalize());
    // A mirror turns a projected image over in Mitsuba; embray's would not turn.
    let image = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/mitsuba/noise_8x8.png");
    let texture = format!(
        "<texture type=\"bitmap\" name=\"texture\"><string name=\"filename\" \
         value=\"{image}\"/></texture></emitter>"
    );
    let mirrored = spot("x=\"-1\"").replace("</emitter>", &texture);
    let message = refused("mitsuba-spot-mirror", &scene_text("", &mirrored));
    assert_contains(&message, &["(line 16)", "spot emitter's to_world mirrors"]);
    // A projector's irradiance would scale with its to_world in Mitsuba.
    let projector = spot("value=\"2\"").replace("type=\"spot\"", "type=\"projector\"");
    let projector = projector.replace("<float name=\"cutoff_angle\" value=\"25\"/>", "");
    let message = refused("mitsuba-projector-scaled", &scene_text("", &projector));
    assert_contains(&message, &["(line 16)", "projector emitter's to_world must not scale"]);
}

#[test]
fn a_spot_clamps_its_beam_to_the_cutoff_and_takes_a_cutoff_up_to_180() {
    let spot =
        |angles: &str| format!("<emitter type=\"spot\">{angles}</emitter><shape type=\"cube\"/>");
    let float = |name: &str, value: f64| format!("<float name=\"{name}\" value=\"{value}\"/>");
    let wide = spot(&(float("cutoff_angle", 20.0) + &float("beam_width", 30.0)));
    let (scene, _) = load("mitsuba-spot-beam", &scene_text("", &wide)).unwrap();
    let [LightDesc::Spot(light)] = &scene.lights[..] else { panic!("{:?}", scene.lights) };
    assert_eq!((light.coverage_degrees, light.falloff_degrees), (40.0, 40.0));
    let (scene, _) =
        load("mitsuba-spot-100", &scene_text("", &spot(&float("cutoff_angle", 100.0)))).unwrap();
    let [LightDesc::Spot(light)] = &scene.lights[..] else { panic!("{:?}", scene.lights) };
    assert_eq!((light.coverage_degrees, light.falloff_degrees), (200.0, 150.0));
    let message =
        refused("mitsuba-spot-190", &scene_text("", &spot(&float("cutoff_angle", 190.0))));
    assert_contains(&message, &["main.xml", "(line 16)", "cutoff_angle 190", "<= 180"]);
}

#[test]
fn max_depth_0_renders_black_as_in_mitsuba_and_says_so() {
    let integrator = "<integrator type=\"path\"><integer name=\"max_depth\" value=\"0\"/>\
                      </integrator>";
    let body = "<shape type=\"cube\"><emitter type=\"area\"/></shape><emitter type=\"constant\"/>";
    let (scene, warnings) = load("mitsuba-md0", &scene_text(integrator, body)).unwrap();
    // embray's depth 0 shows only what the camera sees emitting; hidden, nothing is left.
    assert_eq!((scene.settings.max_depth, scene.settings.hide_emitters), (0, true));
    let [warning] = &warnings[..] else { panic!("one warning expected: {warnings:?}") };
    assert_contains(warning, &["main.xml", "line 3", "max_depth = 0", "black"]);
}

#[test]
fn an_envmap_and_a_constant_are_refused_as_two_environment_emitters() {
    let image = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/mitsuba/noise_8x8.png");
    let body = format!(
        "<emitter type=\"envmap\"><string name=\"filename\" value=\"{image}\"/></emitter>\n\
         <emitter type=\"constant\"/>"
    );
    let message = refused("mitsuba-env-const", &scene_text("", &body));
    assert_contains(
        &message,
        &["main.xml", "(line 17)", "one environment emitter (envmap or constant)"],
    );
}

#[test]
fn convert_refuses_the_aovs_of_an_aov_integrator_rather_than_drop_them() {
    let integrator = "<integrator type=\"aov\"><string name=\"aovs\" value=\"a:albedo\"/>\
                      <integrator type=\"path\"/></integrator>";
    let (scene, _) = load("mitsuba-aov-convert", &scene_text(integrator, "")).unwrap();
    let dir = std::env::temp_dir().join("embray-aov-convert-meshes");
    let mut writer = embray::scene::toml_writer::TomlWriter::new(dir.clone());
    let error = writer.toml(&scene, &dir.join("s.toml"), "test").unwrap_err().to_string();
    assert_contains(&error, &["render settings", "AOVs 'albedo'", "aov integrator"]);
}

#[test]
fn a_parameter_given_twice_with_d_is_refused() {
    let path = files("mitsuba-define-twice", &scene_text("", ""), &[]);
    let message = load_mitsuba(&path, &[("spp", "2"), ("spp", "3")]).unwrap_err();
    assert_contains(&message, &["-D spp=3", "`spp` is given twice", "first as 2"]);
    load_mitsuba(&path, &[("spp", "2"), ("fov", "30")]).unwrap();
}

/// Mitsuba's environment map looks along +z at its centre (embray's own along −z), and its
/// `to_world` turns it: a camera looking along +z sees the map's centre column.
#[test]
fn an_envmap_is_oriented_as_in_mitsuba() {
    // 8 × 4 texels: the two centre columns (u ≈ 0.5) red, the rest blue.
    let mut map = image::RgbImage::from_pixel(8, 4, image::Rgb([0, 0, 255]));
    for y in 0..4 {
        map.put_pixel(3, y, image::Rgb([255, 0, 0]));
        map.put_pixel(4, y, image::Rgb([255, 0, 0]));
    }
    let seen = |rotation: &str| {
        let main = format!(
            r#"<scene version="3.0.0">
    <sensor type="perspective">
        <float name="fov" value="5"/>
        <transform name="to_world"><lookat origin="0, 0, 0" target="0, 0, 1" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
        <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film>
    </sensor>
    <emitter type="envmap"><string name="filename" value="sky.png"/>{rotation}</emitter>
</scene>"#
        );
        let path = files("mitsuba-envmap", &main, &[]);
        map.save(path.parent().unwrap().join("sky.png")).unwrap();
        let scene = load_mitsuba(&path, &[]).unwrap();
        let o = super::common::options(&scene, super::common::backends()[0], 4);
        super::common::film_mean(&super::common::render_ok(&scene, &o).film)
    };
    let ahead = seen("");
    assert!(ahead.x > 0.5 && ahead.z < 0.01, "{ahead}");
    let turned = seen(r#"<transform name="to_world"><rotate y="1" angle="180"/></transform>"#);
    assert!(turned.z > 0.5 && turned.x < 0.01, "{turned}");
    // An exporter's rotation, written to six digits (its columns 3e-7 off unit length), is
    // the rotation it stands for.
    let exact = seen(r#"<transform name="to_world"><rotate y="1" angle="-45"/></transform>"#);
    let written = seen(
        r#"<transform name="to_world"><matrix value="0.707107 0 -0.707107 0  0 1 0 0  0.707107 0 0.707107 0  0 0 0 1"/></transform>"#,
    );
    assert!((written - exact).abs().max_element() < 1e-6, "{written} vs {exact}");
    assert!(exact.x > 0.0 && exact.x < ahead.x, "the test turns the map: {exact} vs {ahead}");
}

/// A spot light or projector without `to_world` sits where Mitsuba's identity puts it: at
/// the origin, shining along +z.
#[test]
fn spot_and_projector_without_to_world_shine_from_the_origin_along_z() {
    let main = format!(
        r#"<scene version="3.0.0"><default name="spp" value="1"/><default name="fov" value="40"/>{SENSOR}
    <emitter type="spot"><rgb name="intensity" value="2"/></emitter>
    <emitter type="projector"/>
</scene>"#
    );
    let scene = load_mitsuba(&files("mitsuba-spot-identity", &main, &[]), &[]).unwrap();
    let [LightDesc::Spot(spot), LightDesc::Projector(projector)] = &scene.lights[..] else {
        panic!("{:?}", scene.lights)
    };
    close(spot.position, DVec3::ZERO);
    close(spot.direction, DVec3::Z);
    assert_eq!(spot.intensity, Vec3::splat(2.0));
    close(projector.position, DVec3::ZERO);
    close(projector.direction, DVec3::Z);
    close(projector.up, DVec3::Y);
}

/// An area emitter's radiance as a texture: a checkerboard's colours are radiances (above 1
/// taken, below 0 refused), and a `rawconstant` is a constant radiance, not a texture.
#[test]
fn an_area_emitters_textured_radiance_is_read_as_a_radiance() {
    let lamp = |radiance: &str| {
        scene_text(
            "",
            &format!("<shape type=\"sphere\"><emitter type=\"area\">{radiance}</emitter></shape>"),
        )
    };
    let checker = r#"<texture type="checkerboard" name="radiance"><rgb name="color0" value="10, 8, 6"/></texture>"#;
    let (scene, _) = load("checker_lamp.xml", &lamp(checker)).unwrap();
    let lamp_material = &scene.materials[scene.objects[0].material as usize];
    assert_eq!(lamp_material.emission, Vec3::ONE);
    let texture = lamp_material.emission_texture.as_ref().expect("a textured radiance");
    let embray::scene::Pattern::Checker2d { even, odd, .. } = texture.pattern else {
        panic!("{:?}", texture.pattern)
    };
    assert_eq!((even, odd), (Vec3::new(10.0, 8.0, 6.0), Vec3::splat(0.2)));
    let negative = checker.replace("10, 8, 6", "-1, 0, 0");
    assert_contains(&refused("negative_lamp.xml", &lamp(&negative)), &["radiance must be >= 0"]);
    let constant = r#"<texture type="rawconstant" name="radiance"><rgb name="value" value="3, 2, 1"/></texture>"#;
    let (scene, _) = load("constant_lamp.xml", &lamp(constant)).unwrap();
    let lamp_material = &scene.materials[scene.objects[0].material as usize];
    assert_eq!(lamp_material.emission, Vec3::new(3.0, 2.0, 1.0));
    assert!(lamp_material.emission_texture.is_none());
}
