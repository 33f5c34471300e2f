//! Small inline scenes' lights: the course's area, directional and spot lights, hw6's
//! object lights, as the course defines them.

use super::inline_scenes::one;
use super::*;
use crate::common::command::temp_dir;
use embray::choice::Choice;
use embray::scene::{Directional, Spot};

/// An invisible area light lights a floor under it (soft shadow sampling) without being
/// seen: the camera looking straight at it sees the background.
#[test]
fn area_lights_light_the_scene_but_are_invisible() {
    let body = r#"
    <VertexData>
        -5 -1 5
        5 -1 5
        5 -1 -5
        -5 -1 -5
    </VertexData>
    <Objects>
        <Mesh id="1">
            <Material>1</Material>
            <Faces>1 2 3 1 3 4</Faces>
        </Mesh>
    </Objects>"#;
    let text = with_lights(scene_xml(body), &area_light("0 1 -3", "0 -1 0", 1, "100 100 100"))
        .replace("<Gaze>0 0 -1</Gaze>", "<Gaze>0 0.5 -1</Gaze>");
    let s = one(&text);
    for backend in BackendKind::compiled() {
        let mut options = course_options(&s, backend);
        options.spp = 16;
        options.jitter = true;
        let output = render(&s, &options).unwrap();
        let film = &output.film;
        // Bottom rows: the lit floor. Top rows: looking up past the light: background.
        let floor = film.pixel(4, 7);
        let sky = film.pixel(4, 0);
        assert!(floor.x > 1.0, "{} floor {floor}", backend.name());
        assert_eq!(sky, glam::Vec3::ZERO, "{}", backend.name());
    }
}

/// `text` (from `scene_xml`) with its lights replaced by `lights` (XML elements).
pub(super) fn with_lights(text: String, lights: &str) -> String {
    text.replace(
        "<Lights><AmbientLight>25 25 25</AmbientLight></Lights>",
        &format!("<Lights>\n{lights}\n</Lights>"),
    )
}

/// A course area light (a square of side `size`).
pub(super) fn area_light(position: &str, normal: &str, size: u32, radiance: &str) -> String {
    format!(
        "<AreaLight id=\"1\"><Position>{position}</Position><Normal>{normal}</Normal>\
         <Size>{size}</Size><Radiance>{radiance}</Radiance></AreaLight>"
    )
}

/// hw6: `<BRDFs>` set a material's model and exponent; a lookAt camera may give a `Gaze`
/// direction; `LightMesh` and `LightSphere` emit their `Radiance` through their own copy of
/// the material, so the material the plain mesh uses stays dark.
#[test]
fn hw6_brdfs_gaze_cameras_and_object_lights() {
    use embray::scene::CourseBrdf;
    let text = scene_xml(TRIANGLE)
        .replace(
            "<Materials>",
            r#"<BRDFs>
        <ModifiedBlinnPhong id="b" normalized="true"><Exponent>40</Exponent></ModifiedBlinnPhong>
        <TorranceSparrow id="t" kdfresnel="true"><Exponent>50</Exponent></TorranceSparrow>
    </BRDFs>
    <Materials>"#,
        )
        .replace("<Material id=\"1\">", "<Material id=\"1\" BRDF=\"b\">")
        .replace(
            "    </Materials>",
            r#"    <Material id="2" BRDF="t">
            <DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance>
            <RefractionIndex>0.37</RefractionIndex>
            <AbsorptionIndex>2.82</AbsorptionIndex>
        </Material>
    </Materials>"#,
        )
        .replace(
            "    </Objects>",
            r#"        <LightMesh id="1">
            <Material>2</Material>
            <Radiance>3 4 5</Radiance>
            <Faces vertexOffset="1">0 1 2</Faces>
        </LightMesh>
        <LightSphere id="1">
            <Material>1</Material>
            <Center>2</Center>
            <Radius>0.25</Radius>
            <Radiance>7 7 7</Radiance>
        </LightSphere>
    </Objects>"#,
        )
        .replace(
            r#"<Camera id="1">
            <Position>0 0 0</Position>
            <Gaze>0 0 -1</Gaze>
            <Up>0 1 0</Up>
            <NearPlane>-1 1 -1 1</NearPlane>"#,
            r#"<Camera id="1" type="lookAt" handedness="right">
            <Position>0 0 0</Position>
            <Gaze>0 0 -1</Gaze>
            <Up>0 1 0</Up>
            <FovY>90</FovY>"#,
        );
    let s = one(&text);
    assert_eq!(s.camera.lookat, DVec3::new(0.0, 0.0, -1.0));
    assert_eq!(s.camera.vfov_deg, 90.0);
    let phong = |i: usize| s.materials[i].phong.clone().unwrap();
    assert_eq!(phong(0).brdf, CourseBrdf::ModifiedBlinnPhong { normalized: true });
    assert_eq!(phong(0).exponent, 40.0);
    assert_eq!(
        phong(1).brdf,
        CourseBrdf::TorranceSparrow {
            kd_fresnel: true,
            eta: glam::Vec3::splat(0.37),
            k: glam::Vec3::splat(2.82)
        }
    );
    // The plain mesh, the light mesh and the light sphere, in file order.
    assert_eq!(s.objects.len(), 3);
    let material = |o: usize| &s.materials[s.objects[o].material as usize];
    assert_eq!(material(0).emission, glam::Vec3::ZERO);
    assert_eq!(material(1).emission, glam::Vec3::new(3.0, 4.0, 5.0));
    assert_eq!(material(1).phong.clone().unwrap().brdf, phong(1).brdf);
    assert_eq!(material(2).emission, glam::Vec3::splat(7.0));
    assert!(matches!(s.objects[2].shape, ShapeDesc::Sphere { radius, .. } if radius == 0.25));
    // `vertexOffset="1"` makes the light mesh's 0-based indices name vertices 1, 2, 3.
    let ShapeDesc::Mesh(mesh) = &s.objects[1].shape else { panic!("a mesh") };
    assert_eq!(mesh.positions.len(), 3);
}

