//! hw6's `<RendererParams>`: next-event estimation, importance sampling and Russian roulette
//! change how the course's path tracer estimates the image, not the image. On a scene where
//! the three agree on what they integrate (light from an emissive mesh only, since no path
//! can hit a point light without next-event estimation; reflectances low enough that the
//! depth limit cuts off less than 1e-5 of the light), all eight combinations must converge to
//! one image.
//!
//! embray maps every combination onto its one path tracer (BSDF sampling and light sampling
//! weighed by MIS, its own roulette); the parameters only set the depth limit and whether the
//! unhittable lights exist. So here, where no path reaches the limit, the eight images are
//! in fact identical, and the check below (paired by seed) would see a bias of a quarter of a
//! percent, as the truncated-depth test shows.

use super::*;

/// A small Cornell box after hw6's `cornellbox_jaroslav_path_diffuse.xml`: diffuse walls
/// under the course's normalized modified Phong, a glossy sphere (the course's specular term
/// as a lobe) and a diffuse one, lit by an emissive cube under the ceiling.
const BOX: &str = r#"
    <MaxRecursionDepth>14</MaxRecursionDepth>
    <BackgroundColor>0 0 0</BackgroundColor>
    <Lights><AmbientLight>0 0 0</AmbientLight></Lights>
    <BRDFs>
        <ModifiedPhong id="1" normalized="true"><Exponent>90</Exponent></ModifiedPhong>
        <ModifiedPhong id="2" normalized="true"><Exponent>20</Exponent></ModifiedPhong>
    </BRDFs>
    <Materials>
        <Material id="1"><DiffuseReflectance>0 0 0</DiffuseReflectance></Material>
        <Material id="2" BRDF="1"><DiffuseReflectance>0.4 0.4 0.4</DiffuseReflectance></Material>
        <Material id="3" BRDF="1"><DiffuseReflectance>0.08 0.4 0.09</DiffuseReflectance></Material>
        <Material id="4" BRDF="1"><DiffuseReflectance>0.4 0.08 0.08</DiffuseReflectance></Material>
        <Material id="5" BRDF="2">
            <DiffuseReflectance>0.2 0.2 0.05</DiffuseReflectance>
            <SpecularReflectance>0.3 0.3 0.3</SpecularReflectance>
        </Material>
    </Materials>
    <VertexData>
        -1.27 1.3 -1.28   1.29 1.3 -1.28   1.29 1.3 1.28   -1.27 1.3 1.28
        -1.27 -1.26 -1.28   1.29 -1.26 -1.28   1.29 -1.26 1.28   -1.27 -1.26 1.28
        -0.54 0.02 -0.78   0.56 0.66 -0.78
        -0.4 0.4 1.0   0.4 0.4 1.0   0.4 0.4 1.28   -0.4 0.4 1.28
        -0.4 -0.4 1.0   0.4 -0.4 1.0   0.4 -0.4 1.28   -0.4 -0.4 1.28
    </VertexData>
    <Objects>
        <Mesh id="1"><Material>2</Material><Faces vertexOffset="1">0 4 5 5 1 0</Faces></Mesh>
        <Mesh id="2"><Material>3</Material><Faces vertexOffset="1">3 7 4 4 0 3</Faces></Mesh>
        <Mesh id="3"><Material>4</Material><Faces vertexOffset="1">1 5 6 6 2 1</Faces></Mesh>
        <Mesh id="4"><Material>2</Material><Faces vertexOffset="1">0 1 2 2 3 0</Faces></Mesh>
        <Mesh id="5"><Material>2</Material><Faces vertexOffset="1">2 6 7 7 3 2</Faces></Mesh>
        <LightMesh id="1">
            <Material>1</Material>
            <Radiance>6 6 6</Radiance>
            <Faces vertexOffset="11">
                0 2 1  2 0 3  3 4 7  4 3 0  1 6 5  6 1 2  4 5 6  6 7 4  0 5 4  5 0 1
            </Faces>
        </LightMesh>
        <Sphere id="1"><Material>5</Material><Center>9</Center><Radius>0.5</Radius></Sphere>
        <Sphere id="2"><Material>2</Material><Center>10</Center><Radius>0.5</Radius></Sphere>
    </Objects>
