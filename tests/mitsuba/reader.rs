//! The Mitsuba reader on scenes written here: what each construct becomes in the model, and
//! the errors that name the plugin, the file and the line.

use super::common::assert_contains;
use super::common::command::{TempPath, temp_dir};
use super::load_mitsuba;
use embray::scene::{LightDesc, Specular};
use glam::{DVec3, Vec3};

/// A folder with `main.xml` (and `extra` files), returning main.xml's path.
pub(super) fn files(name: &str, main: &str, extra: &[(&str, &str)]) -> TempPath {
    let dir = temp_dir(name);
    for (file, text) in extra {
        let path = dir.join(file);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    std::fs::write(dir.join("main.xml"), main).unwrap();
    dir.file("main.xml")
}

pub(super) const SENSOR: &str = r#"
    <sensor type="perspective">
        <float name="fov" value="$fov"/>
        <string name="fov_axis" value="y"/>
        <transform name="to_world">
            <lookat origin="0, 1, 5" target="0, 1, 0" up="0, 1, 0"/>
        </transform>
        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="32"/><integer name="height" value="24"/>
            <rfilter type="box"/>
        </film>
    </sensor>"#;

#[track_caller]
pub(super) fn close(a: DVec3, b: DVec3) {
    assert!((a - b).abs().max_element() < 1e-9, "{a} != {b}");
}

/// Defaults and `-D`, `$name`, `<include>`, `<path>`, `<ref>`, nested transforms and each
/// supported plugin become the model's values with Mitsuba's conventions.
#[test]
fn a_scene_reads_into_the_model_as_mitsuba_defines_it() {
    let main = format!(
        r#"<scene version="3.0.0">
    <default name="spp" value="16"/>
    <default name="fov" value="40"/>
    <path value="assets"/>
    <integrator type="moment"><integrator type="path"><integer name="max_depth" value="4"/></integrator></integrator>
    {SENSOR}
    <include filename="materials.xml"/>
    <shape type="sphere">
        <point name="center" x="1" y="0" z="0"/><float name="radius" value="0.5"/>
        <transform name="to_world"><scale value="2"/><rotate y="1" angle="90"/><translate x="0" y="1" z="0"/></transform>
        <ref id="glass"/>
    </shape>
    <shape type="rectangle">
        <ref id="gold"/>
        <emitter type="area"><rgb name="radiance" value="2, 3, 4"/></emitter>
    </shape>
    <shape type="cube"><bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.25"/></bsdf></bsdf></shape>
    <emitter type="point"><point name="position" x="1" y="2" z="3"/><rgb name="intensity" value="10"/></emitter>
    <emitter type="directional">
        <transform name="to_world"><lookat origin="0,0,0" target="0,-1,0" up="0,0,1"/></transform>
        <rgb name="irradiance" value="0.5"/>
    </emitter>
    <emitter type="constant"/>
</scene>"#
    );
    let materials = r#"<scene version="3.0.0">
    <bsdf type="dielectric" id="glass"><string name="int_ior" value="diamond"/><float name="ext_ior" value="1"/></bsdf>
    <bsdf type="roughconductor" id="gold"><rgb name="eta" value="0.2, 0.4, 1.4"/><rgb name="k" value="3.6, 2.4, 1.8"/><float name="alpha" value="0.3"/><string name="distribution" value="ggx"/></bsdf>
</scene>"#;
    let path = files("mitsuba-model", &main, &[("materials.xml", materials)]);
    let scene = load_mitsuba(&path, &[("fov", "30")]).unwrap();
    // The sensor: -D overrides the default; fov along y is the vertical field of view.
    assert_eq!((scene.camera.width, scene.camera.height), (32, 24));
    assert!((scene.camera.vfov_deg - 30.0).abs() < 1e-12);
    close(scene.camera.lookfrom, DVec3::new(0.0, 1.0, 5.0));
    assert_eq!(scene.settings.spp, 16);
    // Mitsuba's max_depth counts the segment to a visible emitter; embray's, the bounces.
    assert_eq!(scene.settings.max_depth, 3);
    // The sphere: center and radius in object space (Mitsuba's translate · scale of the
    // unit sphere, turned to Mitsuba's uv axes), then scale, rotate, translate in order.
    let sphere = &scene.objects[0];
    let embray::scene::ShapeDesc::Sphere { center, radius } = sphere.shape else { panic!() };
    assert_eq!((center, radius), (DVec3::ZERO, 1.0));
    let to_world = sphere.world_from_object;
    close(to_world.transform_point3(DVec3::ZERO), DVec3::new(0.0, 1.0, -2.0));
    assert!((to_world.transform_vector3(DVec3::Y).length() - 1.0).abs() < 1e-12);
    let glass = &scene.materials[sphere.material as usize];
    assert_eq!(glass.specular, Specular::dielectric(2.419, Vec3::ZERO));
    // The rectangle: the referenced conductor, with the area emitter's radiance.
    let gold = &scene.materials[scene.objects[1].material as usize];
    assert_eq!(gold.emission, Vec3::new(2.0, 3.0, 4.0));
    assert_eq!(gold.roughness, 0.3);
    assert!(matches!(gold.specular, Specular::Conductor { .. }));
    let cube = &scene.materials[scene.objects[2].material as usize];
    assert_eq!(cube.albedo, Vec3::splat(0.25));
    // The emitters, read by embray's light kinds; a placed directional light points along
    // its transform's +z.
    let [LightDesc::Point(point), LightDesc::Directional(sun), LightDesc::Environment(sky)] =
        &scene.lights[..]
    else {
        panic!("{:?}", scene.lights)
    };
    close(point.position, DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(point.intensity, Vec3::splat(10.0));
    close(sun.direction, DVec3::new(0.0, -1.0, 0.0));
    assert_eq!(sun.irradiance, Vec3::splat(0.5));
    assert_eq!(sky.map, embray::scene::EnvironmentMap::Constant(Vec3::ONE));
}

/// Mitsuba's `parse_fov`: every axis (in any case, as Mitsuba lowers it), and the 50 mm
/// default along the diagonal.
#[test]
fn fields_of_view_convert_along_every_axis() {
    let vfov = |fov: &str| {
        let sensor = SENSOR.replace(r#"<string name="fov_axis" value="y"/>"#, fov);
        let main = format!(
            r#"<scene version="3.0.0"><default name="spp" value="1"/><default name="fov" value="40"/>{sensor}</scene>"#
        );
        let path = files("mitsuba-fov", &main, &[]);
        load_mitsuba(&path, &[]).unwrap().camera.vfov_deg
    };
    let aspect = 32.0f64 / 24.0;
    let from_x =
        |x_deg: f64| (2.0 * ((0.5 * x_deg).to_radians().tan() / aspect).atan()).to_degrees();
    let expected_x = from_x(40.0);
    for (axis, expected) in
        [("x", expected_x), ("y", 40.0), ("Y", 40.0), ("smaller", 40.0), ("Larger", expected_x)]
    {
        let got = vfov(&format!(r#"<string name="fov_axis" value="{axis}"/>"#));
        assert!((got - expected).abs() < 1e-9, "{axis}: {got} vs {expected}");
    }
    // diagonal: tan(fov/2) spread over the diagonal.
    let half_diagonal = (20.0f64).to_radians().tan();
    let half_height = half_diagonal / (1.0 + aspect * aspect).sqrt();
    let got = vfov(r#"<string name="fov_axis" value="diagonal"/>"#);
    assert!((got - (2.0 * half_height.atan()).to_degrees()).abs() < 1e-9, "{got}");
    // No fov: a 50 mm lens on 36 × 24 mm film, along the diagonal.
    let sensor = SENSOR
        .replace(r#"<float name="fov" value="$fov"/>"#, "")
        .replace(r#"<string name="fov_axis" value="y"/>"#, "");
    let main = format!(r#"<scene version="3.0.0"><default name="spp" value="1"/>{sensor}</scene>"#);
    let got = load_mitsuba(&files("mitsuba-fov50", &main, &[]), &[]).unwrap().camera.vfov_deg;
    let half_diagonal = (36.0f64 * 36.0 + 24.0 * 24.0).sqrt() / 100.0;
    let expected = (2.0 * (half_diagonal / (1.0 + aspect * aspect).sqrt()).atan()).to_degrees();
    assert!((got - expected).abs() < 1e-9, "{got} vs {expected}");
}

/// What embray cannot render as Mitsuba would is refused with the plugin, file and line,
/// and so is every broken reference.
#[test]
fn errors_name_the_plugin_the_file_and_the_line() {
    let scene = |body: &str| {
        format!(
            "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" value=\"40\"/>{SENSOR}\n{body}\n</scene>"
        )
    };
    let error = |name: &str, main: String, extra: &[(&str, &str)]| {
        let path = files(name, &main, extra);
        load_mitsuba(&path, &[]).unwrap_err()
    };
    let message =
        error("mitsuba-hair", scene("<shape type=\"cube\"><bsdf type=\"hair\"/></shape>"), &[]);
    assert_contains(
        &message,
        &["main.xml", "<bsdf type=\"hair\">", "'hair' is not supported yet", "(line 15)"],
    );
    let message = error("mitsuba-medium", scene("<medium type=\"homogeneous\"/>"), &[]);
    assert_contains(&message, &["<medium> 'homogeneous' is not supported", "(line 15)"]);
    let inside = "<shape type=\"sphere\"><medium type=\"homogeneous\" name=\"interior\"/></shape>";
    let message = error("mitsuba-medium-inside", scene(inside), &[]);
    assert_contains(&message, &["participating media (<medium>) are not supported", "(line 15)"]);
    let message = error(
        "mitsuba-param",
        scene("<shape type=\"sphere\"><float name=\"radius\" value=\"$r\"/></shape>"),
        &[],
    );
    assert_contains(&message, &["$r is not a parameter", "-D r=VALUE"]);
    let message =
        error("mitsuba-ref", scene("<shape type=\"cube\"><ref id=\"nothing\"/></shape>"), &[]);
    assert_contains(&message, &["no object has the id 'nothing'", "(line 15)"]);
    let message = error("mitsuba-include", scene("<include filename=\"missing.xml\"/>"), &[]);
    assert_contains(&message, &["<include>", "cannot read", "missing.xml"]);
    let message = error(
        "mitsuba-unread",
        scene(
            "<bsdf type=\"diffuse\" id=\"d\"><float name=\"roughness\" value=\"1\"/></bsdf><shape type=\"cube\"><ref id=\"d\"/></shape>",
        ),
        &[],
    );
    assert_contains(&message, &["does not take `roughness`", "(it takes: reflectance)"]);
    let fragment = "<scene version=\"3.0.0\">\n\n<shape type=\"bsplinecurve\"/>\n</scene>";
    let message =
        error("mitsuba-fragment", scene("<include filename=\"f.xml\"/>"), &[("f.xml", fragment)]);
    assert_contains(
        &message,
        &["f.xml", "the shape 'bsplinecurve' is not supported yet", "(line 3)"],
    );
    // A boolean is true or false, not read as false when it is anything else.
    let message = error(
        "mitsuba-boolean",
        scene("<shape type=\"cube\"><boolean name=\"flip_normals\" value=\"yes\"/></shape>"),
        &[],
    );
    assert_contains(&message, &["'yes' is not true or false", "(line 15)"]);
    let message = error("mitsuba-nosensor", "<scene version=\"3.0.0\"/>".to_owned(), &[]);
    assert_contains(&message, &["the scene has no <sensor>"]);
}

/// `embray convert`'s TOML keeps what the Mitsuba scene says, the reconstruction filter and
/// the sampler's seed included (the TOML format's `[render] filter` and `seed`).
#[test]
fn a_mitsuba_scene_converts_to_toml_and_back() {
    let main = format!(
        r#"<scene version="3.0.0">
    <default name="spp" value="16"/><default name="fov" value="40"/>
    {}
    <shape type="sphere"><bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.4, 0.6"/></bsdf></shape>
    <emitter type="point"><point name="position" x="1" y="2" z="3"/><rgb name="intensity" value="10"/></emitter>
    <emitter type="constant"><rgb name="radiance" value="0.5"/></emitter>
</scene>"#,
        SENSOR
            .replace(
                r#"<rfilter type="box"/>"#,
                r#"<rfilter type="gaussian"><float name="stddev" value="0.4"/></rfilter>"#
            )
            .replace("</sampler>", r#"<integer name="seed" value="5"/></sampler>"#)
    );
    let path = files("mitsuba-convert", &main, &[]);
    let scene = load_mitsuba(&path, &[]).unwrap();
    assert_eq!(scene.settings.seed, 5);
    assert_eq!(
        scene.settings.filter,
        embray::sampling::filter::PixelFilter::Gaussian { stddev: 0.4 }
    );
    let back = super::converted(&path, &scene);
    assert_eq!(back.settings, scene.settings);
    assert_eq!(back.lights, scene.lights);
    assert_eq!(back.materials[back.objects[0].material as usize].albedo, Vec3::new(0.2, 0.4, 0.6));
}

/// Integrators read their own parameters only: `rr_depth` (Mitsuba's default 5), `direct`'s
/// `emitter_samples` (1 or more); anything else is refused with the parameter and line.
#[test]
fn integrator_parameters_are_read_or_refused() {
    let scene = |integrator: &str| {
        format!(
            "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" \
             value=\"40\"/>{SENSOR}\n{integrator}\n</scene>"
        )
    };
    let load =
        |name: &str, integrator: &str| load_mitsuba(&files(name, &scene(integrator), &[]), &[]);
    let path = load("m-int-path", "<integrator type=\"path\"/>").unwrap();
    assert_eq!(path.settings.rr_depth, 5);
    let rr = load(
        "m-int-rr",
        "<integrator type=\"path\"><integer name=\"rr_depth\" value=\"9\"/></integrator>",
    );
    assert_eq!(rr.unwrap().settings.rr_depth, 9);
    let direct = load(
        "m-int-direct",
        "<integrator type=\"direct\"><integer name=\"emitter_samples\" value=\"4\"/></integrator>",
    )
    .unwrap();
    assert_eq!((direct.settings.light_samples, direct.settings.max_depth), (4, 1));
    // 0 of either leaves a technique out, which Mitsuba renders (its image lacks what only
    // the other sees) and embray does not: refused, rather than rendered otherwise.
    for name in ["emitter_samples", "bsdf_samples"] {
        let integrator = format!(
            "<integrator type=\"direct\"><integer name=\"{name}\" value=\"0\"/></integrator>"
        );
        let message = load("m-int-zero", &integrator).unwrap_err();
        assert_contains(&message, &[&format!("{name} is 0, but must be 1 to 65536"), "(line 15)"]);
    }
    let message = load(
        "m-int-bad",
        "<integrator type=\"path\"><integer name=\"samples_per_pass\" value=\"4\"/></integrator>",
    )
    .unwrap_err();
    assert_contains(
        &message,
        &["the path integrator does not take `samples_per_pass`", "(line 15)"],
    );
}

/// The film's crop window is the scene's crop (rendered as `--crop` renders); one that
/// leaves the film is refused.
#[test]
fn a_film_crop_is_the_scenes_crop() {
    let with_crop = |name: &str, crop: &str| {
        let sensor = SENSOR.replace("<rfilter", &format!("{crop}<rfilter"));
        let main = format!(
            "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" \
             value=\"40\"/>{sensor}\n</scene>"
        );
        load_mitsuba(&files(name, &main, &[]), &[])
    };
    let crop = "<integer name=\"crop_offset_x\" value=\"4\"/><integer name=\"crop_offset_y\" \
                value=\"2\"/><integer name=\"crop_width\" value=\"10\"/><integer \
                name=\"crop_height\" value=\"8\"/>";
    let scene = with_crop("m-crop", crop).unwrap();
    assert_eq!(scene.settings.crop, Some(embray::film::Tile { x0: 4, y0: 2, x1: 14, y1: 10 }));
    let message = with_crop("m-crop-out", &crop.replace("\"10\"", "\"30\"")).unwrap_err();
    assert_contains(&message, &["the crop 30 × 8 at (4, 2) does not lie within the 32 × 24 film"]);
}

/// A sensor parameter embray does not read is refused, not ignored.
#[test]
fn an_unknown_sensor_parameter_is_refused() {
    let sensor = SENSOR.replace(
        "<float name=\"fov\"",
        "<float name=\"near_clp\" value=\"1\"/><float name=\"fov\"",
    );
    let main = format!(
        "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" \
         value=\"40\"/>{sensor}\n</scene>"
    );
    let message = load_mitsuba(&files("m-sensor-typo", &main, &[]), &[]).unwrap_err();
    assert_contains(&message, &["the perspective sensor does not take `near_clp`"]);
}

/// `near_clip` hides what lies nearer along the view axis: a sphere in front of the camera
/// disappears behind a near plane past it, on every backend.
#[test]
fn the_near_clip_plane_hides_what_is_nearer() {
    let scene = |near: &str| {
        format!(
            "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><float name=\"fov\" \
             value=\"30\"/><float name=\"near_clip\" value=\"{near}\"/><film type=\"hdrfilm\">\
             <integer name=\"width\" value=\"9\"/><integer name=\"height\" value=\"9\"/>\
             <rfilter type=\"box\"/></film></sensor>\n<shape type=\"sphere\"><point \
             name=\"center\" x=\"0\" y=\"0\" z=\"3\"/><float name=\"radius\" value=\"0.5\"/>\
             <bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.3\"/></bsdf></shape>\n\
             <emitter type=\"constant\"><rgb name=\"radiance\" value=\"1\"/></emitter>\n</scene>"
        )
    };
    for (near, seen) in [("0.01", 0.3), ("4", 1.0)] {
        let desc = load_mitsuba(&files(&format!("m-near-{near}"), &scene(near), &[]), &[]).unwrap();
        for backend in super::common::backends() {
            let options = super::common::options(&desc, backend, 16);
            let film = super::common::render_ok(&desc, &options).film;
            let centre = film.color[4 * 9 + 4];
            assert!((centre.x - seen).abs() < 0.05, "near {near} on {backend:?}: {centre}");
        }
    }
}

/// `embray info` and `embray convert` take `-D` as `render` does.
#[test]
fn info_and_convert_take_parameters() {
    let main = format!(
        "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" \
         value=\"40\"/>{SENSOR}\n<shape type=\"sphere\"/>\n</scene>"
    );
    let path = files("m-info-define", &main, &[]);
    let dir = path.parent().unwrap();
    let out = super::common::command::embray(&["info", "main.xml", "-D", "fov=30"], dir);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && stdout.contains("vfov 29.99999"), "{stdout}");
    let out = super::common::command::embray(
        &["convert", "main.xml", "-D", "fov=25", "-o", "scene.toml"],
        dir,
    );
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let toml = std::fs::read_to_string(dir.join("scene.toml")).unwrap();
    assert!(toml.contains("vfov = 25"), "{toml}");
}