/// hw5's `DirectionalLight` (Radiance is the irradiance it gives) and `SpotLight` (angles in
/// degrees, full cones) import, refuse bad angles naming the element, and survive
/// `embray convert`'s TOML.
#[test]
fn hw5_directional_and_spot_lights_import_and_convert() {
    let lights = "<DirectionalLight id=\"1\"><Direction>1 -0.8 -1</Direction>\
                  <Radiance>200 200 200</Radiance></DirectionalLight>\n\
                  <SpotLight id=\"1\"><Position>-0.93 1 0.9</Position><Direction>1 -1 -1</Direction>\
                  <Intensity>600 600 600</Intensity><CoverageAngle>10</CoverageAngle>\
                  <FalloffAngle>8</FalloffAngle></SpotLight>";
    let s = one(&with_lights(scene_xml(TRIANGLE), lights));
    assert_eq!(
        s.lights,
        [
            LightDesc::Directional(Directional {
                direction: DVec3::new(1.0, -0.8, -1.0).normalize(),
                irradiance: glam::Vec3::splat(200.0)
            }),
            LightDesc::Spot(Spot {
                position: DVec3::new(-0.93, 1.0, 0.9),
                direction: DVec3::new(1.0, -1.0, -1.0).normalize(),
                intensity: glam::Vec3::splat(600.0),
                coverage_degrees: 10.0,
                falloff_degrees: 8.0,
                profile: Default::default(),
                texture: None,
            }),
        ]
    );
    let dir = temp_dir("hw5-lights");
    let mut writer = embray::scene::toml_writer::TomlWriter::new(dir.join("meshes"));
    let toml = dir.join("lights.toml");
    writer.write(&s, &toml, "round trip").unwrap();
    let back = embray::scene::load(&toml).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back.lights, s.lights);
    let wider = lights.replace("<FalloffAngle>8", "<FalloffAngle>12");
    let message = load_text(&with_lights(scene_xml(TRIANGLE), &wider)).unwrap_err().to_string();
    assert!(message.contains("FalloffAngle") && message.contains("12"), "{message}");
    assert!(
        message.contains("must be an angle in degrees, >= 0 and <= CoverageAngle"),
        "{message}"
    );
    // A missing parameter is named as the course writes it, not by the kind's own name.
    let no_position = lights.replace("<Position>", "<!--").replace("</Position>", "-->");
    let message = load_text(&with_lights(scene_xml(TRIANGLE), &no_position)).unwrap_err();
    let message = message.to_string();
    assert!(message.contains("is missing the field `Position`"), "{message}");
}