"#;

/// One camera per combination of the three parameters.
fn cameras(size: u32, spp: u32) -> (String, Vec<String>) {
    let mut xml = String::from("<Cameras>");
    let mut names = Vec::new();
    for combination in 0..8u32 {
        let params: Vec<&str> = ["NextEventEstimation", "ImportanceSampling", "RussianRoulette"]
            .into_iter()
            .enumerate()
            .filter(|(bit, _)| combination & (1 << bit) != 0)
            .map(|(_, name)| name)
            .collect();
        let params = params.join(" ");
        xml += &format!(
            r#"<Camera id="{id}" type="lookAt" handedness="right">
                <Position>-0.04 -4.1 0.22</Position>
                <Gaze>0.0069 0.9985 -0.054</Gaze>
                <Up>0 0.054 0.9985</Up>
                <FovY>45</FovY>
                <NearDistance>0.1</NearDistance>
                <ImageResolution>{size} {size}</ImageResolution>
                <NumSamples>{spp}</NumSamples>
                <ImageName>c{combination}.exr</ImageName>
                <Renderer>PathTracing</Renderer>
                <RendererParams>{params}</RendererParams>
            </Camera>"#,
            id = combination + 1,
        );
        names.push(if params.is_empty() { "(none)".to_owned() } else { params });
    }
    xml += "</Cameras>";
    (xml, names)
}

/// The image mean (per channel) of each camera's render with each of `seeds` seeds:
/// `means[camera][seed]`.
fn image_means(scenes: &[CameraScene], seeds: u64) -> Vec<Vec<DVec3>> {
    scenes
        .iter()
        .map(|camera| {
            (0..seeds)
                .map(|seed| {
                    let mut options =
                        course_options(&camera.scene, BackendKind::default_compiled());
                    options.seed = 1000 + seed;
                    let film = render(&camera.scene, &options).unwrap().film;
                    film.color.iter().map(|c| c.as_dvec3()).sum::<DVec3>() / film.color.len() as f64
                })
                .collect()
        })
        .collect()
}

/// Mean and standard error of the mean of `samples`.
fn mean_and_error(samples: &[DVec3]) -> (DVec3, DVec3) {
    let n = samples.len() as f64;
    let mean = samples.iter().sum::<DVec3>() / n;
    let variance = samples.iter().map(|s| (*s - mean) * (*s - mean)).sum::<DVec3>() / (n - 1.0);
    (mean, (variance / n).map(f64::sqrt))
}

/// How far camera `a`'s image mean lies from camera `b`'s, in standard errors of their
/// difference. Renders with the same seed share their random numbers, so the difference is
/// estimated seed by seed (paired): that cancels most of the noise and leaves any bias.
fn paired_difference(means: &[Vec<DVec3>], a: usize, b: usize) -> (DVec3, DVec3) {
    let differences: Vec<DVec3> = means[a].iter().zip(&means[b]).map(|(x, y)| *x - *y).collect();
    mean_and_error(&differences)
}

fn load_box(depth: u32, spp: u32) -> (Vec<CameraScene>, Vec<String>) {
    let (cameras, names) = cameras(8, spp);
    let scene = BOX.replace("<MaxRecursionDepth>14<", &format!("<MaxRecursionDepth>{depth}<"));
    let text = format!("<Scene>{cameras}{scene}</Scene>");
    let scenes = load_text(&text).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scenes.len(), 8);
    (scenes, names)
}

/// Camera index of the combination with only Russian roulette (no depth limit).
const ROULETTE: usize = 4;

#[test]
fn every_renderer_params_combination_converges_to_the_same_image() {
    let (scenes, names) = load_box(14, 256);
    let start = Instant::now();
    let means = image_means(&scenes, 6);
    println!("8 combinations × 6 seeds at 8×8, 256 spp: {:.2} s", start.elapsed().as_secs_f64());
    for (camera, name) in names.iter().enumerate() {
        let (mean, error) = mean_and_error(&means[camera]);
        let (apart, apart_error) = paired_difference(&means, camera, ROULETTE);
        println!(
            "{name:>52}: mean {:.5} {:.5} {:.5} ± {:.5}; off roulette's by {:.6} ± {:.6}",
            mean.x,
            mean.y,
            mean.z,
            error.max_element(),
            apart.abs().max_element(),
            apart_error.max_element()
        );
        // The estimate must be tight enough for the comparison to mean something.
        assert!(
            (error / mean).max_element() < 0.005,
            "{name}: standard error {error} of mean {mean} too large to compare"
        );
        assert!(
            apart.abs().cmple(apart_error * 4.0).all(),
            "{name} converges elsewhere than RussianRoulette alone: {apart} ± {apart_error}"
        );
    }
}

