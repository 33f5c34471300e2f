//! Small inline scenes: cameras, transforms, instances, motion, materials and lights map to
//! the scene description as the course defines them.

use super::inline_lights::{area_light, with_lights};
use super::*;
use embray::scene::{Ambient, Area, Point};

pub(super) fn one(text: &str) -> SceneDesc {
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
    assert_eq!(m[2].specular, Specular::dielectric(1.5, glam::Vec3::new(0.01, 0.02, 0.03)));
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
