//! The course's SphericalDirectionalLight (hw5): an `<Image>` read as a latitude-longitude
//! radiance map. The pack's own maps (grace-new.exr, pisa_latlong.exr) are missing, so these
//! scenes use a generated map: a mirror sphere reflects the texel hw5.tex's mapping puts in
//! the reflected direction, the sky is seen where rays leave, and the scene converts to
//! TOML unchanged.

use super::*;
use embray::film::Film;
use embray::scene::{Environment, EnvironmentMap};
use glam::Vec3;

/// 9 × 5 texels (odd, so that the directions used below are inside texels, not on their
/// edges), each a distinct colour.
fn texel(col: u32, row: u32) -> Vec3 {
    Vec3::new(0.1 + col as f32, 0.2 + row as f32, 0.5 + (col * 5 + row) as f32 * 0.25)
}

fn environment_scene(name: &str, lights: &str) -> crate::common::command::TempPath {
    let (w, h) = (9, 5);
    let mut film = Film::new(w, h);
    for row in 0..h {
        for col in 0..w {
            film.color[(row * w + col) as usize] = texel(col, row);
        }
    }
    let xml = format!(
        r#"<Scene>
    <BackgroundColor>0 0 0</BackgroundColor>
    <MaxRecursionDepth>4</MaxRecursionDepth>
    <Cameras>
        <Camera id="1" type="lookAt">
            <Position>0 0 0</Position>
            <GazePoint>6 0 0</GazePoint>
            <Up>0 1 0</Up>
            <FovY>40</FovY>
            <NearDistance>1</NearDistance>
            <ImageResolution>9 9</ImageResolution>
            <ImageName>mirror.exr</ImageName>
        </Camera>
    </Cameras>
    <VertexData>6 0 0</VertexData>
    <Materials>
        <Material id="1" type="mirror">
            <AmbientReflectance>0 0 0</AmbientReflectance>
            <DiffuseReflectance>0 0 0</DiffuseReflectance>
            <SpecularReflectance>0 0 0</SpecularReflectance>
            <MirrorReflectance>1 1 1</MirrorReflectance>
            <PhongExponent>1</PhongExponent>
        </Material>
    </Materials>
    <Textures>
        <Images>
            <Image id="3">sky.exr</Image>
        </Images>
    </Textures>
    <Lights>
{lights}
    </Lights>
    <Objects>
        <Sphere id="1"><Center>1</Center><Radius>2</Radius><Material>1</Material></Sphere>
    </Objects>
</Scene>
"#
    );
    let path = temp_scene(name, &xml);
    embray::output::write_exr(&film, &path.with_file_name("sky.exr")).unwrap();
    path
}

const SKY: &str =
    "<SphericalDirectionalLight id=\"1\"><ImageId>3</ImageId></SphericalDirectionalLight>";

#[test]
fn a_mirror_sphere_reflects_the_map_where_the_course_mapping_puts_it() {
    let path = environment_scene("environment-mirror", SKY);
    let (cameras, _) = ceng795::load_with_warnings(&path).unwrap();
    let scene = &cameras[0].scene;
    match &scene.lights[..] {
        [
            LightDesc::Environment(Environment {
                map: EnvironmentMap::Image(image),
                scale,
                mapping,
                world_from_map,
                ..
            }),
        ] => {
            assert_eq!(*world_from_map, glam::DMat3::IDENTITY);
            assert_eq!(*mapping, embray::scene::EnvironmentMapping::LatLong);
            assert_eq!((image.width, image.height, image.hdr), (9, 5, true));
            assert_eq!(*scale, Vec3::ONE);
        }
        other => panic!("one environment light, got {other:?}"),
    }
    for backend in BackendKind::compiled() {
        let film = render(scene, &course_options(scene, backend)).unwrap().film;
        // The centre ray meets the sphere head-on and comes straight back along −x:
        // u = (1 + atan2(−1, 0)/π)/2 = 1/4 → column 2 of 9; v = acos(0)/π = 1/2 → row 2 of 5.
        assert_eq!(film.pixel(4, 4), texel(2, 2), "{backend:?}: the reflection");
        // A corner ray leaves the scene and sees the sky in its direction.
        let corner = film.pixel(8, 0);
        // Right is +z (gaze × up), up is +y.
        let d = {
            let half = (20f64).to_radians().tan();
            let (u, v) = ((8.5 / 9.0 * 2.0 - 1.0) * half, (1.0 - 0.5 / 9.0 * 2.0) * half);
            DVec3::new(1.0, v, u).normalize()
        };
        let u = 0.5 * (1.0 + d.x.atan2(-d.z) / std::f64::consts::PI);
        let v = d.y.acos() / std::f64::consts::PI;
        let expected = texel((u * 9.0) as u32, (v * 5.0) as u32);
        assert_eq!(corner, expected, "{backend:?}: the sky at the top-right corner");
    }
}