/// The comparison above can see a bias of a fraction of a percent: with the course's depth
/// limit set to 2, the truncated combinations come out darker than the roulette ones, by
/// many paired standard errors.
#[test]
fn the_convergence_check_sees_a_truncated_depth() {
    let (scenes, names) = load_box(2, 64);
    let means = image_means(&scenes, 6);
    for camera in [0, 1, 2, 3] {
        let (apart, apart_error) = paired_difference(&means, camera, ROULETTE);
        let (mean, _) = mean_and_error(&means[ROULETTE]);
        println!(
            "{:>40} at depth 2: {:+.3} % of roulette's mean, {:.1} standard errors",
            names[camera],
            100.0 * (apart / mean).min_element(),
            (apart / apart_error).min_element()
        );
        assert!(
            (apart + apart_error * 4.0).cmplt(DVec3::ZERO).all(),
            "{}: depth 2 should be darker than roulette: {apart} ± {apart_error}",
            names[camera]
        );
    }
}

/// A `LightSphere` under a non-uniform `<Scaling>` (hw6's ellipsoid light) is sampled like
/// any emitter. Its sampling goes through the sphere's own space
/// (`src/shading/light/ellipsoid.rs`, whose tests check the density against a brute-force
/// solid angle); here a sphere scaled by 1 1 1.0001 must light the box as the plain sphere
/// does (paired by seed), and one stretched 3× must light it, and more.
#[test]
fn scaled_light_spheres_light_the_box() {
    let light = |scaling: &str| {
        let (cameras, _) = cameras(8, 512);
        let first = &cameras[..cameras.find("</Camera>").unwrap() + "</Camera>".len()];
        let objects = BOX.replace(
            r#"<LightMesh id="1">"#,
            r#"<LightSphere id="1"><Material>1</Material><Center>9</Center><Radius>0.15</Radius>
               <Radiance>30 30 30</Radiance><Transformations>s1 t1</Transformations></LightSphere>
               <LightMesh id="1">"#,
        );
        let objects = objects.replace("<Radiance>6 6 6</Radiance>", "<Radiance>0 0 0</Radiance>");
        let transforms = format!(
            "<Transformations><Translation id=\"1\">0.3 0 1.7</Translation>\
             <Scaling id=\"1\">{scaling}</Scaling></Transformations>"
        );
        let text = format!("<Scene>{first}</Cameras>{transforms}{objects}</Scene>");
        let mut scenes = load_text(&text).unwrap_or_else(|e| panic!("{e}"));
        scenes.remove(0)
    };
    let scenes = [light("1 1 1"), light("1 1 1.0001"), light("3 1 1")];
    let means = image_means(&scenes, 6);
    let [sphere, nearly, stretched] = [0, 1, 2].map(|i| mean_and_error(&means[i]).0);
    let (apart, apart_error) = paired_difference(&means, 1, 0);
    println!(
        "box lit by a sphere {sphere}, scaled 1 1 1.0001 {nearly} (paired difference {apart} ± \
         {apart_error}), 3 1 1 {stretched}"
    );
    assert!(sphere.min_element() > 0.01, "the sphere lights the box: {sphere}");
    assert!(
        (apart_error / sphere).max_element() < 0.005,
        "too noisy to compare: {apart_error} of {sphere}"
    );
    assert!(
        apart.abs().cmple(apart_error * 4.0 + sphere * 1e-3).all(),
        "a sphere scaled by 1.0001 lights the box as the sphere does: {nearly} vs {sphere}"
    );
    assert!((stretched - sphere).min_element() > 0.2 * sphere.min_element(), "{stretched}");
}
