//! Small inline scenes: cameras, transforms, instances, motion, materials and lights map to
//! the scene description as the course defines them.

use super::*;
use crate::common::command::temp_dir;
use embray::choice::Choice;
use embray::scene::{Ambient, Area, Directional, Point, Spot};

fn one(text: &str) -> SceneDesc {
    let mut scenes = load_text(text).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scenes.len(), 1);
    scenes.remove(0).scene
}

#[test]
fn cameras_follow_the_course_conventions() {
    // Gaze not perpendicular to Up: orthonormalised (w = −gaze, u = up × w, v = w × u).
    let text = scene_xml(TRIANGLE)
        .replace("<Gaze>0 0 -1</Gaze>", "<Gaze>0 -0.2 -1</Gaze>")
        .replace("<NearPlane>-1 1 -1 1</NearPlane>", "<NearPlane>-1 1 -0.5 0.5 10</NearPlane>")
        .replace("<NearDistance>1</NearDistance>", "<NearDistance>2</NearDistance>")
        .replace(
            "<ImageResolution>8 8</ImageResolution>",
            "<ImageResolution>16 8</ImageResolution>",
        );
    let s = one(&text);
    let c = &s.camera;
    assert_eq!((c.width, c.height), (16, 8));
    assert!((c.vfov_deg - 2.0 * 0.25f64.atan().to_degrees()).abs() < 1e-9);
    let view = (c.lookat - c.lookfrom).normalize();
    assert!((view - DVec3::new(0.0, -0.2, -1.0).normalize()).length() < 1e-12);
    assert_eq!((s.settings.spp, s.settings.max_depth), (1, 0));
    assert_eq!(s.settings.integrator, embray::scene::IntegratorKind::Whitted);
    // lookAt: GazePoint and FovY.
    let look_at = scene_xml(TRIANGLE).replace(
        r#"<Camera id="1">
            <Position>0 0 0</Position>
            <Gaze>0 0 -1</Gaze>"#,
        r#"<Camera id="1" type="lookAt">
            <Position>1 2 3</Position>
            <GazePoint>1 2 -7</GazePoint>
            <FovY>40</FovY>"#,
    );
    let look_at = look_at.replace("<NearPlane>-1 1 -1 1</NearPlane>", "");
    let s = one(&look_at);
    assert_eq!(s.camera.vfov_deg, 40.0);
    assert_eq!(s.camera.lookfrom, DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(s.camera.lookat, DVec3::new(1.0, 2.0, -7.0));
    // Depth of field: a square lens whose side is the aperture.
    let dof = scene_xml(TRIANGLE).replace(
        "<ImageName>",
        "<ApertureSize>1.5</ApertureSize><FocusDistance>21</FocusDistance><NumSamples>9</NumSamples><ImageName>",
    );
    let s = one(&dof);
    assert_eq!(s.camera.aperture, 1.5);
    assert_eq!(s.camera.focus_distance, Some(21.0));
    assert_eq!(s.camera.lens_shape, embray::scene::LensShape::Square);
    assert_eq!(s.settings.spp, 9);
}

#[test]
fn off_centre_windows_are_reproduced_exactly_by_a_lens_shift() {
    use embray::compile::{EffectsMode, to_render_scene};
    use embray::render_space::RenderSpace;
    let text = scene_xml(TRIANGLE)
        .replace("<NearPlane>-1 1 -1 1</NearPlane>", "<NearPlane>-1 1.5 -1 0.6</NearPlane>")
        .replace(
            "<ImageResolution>8 8</ImageResolution>",
            "<ImageResolution>25 16</ImageResolution>",
        );
    let (scenes, warnings) = ceng795::load_str_with_warnings(&text, Path::new("x.xml")).unwrap();
    assert!(warnings.is_empty(), "an off-centre window is no approximation: {warnings:?}");
    let desc = &scenes[0].scene;
    // The view stays along the gaze; the window's height gives the angle, its centre the shift.
    let view = (desc.camera.lookat - desc.camera.lookfrom).normalize();
    assert!((view - DVec3::NEG_Z).length() < 1e-12);
    assert!((desc.camera.vfov_deg - 2.0 * 0.8f64.atan().to_degrees()).abs() < 1e-9);
    assert_eq!(desc.camera.shift, glam::DVec2::new(0.25, -0.2));
    // The corner rays go through the window's corners (NearDistance 1, camera at 0, -Z).
    let scene = to_render_scene(desc, RenderSpace::Camera, EffectsMode::Auto).unwrap();
    for (raster, corner) in [
        (glam::Vec2::new(0.0, 0.0), glam::Vec3::new(-1.0, 0.6, -1.0)),
        (glam::Vec2::new(25.0, 16.0), glam::Vec3::new(1.5, -1.0, -1.0)),
    ] {
        let ray = scene.camera.generate_ray(raster, None);
        let at_plane = ray.origin + ray.dir * (1.0 / -ray.dir.z);
        assert!((at_plane - corner).length() < 1e-5, "{raster}: {at_plane} vs {corner}");
    }
}

#[test]
fn transformations_instances_and_motion() {
    let body = r#"
    <Transformations>
        <Scaling id="1">2 2 2</Scaling>
        <Rotation id="1">90 0 0 1</Rotation>
        <Translation id="1">10 0 0</Translation>
        <Translation id="2">0 0 -5</Translation>
    </Transformations>
    <VertexData>
        1 0 0
        0 1 0
        0 0 1
    </VertexData>
    <Objects>
        <Mesh id="1" shadingMode="smooth">
            <Material>1</Material>
            <Transformations>s1 r1 t1</Transformations>
            <Faces>1 2 3</Faces>
        </Mesh>
        <MeshInstance id="1" baseMeshId="1" resetTransform="true">
            <Transformations>t2</Transformations>
            <MotionBlur>0 3 0</MotionBlur>
        </MeshInstance>
        <MeshInstance id="2" baseMeshId="1">
            <Transformations>t2</Transformations>
        </MeshInstance>
        <Sphere id="1">
            <Material>1</Material>
            <Center>1</Center>
            <Radius>0.5</Radius>
        </Sphere>
    </Objects>"#;
    let s = one(&scene_xml(body));
    assert_eq!(s.objects.len(), 4);
    let (mesh, reset, stacked) = (&s.objects[0], &s.objects[2], &s.objects[3]);
    // s1 r1 t1: scale, then rotate 90° about z, then translate: (1,0,0) → (2,0,0) → (0,2,0)
    // → (10,2,0).
    let p = mesh.world_from_object.transform_point3(DVec3::X);
    assert!((p - DVec3::new(10.0, 2.0, 0.0)).length() < 1e-12, "{p}");
    assert_eq!(reset.world_from_object, DAffine3::from_translation(DVec3::new(0.0, 0.0, -5.0)));
    assert_eq!(
        reset.world_from_object_end,
        Some(DAffine3::from_translation(DVec3::new(0.0, 3.0, -5.0)))
    );
    let p = stacked.world_from_object.transform_point3(DVec3::X);
    assert!((p - DVec3::new(10.0, 2.0, -5.0)).length() < 1e-12, "{p}");
    assert!(stacked.world_from_object_end.is_none());
    match (&mesh.shape, &reset.shape, &stacked.shape) {
        (ShapeDesc::Mesh(a), ShapeDesc::Mesh(b), ShapeDesc::Mesh(c)) => {
            assert!(std::sync::Arc::ptr_eq(a, b) && std::sync::Arc::ptr_eq(a, c));
            let normals = a.normals.as_ref().expect("smooth shading gives normals");
            assert!((normals[0] - DVec3::ONE.normalize()).length() < 1e-12);
        }
        _ => panic!("instances must be meshes"),
    }
    assert_eq!(s.objects[1].shape, ShapeDesc::Sphere { center: DVec3::X, radius: 0.5 });
}

#[test]
fn materials_and_lights_map_to_the_scene_description() {
    use embray::scene::Specular;
    let materials = MATERIALS.replace(
        "    </Materials>",
        r#"    <Material id="2" type="conductor">
            <MirrorReflectance>1 0.86 0.57</MirrorReflectance>
            <RefractionIndex>0.37</RefractionIndex>
            <AbsorptionIndex>2.82</AbsorptionIndex>
            <Roughness>0.1</Roughness>
        </Material>
        <Material id="3" type="dielectric">
            <AbsorptionCoefficient>0.01 0.02 0.03</AbsorptionCoefficient>
            <RefractionIndex>1.5</RefractionIndex>
        </Material>
        <Material id="4" type="mirror">
            <DiffuseReflectance>0.5 0.5 1.5</DiffuseReflectance>
            <MirrorReflectance>0.5 0.5 0.5</MirrorReflectance>
        </Material>
    </Materials>"#,
    );
    let lights = format!(
        "<AmbientLight>25 25 25</AmbientLight>\n\
         <PointLight id=\"1\"><Position>1 2 3</Position><Intensity>1000 1000 1000</Intensity></PointLight>\n{}",
        area_light("0 9.8 2", "0 -2 0", 3, "150000 150000 150000")
    );
    let text = with_lights(scene_xml(TRIANGLE).replace(MATERIALS, &materials), &lights);
    let s = one(&text);
    let m = &s.materials;
    assert_eq!(m.len(), 4);
    assert_eq!(m[0].phong.as_ref().unwrap().exponent, 1.0);
    assert_eq!(
        m[1].specular,
        Specular::Conductor {
            eta: glam::Vec3::splat(0.37),
            k: glam::Vec3::splat(2.82),
            reflectance: glam::Vec3::new(1.0, 0.86, 0.57)
        }
    );
    assert_eq!(m[1].roughness, 0.1);
    assert_eq!(
        m[2].specular,
        Specular::Dielectric { ior: 1.5, absorption: glam::Vec3::new(0.01, 0.02, 0.03) }
    );
    assert_eq!(m[3].albedo, glam::Vec3::new(0.5, 0.5, 1.5));
    assert_eq!(
        s.lights,
        [
            LightDesc::Ambient(Ambient { radiance: glam::Vec3::splat(25.0) }),
            LightDesc::Point(Point {
                position: DVec3::new(1.0, 2.0, 3.0),
                intensity: glam::Vec3::splat(1000.0)
            }),
            LightDesc::Area(Area {
                center: DVec3::new(0.0, 9.8, 2.0),
                normal: DVec3::NEG_Y,
                size: 3.0,
                radiance: glam::Vec3::splat(150000.0)
            }),
        ]
    );
}

#[test]
fn degamma_materials_read_their_reflectances_linearised() {
    let materials = MATERIALS.replace(
        "    </Materials>",
        r#"    <Material id="2" degamma="true">
            <AmbientReflectance>0.651 0.389 0.389</AmbientReflectance>
            <DiffuseReflectance>0.651 0.389 1</DiffuseReflectance>
            <SpecularReflectance>0.5 0.389 0.389</SpecularReflectance>
            <MirrorReflectance>0.25 0.25 0.25</MirrorReflectance>
        </Material>
        <Material id="3" degamma="false">
            <DiffuseReflectance>0.651 0.389 1</DiffuseReflectance>
        </Material>
    </Materials>"#,
    );
    let s = one(&scene_xml(TRIANGLE).replace(MATERIALS, &materials));
    let linear = |c: f32| c.powf(2.2);
    let m = &s.materials;
    assert_eq!(m[1].albedo, glam::Vec3::new(linear(0.651), linear(0.389), 1.0));
    let phong = m[1].phong.as_ref().unwrap();
    assert_eq!(phong.ambient, glam::Vec3::new(linear(0.651), linear(0.389), linear(0.389)));
    assert_eq!(phong.specular.x, linear(0.5));
    assert_eq!(m[2].albedo, glam::Vec3::new(0.651, 0.389, 1.0));
    let bad =
        scene_xml(TRIANGLE).replace("<Material id=\"1\">", "<Material id=\"1\" degamma=\"yes\">");
    assert_contains(&error_of(&bad), &["degamma=\"yes\"", "\"true\" or \"false\"", "line"]);
}

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
fn with_lights(text: String, lights: &str) -> String {
    text.replace(
        "<Lights><AmbientLight>25 25 25</AmbientLight></Lights>",
        &format!("<Lights>\n{lights}\n</Lights>"),
    )
}

/// A course area light (a square of side `size`).
fn area_light(position: &str, normal: &str, size: u32, radiance: &str) -> String {
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
                falloff_degrees: 8.0
            }),
        ]
    );
    let dir = temp_dir("hw5-lights");
    let mut writer = embray::scene::toml_writer::TomlWriter::new(dir.join("meshes"));
    let toml = dir.join("lights.toml");
    writer.write(&s, &toml, "round trip").unwrap();
    let back = embray::scene::load(&toml).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back.lights, s.lights);
    std::fs::remove_dir_all(&dir).unwrap();
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
