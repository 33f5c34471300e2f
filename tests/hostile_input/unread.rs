//! What the second and third probes of the binary found: input that panicked, or that was
//! dropped without a word (an area emitter's scale read as none, a light scaled out of f32's
//! range, a thin lens focused nowhere, a second integrator, a film parameter misspelt), now
//! refused with the file, line and field.

use crate::harness::{Scratch, accepted_in, refused_cases, refused_in, scene};

/// A Mitsuba scene: 8×8, a sphere, a constant sky, `sensor` as its sensor's opening tag
/// (closed by `</sensor>`), `film` inside its film and `extra` in the scene.
fn mitsuba(sensor: &str, film: &str, extra: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    {sensor}
        <film type="hdrfilm">
            <integer name="width" value="8"/><integer name="height" value="8"/>
            {film}
        </film>
    </sensor>
    <shape type="sphere"/>
    <emitter type="constant"/>
    {extra}
</scene>
"#
    )
}

const PERSPECTIVE: &str = r#"<sensor type="perspective">"#;

refused_cases! {
    gaussian_narrower_than_f32_holds: ["s.toml" => scene("").replace("spp = 1", "spp = 1\nfilter = { type = \"gaussian\", stddev = 1e-30 }")], ["render", "s.toml"]
        => ["s.toml", "render.filter.stddev", "[0.001, 16] pixels", "(line 9)"];
    mitsuba_gaussian_narrower_than_f32_holds: ["s.xml" => mitsuba(PERSPECTIVE, r#"<rfilter type="gaussian"><float name="stddev" value="1e-30"/></rfilter>"#, "")], ["render", "s.xml"]
        => ["s.xml", "stddev is 1e-30", "[0.001, 16] pixels", "line 5"];
    mitchell_negative_at_its_centre: ["s.xml" => mitsuba(PERSPECTIVE, r#"<rfilter type="mitchell"><float name="B" value="16"/><float name="C" value="-16"/></rfilter>"#, "")], ["render", "s.xml"]
        => ["s.xml", "not positive at its centre", "line 5"];
    thin_lens_focused_behind_it: ["s.xml" => mitsuba(r#"<sensor type="thinlens"><float name="aperture_radius" value="0.1"/><float name="focus_distance" value="-5"/>"#, "", "")], ["render", "s.xml"]
        => ["s.xml", "focus_distance is -5", "line 2"];
    thin_lens_aperture_beyond_the_coordinate_range: ["s.xml" => mitsuba(r#"<sensor type="thinlens"><float name="aperture_radius" value="1e12"/><float name="focus_distance" value="5"/>"#, "", "")], ["render", "s.xml"]
        => ["s.xml", "aperture_radius is 1000000000000", "at most 1e8", "line 2"];
    thin_lens_focused_beyond_the_coordinate_range: ["s.xml" => mitsuba(r#"<sensor type="thinlens"><float name="aperture_radius" value="0.1"/><float name="focus_distance" value="1e20"/>"#, "", "")], ["render", "s.xml"]
        => ["s.xml", "focus_distance is 100000000000000000000", "at most 1e8", "line 2"];
    principal_point_beyond_the_coordinate_range: ["s.xml" => mitsuba(r#"<sensor type="perspective"><float name="principal_point_offset_x" value="1e20"/>"#, "", "")], ["render", "s.xml"]
        => ["s.xml", "principal_point_offset_x is 100000000000000000000", "a shift of 1e8", "line 2"];
    area_radiance_past_f32: ["s.xml" => mitsuba(PERSPECTIVE, "", r#"<shape type="sphere"><emitter type="area"><rgb name="radiance" value="1e39, 1, 1"/></emitter></shape>"#)], ["render", "s.xml"]
        => ["s.xml", "`radiance` is 1e39, but must be within f32's range (±3.4e38)", "line 10"];
    rawconstant_reflectance_past_f32: ["s.xml" => mitsuba(PERSPECTIVE, "", r#"<shape type="sphere"><bsdf type="roughconductor"><texture type="rawconstant" name="alpha"><float name="value" value="-1e300"/></texture></bsdf></shape>"#)], ["render", "s.xml"]
        => ["s.xml", "`alpha` is -1e300, but must be within f32's range (±3.4e38)", "line 10"];
    projector_scaled_past_f32: ["s.xml" => mitsuba(PERSPECTIVE, "", r#"<emitter type="projector"><float name="scale" value="1e300"/></emitter>"#)], ["render", "s.xml"]
        => ["s.xml", "scale is 3.14159", "e300, but must be small enough for f32", "line 10"];
    box_filter_given_a_radius: ["s.xml" => mitsuba(PERSPECTIVE, r#"<rfilter type="box"><float name="radius" value="3"/></rfilter>"#, "")], ["render", "s.xml"]
        => ["s.xml", "the box filter does not take it", "its parameters: none", "line 5"];
    film_crop_past_u32: ["s.xml" => mitsuba(PERSPECTIVE, r#"<integer name="crop_width" value="99999999999"/>"#, "")], ["render", "s.xml"]
        => ["s.xml", "crop_width is 99999999999, but must be 0 to 4294967295"];
    scaled_area_radiance: ["s.xml" => mitsuba(PERSPECTIVE, "", r#"<shape type="sphere"><emitter type="area"><float name="scale" value="2"/></emitter></shape>"#)], ["render", "s.xml"]
        => ["s.xml", "an area emitter takes only its radiance", "line 10"];
    mesh_attribute_area_radiance: ["s.xml" => mitsuba(PERSPECTIVE, "", r#"<shape type="sphere"><emitter type="area"><texture type="mesh_attribute" name="radiance"><string name="name" value="vertex_color"/></texture></emitter></shape>"#)], ["render", "s.xml"]
        => ["s.xml", "cannot be a mesh_attribute", "line 10"];
    textured_constant_sky: ["s.xml" => mitsuba(PERSPECTIVE, "", "").replace(r#"<emitter type="constant"/>"#, r#"<emitter type="constant"><texture type="checkerboard" name="radiance"/></emitter>"#)], ["render", "s.xml"]
        => ["s.xml", "does not take a <texture> named `radiance`", "line 9"];
    pinhole_focus_not_a_number: ["s.xml" => mitsuba(r#"<sensor type="perspective"><float name="focus_distance" value="abc"/>"#, "", "")], ["render", "s.xml"]
        => ["s.xml", "'abc' is not a number", "line 2"];
    two_integrators: ["s.xml" => mitsuba(PERSPECTIVE, "", r#"<integrator type="path"/><integrator type="direct"/>"#)], ["render", "s.xml"]
        => ["s.xml", "a scene takes one <integrator>", "line 10"];
    film_typo: ["s.xml" => mitsuba(PERSPECTIVE, r#"<string name="pixel_fromat" value="rgb"/>"#, "")], ["render", "s.xml"]
        => ["s.xml", "the hdrfilm film does not take `pixel_fromat`", "line 5"];
    toml_array_longer_than_its_field: ["s.toml" => scene("").replace("[8, 8]", "[8, 8, \"junk\"]")], ["render", "s.toml"]
        => ["s.toml", "line 5", "invalid length 3, expected an array of length 2"];
    toml_colour_of_four: ["s.toml" => scene("").replace("albedo = [0.5, 0.5, 0.5]", "albedo = [0.5, 0.5, 0.5, 0.9]")], ["render", "s.toml"]
        => ["s.toml", "line 11", "invalid length 4, expected an array of length 3"];
    toml_matrix_row_of_five: ["s.toml" => scene("").replace("v = [2.0, 0.0, 0.0]", "v = [2.0, 0.0, 0.0]\ntransform = [{ matrix = [[1.0, 0, 0, 0, 9], [0, 1.0, 0, 0], [0, 0, 1.0, 0], [0, 0, 0, 1.0]] }]")], ["render", "s.toml"]
        => ["s.toml", "invalid length 5, expected an array of length 4"];
    toml_tonemap_key_zero: ["s.toml" => scene("").replace("spp = 1", "spp = 1\ntonemap = { operator = \"photographic\", key = 0 }")], ["render", "s.toml"]
        => ["s.toml", "render.tonemap.key is 0, but must be > 0", "(line 9)"];
    environment_scaled_past_f32: ["s.toml" => scene("[[lights]]\ntype = \"environment\"\nradiance = [1e38, 1e38, 1e38]\nscale = [10.0, 10.0, 10.0]\n")], ["render", "s.toml"]
        => ["s.toml", "scale", "within f32's range"];
}

/// A clipping camera's planes survive `convert` (they were dropped) and load back.
#[test]
fn converting_keeps_the_clip_planes() {
    let scratch = Scratch::new();
    let clipped = r#"<sensor type="perspective"><float name="near_clip" value="5.2"/>"#;
    scratch.write("s.xml", mitsuba(clipped, "", ""));
    accepted_in(&scratch, &["convert", "s.xml", "-o", "s.toml"]);
    let toml = std::fs::read_to_string(scratch.path("s.toml")).unwrap();
    assert!(toml.contains("clip = [5.2, 10000.0]"), "{toml}");
    accepted_in(&scratch, &["info", "s.toml"]);
    let reversed = toml.replace("clip = [5.2, 10000.0]", "clip = [5.2, 1.0]");
    scratch.write("r.toml", reversed);
    refused_in(&scratch, &["info", "r.toml"], &["r.toml", "camera.clip", "0 <= near < far"]);
}

/// A transform render space cannot hold is refused by the compiler, which now names the
/// scene file (the object names its line), once.
#[test]
fn a_compile_error_names_the_file_once() {
    let scratch = Scratch::new();
    let singular = r#"<shape type="cube"><transform name="to_world"><scale x="1e-200" y="1" z="1"/></transform></shape>"#;
    scratch.write("s.xml", mitsuba(PERSPECTIVE, "", singular));
    let run =
        refused_in(&scratch, &["render", "s.xml"], &["s.xml: <shape type=\"cube\"> (line 10)"]);
    assert_eq!(run.stderr.matches("transform is singular").count(), 1, "{}", run.stderr);
}

/// What `convert` cannot write is named with the scene file and the material (it said only
/// "a texture").
#[test]
fn convert_names_the_scene_and_material_it_cannot_write() {
    let scratch = Scratch::new();
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/mitsuba/materials.xml");
    let expected = ["materials.xml: material 'floor': a texture:", "cannot express"];
    refused_in(&scratch, &["convert", scene, "-o", "m.toml"], &expected);
}