#[test]
fn a_light_probe_is_read_as_an_angular_map() {
    let probe = "<SphericalDirectionalLight id=\"1\" type=\"probe\"><ImageId>3</ImageId></SphericalDirectionalLight>";
    let path = environment_scene("environment-probe", probe);
    let (cameras, _) = ceng795::load_with_warnings(&path).unwrap();
    let scene = &cameras[0].scene;
    assert!(matches!(
        &scene.lights[..],
        [LightDesc::Environment(Environment {
            mapping: embray::scene::EnvironmentMapping::Probe,
            ..
        })]
    ));
    for backend in BackendKind::compiled() {
        let film = render(scene, &course_options(scene, backend)).unwrap().film;
        // The reflection goes back along −x: a quarter turn from the probe's centre (−z),
        // half-way to its rim on the left: (a, b) = (−1/2, 0) → u = 1/4 → column 2 of 9,
        // v = 1/2 → row 2 of 5.
        assert_eq!(film.pixel(4, 4), texel(2, 2), "{backend:?}: the reflection");
    }
}

#[test]
fn environment_scenes_convert_to_toml_unchanged() {
    for (name, lights) in [
        ("environment-convert", SKY.to_owned()),
        ("environment-convert-probe", SKY.replace("id=\"1\"", "id=\"1\" type=\"probe\"")),
    ] {
        convert_round_trip(name, &lights);
    }
}

fn convert_round_trip(name: &str, lights: &str) {
    let path = environment_scene(name, lights);
    let (cameras, _) = ceng795::load_with_warnings(&path).unwrap();
    let scene = &cameras[0].scene;
    let toml = path.with_file_name("scene.toml");
    let mut writer = embray::scene::toml_writer::TomlWriter::new(path.with_file_name("meshes"));
    writer.write(scene, &toml, "round trip").unwrap();
    let back = embray::scene::load(&toml).unwrap();
    assert_eq!(back.lights, scene.lights);
    let backend = BackendKind::default_compiled();
    let a = render(scene, &course_options(scene, backend)).unwrap().film;
    let b = render(&back, &course_options(&back, backend)).unwrap().film;
    assert_eq!(a.color, b.color);
}

#[test]
fn environment_light_errors_name_the_element() {
    let undefined = environment_scene(
        "environment-undefined",
        "<SphericalDirectionalLight id=\"1\"><ImageId>4</ImageId></SphericalDirectionalLight>",
    );
    let err = ceng795::load_with_warnings(&undefined).unwrap_err().to_string();
    assert_contains(&err, &["scene.xml", "image id 4 is not defined; images: 3", "line"]);
    let twice = environment_scene("environment-twice", &format!("{SKY}\n{SKY}"));
    let err = ceng795::load_with_warnings(&twice).unwrap_err().to_string();
    assert_contains(&err, &["scene.xml", "one SphericalDirectionalLight"]);
    let cube = environment_scene(
        "environment-cube",
        "<SphericalDirectionalLight id=\"1\" type=\"cube\"><ImageId>3</ImageId></SphericalDirectionalLight>",
    );
    let err = ceng795::load_with_warnings(&cube).unwrap_err().to_string();
    assert_contains(
        &err,
        &["environment map type cube is not supported (expected latlong or probe)"],
    );
}
