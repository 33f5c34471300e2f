//! Energy through glass on long paths (hw6's glass box with Russian roulette): a material that
//! adds the course's specular lobe to glass must not reflect more than it receives, and
//! roulette must judge a path by its energy, not by radiance compressed inside glass.

use super::reference_scenes::data_dir;
use super::*;
use embray::choice::Choice;
use glam::DVec3;

/// The glass box's `glass_next_importance_russian` camera (no depth limit) at 48×48, 16 spp:
/// before the fix its brightest pixel grew about 15 % a bounce, to 1e7 and beyond.
#[test]
#[cfg_attr(not(course_data), ignore = "needs the CENG795 packs at ../shared/data/ceng795")]
fn hw6_glass_box_with_roulette_has_no_runaway_pixels() {
    let xml = data_dir().join("2022/hw6/pathTracing/inputs/cornellbox_jaroslav_path_glass.xml");
    let cameras = ceng795::load(&xml).unwrap();
    for name in ["glass_next_importance_russian.exr", "glass_next_russian.exr"] {
        let camera = cameras.iter().find(|c| c.image_name == name).unwrap();
        let mut scene = camera.scene.clone();
        (scene.camera.width, scene.camera.height, scene.settings.spp) = (48, 48, 16);
        let mut options = course_options(&scene, BackendKind::compiled()[0]);
        options.spp = 16;
        let film = render(&scene, &options).unwrap().film;
        let brightest = film.color.iter().map(|c| c.max_element()).fold(0.0f32, f32::max);
        let mean = film.color.iter().map(|c| c.as_dvec3()).sum::<DVec3>() / film.color.len() as f64;
        println!("{name} at 48², 16 spp, no depth limit: brightest {brightest:.3}, mean {mean:.4}");
        // The light's radiance is what a pixel that sees it directly gets; glass may focus
        // light, but a 16-sample mean a hundred times the light's radiance is a runaway path.
        assert!(brightest < 100.0 * mean.max_element() as f32, "{name}: {brightest}");
    }
}

/// A white furnace: a glass sphere whose material adds the course's lobe (ks 0.3, normalized
/// modified Phong, p 200, hw6's glass) in a uniform white background, paths up to 1000
/// bounces with roulette. Nothing in the scene emits but the background, so no pixel can
/// be brighter than 1 on average: glass that reflects or transmits all it receives plus the
/// lobe on top made the sphere 1.1–1.3 times as bright as the background.
#[test]
fn white_furnace_through_course_glass_gains_no_energy() {
    let xml = r#"<Scene>
    <BackgroundColor>1 1 1</BackgroundColor>
    <MaxRecursionDepth>1000</MaxRecursionDepth>
    <Cameras>
        <Camera id="1">
            <Position>0 0 4</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>
            <NearPlane>-0.3 0.3 -0.3 0.3</NearPlane><NearDistance>1</NearDistance>
            <ImageResolution>12 12</ImageResolution><NumSamples>256</NumSamples>
            <ImageName>furnace.exr</ImageName>
            <Renderer>PathTracing</Renderer>
            <RendererParams>ImportanceSampling</RendererParams>
        </Camera>
    </Cameras>
    <Lights><AmbientLight>0 0 0</AmbientLight></Lights>
    <BRDFs><ModifiedPhong id="1" normalized="true"><Exponent>200</Exponent></ModifiedPhong></BRDFs>
    <Materials>
        <Material id="1" BRDF="1" type="dielectric">
            <AmbientReflectance>0 0 0</AmbientReflectance>
            <DiffuseReflectance>0 0 0</DiffuseReflectance>
            <SpecularReflectance>0.3 0.3 0.3</SpecularReflectance>
            <AbsorptionCoefficient>0 0 0</AbsorptionCoefficient>
            <RefractionIndex>1.5</RefractionIndex>
        </Material>
    </Materials>
    <VertexData>0 0 0</VertexData>
    <Objects><Sphere id="1"><Material>1</Material><Center>1</Center><Radius>1</Radius></Sphere></Objects>
</Scene>"#;
    let cameras = load_text(xml).unwrap();
    let scene = &cameras[0].scene;
    // The course's own model adds the lobe to Fresnel's full share: the same furnace runs away.
    let mut additive = course_options(scene, BackendKind::compiled()[0]);
    additive.energy = embray::shading::bsdf::Energy::Additive;
    let film = render(scene, &additive).unwrap().film;
    let gained = film.color.iter().map(|c| f64::from(c.x)).sum::<f64>() / film.color.len() as f64;
    println!("furnace with --energy additive: mean {gained:.2}");
    assert!(gained > 2.0, "the additive model should gain energy here: {gained}");
    assert_eq!(scene.settings.max_depth, 1000, "the path depth the furnace is meant to test");
    for backend in BackendKind::compiled() {
        let options = course_options(scene, backend);
        let film = render(scene, &options).unwrap().film;
        let n = film.color.len() as f64;
        let mean = film.color.iter().map(|c| c.as_dvec3()).sum::<DVec3>() / n;
        let brightest = film.color.iter().map(|c| c.max_element()).fold(0.0f32, f32::max);
        println!("furnace on {}: mean {mean:.4}, brightest pixel {brightest:.4}", backend.name());
        // Every pixel sees the sphere (its disc covers the 0.6-wide window at distance 3),
        // which loses nothing (no absorption) and gains nothing: the mean of 144 × 256
        // paths is 1 within its noise, and a gain of a few % a bounce would show far above.
        assert!((mean.max_element() - 1.0).abs() <= 0.01, "{}: mean {mean}", backend.name());
        assert!(brightest <= 1.25, "{}: brightest {brightest}", backend.name());
    }
}
