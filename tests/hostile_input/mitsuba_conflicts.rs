//! Mitsuba scenes the fourth probe found read differently from Mitsuba: a colour given as a
//! number ignored, parameters that conflict (one silently winning), embray's own TOML names
//! taken by Mitsuba plugins, attributes no Mitsuba element takes. Each is now read as Mitsuba
//! reads it or refused with the file, line and element.

use crate::harness::{Scratch, accepted_in, refused_cases, refused_in};

/// An 8×8 Mitsuba scene at 1 spp whose sensor holds `sensor` (line 2) and whose body is
/// `body` (from line 3 on).
fn with_sensor(sensor: &str, body: &str) -> String {
    format!(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">{sensor}<film type=\"hdrfilm\">\
         <integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/></film>\
         <sampler type=\"independent\"><integer name=\"sample_count\" value=\"1\"/></sampler>\
         </sensor>\n{body}\n</scene>\n"
    )
}

/// `with_sensor` with a plain sensor: `body` starts at line 3.
fn m3(body: &str) -> String {
    with_sensor("", body)
}

/// A sphere with the BSDF `bsdf` (on line 3).
fn sphere(bsdf: &str) -> String {
    m3(&format!("<shape type=\"sphere\">{bsdf}</shape>"))
}

const LOOKAT: &str = r#"<lookat origin="0,0,-5" target="0,0,0" up="0,1,0"/>"#;

refused_cases! {
    string_reflectance: ["s.xml" => sphere(r#"<bsdf type="diffuse"><string name="reflectance" value="0.5"/></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "<string name=\"reflectance\">", "must be a colour", "(line 3)"];
    principled_sampling_rates_all_zero: ["s.xml" => sphere(r#"<bsdf type="principled"><float name="main_specular_sampling_rate" value="0"/><float name="clearcoat_sampling_rate" value="0"/><float name="diffuse_reflectance_sampling_rate" value="0"/></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "every *_sampling_rate is 0", "at least one lobe", "line 3"];
    boolean_base_color: ["s.xml" => sphere(r#"<bsdf type="principled"><boolean name="base_color" value="true"/></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "`base_color` must be a colour", "(line 3)"];
    vector_diffuse_reflectance: ["s.xml" => sphere(r#"<bsdf type="roughplastic"><vector name="diffuse_reflectance" value="0.1, 0.2, 0.3"/></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "not a <vector>", "(line 3)"];
    float_reflectance_past_one: ["s.xml" => sphere(r#"<bsdf type="diffuse"><float name="reflectance" value="1.5"/></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "a reflectance must be in [0, 1]", "(line 3)"];
    float_point_intensity_negative_is_named: ["s.xml" => m3(r#"<emitter type="point"><float name="intensity" value="-2"/></emitter>"#)], ["info", "s.xml"]
        => ["s.xml", "intensity", ">= 0", "(line 3)"];
    string_constant_radiance: ["s.xml" => m3(r#"<emitter type="constant"><string name="radiance" value="1"/></emitter>"#)], ["info", "s.xml"]
        => ["s.xml", "`radiance` must be a colour", "(line 3)"];
    checkerboard_float_colour_past_one: ["s.xml" => sphere(r#"<bsdf type="diffuse"><texture type="checkerboard" name="reflectance"><float name="color0" value="5"/></texture></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "<float name=\"color0\">", "must be in [0, 1]", "(line 3)"];
    checkerboard_float_colour_negative: ["s.xml" => sphere(r#"<bsdf type="principled"><texture type="checkerboard" name="roughness"><float name="color1" value="-5"/></texture></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "<float name=\"color1\">", "must be in [0, 1]", "(line 3)"];
    envmap_takes_no_toml_file: ["s.xml" => m3(r#"<emitter type="envmap"><string name="filename" value="a.exr"/><string name="file" value="b.exr"/></emitter>"#)], ["info", "s.xml"]
        => ["s.xml", "the envmap emitter does not take `file`", "(line 3)"];
    envmap_takes_no_toml_encoding: ["s.xml" => m3(r#"<emitter type="envmap"><string name="filename" value="a.exr"/><string name="encoding" value="raw"/></emitter>"#)], ["info", "s.xml"]
        => ["s.xml", "does not take `encoding`", "(line 3)"];
    spot_takes_no_toml_direction: ["s.xml" => m3(&format!(r#"<emitter type="spot"><transform name="to_world">{LOOKAT}</transform><vector name="direction" value="0,0,1"/></emitter>"#))], ["info", "s.xml"]
        => ["s.xml", "the spot emitter does not take `direction`", "(line 3)"];
    spot_takes_no_toml_falloff: ["s.xml" => m3(&format!(r#"<emitter type="spot"><transform name="to_world">{LOOKAT}</transform><float name="falloff_angle" value="10"/></emitter>"#))], ["info", "s.xml"]
        => ["s.xml", "does not take `falloff_angle`", "(line 3)"];
    constant_takes_no_file: ["s.xml" => m3(r#"<emitter type="constant"><string name="file" value="a.exr"/></emitter>"#)], ["info", "s.xml"]
        => ["s.xml", "the constant emitter does not take `file`", "(line 3)"];
    twosided_dielectric: ["s.xml" => sphere(r#"<bsdf type="twosided"><bsdf type="dielectric"/></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "<bsdf type=\"twosided\">", "cannot hold a transmitting BSDF", "(line 3)"];
    twosided_roughdielectric: ["s.xml" => sphere(r#"<bsdf type="twosided"><bsdf type="roughdielectric"/></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "cannot hold a transmitting BSDF", "(line 3)"];
    twosided_mask: ["s.xml" => sphere(r#"<bsdf type="twosided"><bsdf type="mask"><bsdf type="diffuse"/></bsdf></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "cannot hold a transmitting BSDF", "(line 3)"];
    twosided_blend_with_glass: ["s.xml" => sphere(r#"<bsdf type="twosided"><bsdf type="blendbsdf"><float name="weight" value="0.5"/><bsdf type="diffuse"/><bsdf type="dielectric"/></bsdf></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "cannot hold a transmitting BSDF", "(line 3)"];
    twosided_allowing_transmission: ["s.xml" => sphere(r#"<bsdf type="twosided"><boolean name="allow_transmission" value="true"/><bsdf type="dielectric"/></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "allow_transmission is not supported", "(line 3)"];
    conductor_material_and_eta: ["s.xml" => sphere(r#"<bsdf type="conductor"><string name="material" value="Au"/><rgb name="eta" value="0.2"/></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "<rgb name=\"eta\">", "either (eta, k) or material, not both", "(line 3)"];
    roughconductor_material_and_k: ["s.xml" => sphere(r#"<bsdf type="roughconductor"><string name="material" value="Au"/><rgb name="k" value="3"/></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "<rgb name=\"k\">", "either (eta, k) or material, not both", "(line 3)"];
    conductor_k_without_eta_checked: ["s.xml" => sphere(r#"<bsdf type="conductor"><rgb name="k" value="inf"/></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "<rgb name=\"k\">", "not a finite number", "(line 3)"];
    conductor_k_of_text: ["s.xml" => sphere(r#"<bsdf type="conductor"><string name="k" value="3"/></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "`k` must be a colour", "(line 3)"];
    two_area_emitters: ["s.xml" => m3("<shape type=\"sphere\">\n<emitter type=\"area\"/>\n<emitter type=\"area\"><rgb name=\"radiance\" value=\"9\"/></emitter></shape>")], ["info", "s.xml"]
        => ["s.xml", "<shape type=\"sphere\"> takes one <emitter>", "(line 5)"];
    point_position_and_to_world: ["s.xml" => m3(r#"<emitter type="point"><point name="position" value="0,0,-2"/><transform name="to_world"><translate z="2"/></transform></emitter>"#)], ["info", "s.xml"]
        => ["s.xml", "<emitter type=\"point\">", "`position` or a to_world, not both", "(line 3)"];
    directional_direction_and_to_world: ["s.xml" => m3(r#"<emitter type="directional"><vector name="direction" value="0,0,1"/><transform name="to_world"><rotate y="1" angle="90"/></transform></emitter>"#)], ["info", "s.xml"]
        => ["s.xml", "`direction` or a to_world, not both", "(line 3)"];
    sensor_scaled: ["s.xml" => with_sensor(&format!(r#"<transform name="to_world"><scale value="2"/>{LOOKAT}</transform>"#), "")], ["info", "s.xml"]
        => ["s.xml", "<transform name=\"to_world\">", "scale factors", "(line 2)"];
    sensor_sheared: ["s.xml" => with_sensor(r#"<transform name="to_world"><matrix value="1 0.5 0 0  0 1 0 0  0 0 1 0  0 0 0 1"/></transform>"#, "")], ["info", "s.xml"]
        => ["s.xml", "scale factors", "(line 2)"];
    sensor_fov_and_focal_length: ["s.xml" => with_sensor(r#"<float name="fov" value="45"/><string name="focal_length" value="50mm"/>"#, "")], ["info", "s.xml"]
        => ["s.xml", "<string name=\"focal_length\">", "either fov or focal_length, not both", "(line 2)"];
    sensor_focal_length_as_a_number: ["s.xml" => with_sensor(r#"<float name="focal_length" value="50"/>"#, "")], ["info", "s.xml"]
        => ["s.xml", "`focal_length` must be a <string>", "(line 2)"];
    projector_fov_and_focal_length: ["s.xml" => m3(&format!(r#"<emitter type="projector"><transform name="to_world">{LOOKAT}</transform><float name="fov" value="30"/><string name="focal_length" value="50mm"/></emitter>"#))], ["info", "s.xml"]
        => ["s.xml", "either fov or focal_length, not both", "(line 3)"];
    projector_negative_irradiance: ["s.xml" => m3(&format!(r#"<emitter type="projector"><transform name="to_world">{LOOKAT}</transform><rgb name="irradiance" value="-1"/></emitter>"#))], ["info", "s.xml"]
        => ["s.xml", "<rgb name=\"irradiance\">", "irradiance is", "must be >= 0", "(line 3)"];
    projector_negative_scale: ["s.xml" => m3(&format!(r#"<emitter type="projector"><transform name="to_world">{LOOKAT}</transform><float name="scale" value="-1"/></emitter>"#))], ["info", "s.xml"]
        => ["s.xml", "<float name=\"scale\">", "scale is -1, but must be >= 0", "(line 3)"];
    bitmap_filter_type_unknown: ["s.xml" => sphere(r#"<bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="t.png"/><string name="filter_type" value="bogus"/></texture></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "the filter_type 'bogus' is not known (bilinear, nearest)", "(line 3)"];
    bitmap_filter_type_as_a_number: ["s.xml" => sphere(r#"<bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="t.png"/><integer name="filter_type" value="0"/></texture></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "`filter_type` must be a <string>", "(line 3)"];
    bitmap_format_unknown: ["s.xml" => sphere(r#"<bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="t.png"/><string name="format" value="bogus"/></texture></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "the format 'bogus' is not known", "(line 3)"];
    bitmap_rgbe_without_header_end: ["s.xml" => sphere(r#"<bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="t.hdr"/></texture></bsdf>"#), "t.hdr" => "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n"], ["info", "s.xml"]
        => ["s.xml", "t.hdr", "not a readable Radiance RGBE file", "(line 3)"];
    envmap_rgbe_cut_short: ["s.xml" => m3(r#"<emitter type="envmap"><string name="filename" value="sky.hdr"/></emitter>"#), "sky.hdr" => "#?RADIANCE\n\n-Y 4 +X 4\n\u{80}\u{80}"], ["info", "s.xml"]
        => ["s.xml", "sky.hdr", "broken Radiance RGBE file", "(line 3)"];
    point_value_and_z: ["s.xml" => m3("<shape type=\"sphere\"><point name=\"center\" value=\"0,0,1\" z=\"-1\"/></shape>")], ["info", "s.xml"]
        => ["s.xml", "<point name=\"center\">", "give `value` or `x`/`y`/`z`, not both", "(line 3)"];
    translate_value_and_z: ["s.xml" => m3("<shape type=\"sphere\"><transform name=\"to_world\">\n<translate value=\"0 0 1\" z=\"-1\"/></transform></shape>")], ["info", "s.xml"]
        => ["s.xml", "<translate>", "not both", "(line 4)"];
    unknown_attribute_on_a_float: ["s.xml" => m3("<shape type=\"sphere\"><float name=\"radius\" value=\"1\" foo=\"bar\"/></shape>")], ["info", "s.xml"]
        => ["s.xml", "<float> does not take the attribute `foo` (it takes: name, value)", "(line 3)"];
    unknown_attribute_on_a_point: ["s.xml" => m3("<shape type=\"sphere\"><point name=\"center\" x=\"0\" y=\"0\" z=\"0\" w=\"5\"/></shape>")], ["info", "s.xml"]
        => ["s.xml", "does not take the attribute `w`", "(line 3)"];
    rotate_by_an_axis_attribute: ["s.xml" => m3("<shape type=\"sphere\"><transform name=\"to_world\">\n<rotate axis=\"1,0,0\" angle=\"30\"/></transform></shape>")], ["info", "s.xml"]
        => ["s.xml", "<rotate> does not take the attribute `axis`", "(line 4)"];
    point_missing_a_coordinate: ["s.xml" => m3("<shape type=\"sphere\"><point name=\"center\" x=\"1\" y=\"0\"/></shape>")], ["info", "s.xml"]
        => ["s.xml", "the attribute `z` is missing", "(line 3)"];
    sample_count_past_the_limit: ["s.xml" => m3("").replace("name=\"sample_count\" value=\"1\"", "name=\"sample_count\" value=\"2000000\"")], ["info", "s.xml"]
        => ["s.xml", "<integer name=\"sample_count\">", "sample_count is 2000000, but must be 1 to 1048576", "(line 2)"];
    film_width_as_text: ["s.xml" => m3("").replace("<integer name=\"width\" value=\"8\"/>", "<string name=\"width\" value=\"8\"/>")], ["info", "s.xml"]
        => ["s.xml", "`width` must be an <integer>", "(line 2)"];
    version_not_a_version: ["s.xml" => m3("").replace("3.0.0", "banana")], ["info", "s.xml"]
        => ["s.xml", "the version 'banana' is not a version number", "(line 1)"];
    ply_shape_given_an_obj: ["s.xml" => m3(r#"<shape type="ply"><string name="filename" value="m.obj"/></shape>"#)], ["info", "s.xml"]
        => ["s.xml", "<shape type=\"ply\"> given a .obj file (use <shape type=\"obj\">)", "(line 3)"];
    serialized_shape_given_a_ply: ["s.xml" => m3(r#"<shape type="serialized"><string name="filename" value="m.PLY"/></shape>"#)], ["info", "s.xml"]
        => ["s.xml", "use <shape type=\"ply\">", "(line 3)"];
    conductor_textured_specular_reflectance: ["s.xml" => sphere(r#"<bsdf type="conductor"><string name="material" value="Ag"/><texture type="checkerboard" name="specular_reflectance"/></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "<texture", "a textured `specular_reflectance` is not supported", "(line 3)"];
    roughconductor_referenced_specular_reflectance: ["s.xml" => m3("<texture type=\"checkerboard\" id=\"t\"/>\n<shape type=\"sphere\"><bsdf type=\"roughconductor\"><ref name=\"specular_reflectance\" id=\"t\"/></bsdf></shape>")], ["info", "s.xml"]
        => ["s.xml", "a textured `specular_reflectance` is not supported", "(line 4)"];
    area_radiance_pairs_negative: ["s.xml" => m3(r#"<shape type="sphere"><emitter type="area"><spectrum name="radiance" value="400:-5, 700:-5"/></emitter></shape>"#)], ["info", "s.xml"]
        => ["s.xml", "<spectrum name=\"radiance\"", "`radiance` is -5 at 400 nm, but must be >= 0", "(line 3)"];
    constant_radiance_pairs_negative: ["s.xml" => m3(r#"<emitter type="constant"><spectrum name="radiance" value="400:1, 500:-0.5, 700:1"/></emitter>"#)], ["info", "s.xml"]
        => ["s.xml", "`radiance` is -0.5 at 500 nm, but must be >= 0", "(line 3)"];
    reflectance_pairs_past_one: ["s.xml" => sphere(r#"<bsdf type="diffuse"><spectrum name="reflectance" value="400:5, 700:5"/></bsdf>"#)], ["info", "s.xml"]
        => ["s.xml", "`reflectance` is 5 at 400 nm, but must be in [0, 1]", "(line 3)"];
    reflectance_spd_past_one: ["s.xml" => sphere(r#"<bsdf type="diffuse"><spectrum name="reflectance" filename="big.spd"/></bsdf>"#), "big.spd" => "400 0.5\n700 5\n"], ["info", "s.xml"]
        => ["s.xml", "`reflectance` is 5 at 700 nm, but must be in [0, 1]", "(line 3)"];
    radiance_spd_negative: ["s.xml" => m3(r#"<shape type="sphere"><emitter type="area"><spectrum name="radiance" filename="neg.spd"/></emitter></shape>"#), "neg.spd" => "400 -5\n700 -5\n"], ["info", "s.xml"]
        => ["s.xml", "`radiance` is -5 at 400 nm, but must be >= 0", "(line 3)"];
    envmap_scaled: ["s.xml" => m3("<emitter type=\"envmap\"><string name=\"filename\" value=\"a.exr\"/>\n<transform name=\"to_world\"><scale value=\"2\"/></transform></emitter>")], ["info", "s.xml"]
        => ["s.xml", "an envmap's to_world must be a rotation", "not 2, 0, 0, 0, 2, 0, 0, 0, 2", "(line 4)"];
}

/// A number where Mitsuba takes a colour is a constant grey, for a BSDF and an emitter
/// alike, and a zero `up` makes Mitsuba pick one (both were silently replaced or refused).
#[test]
fn numbers_as_colours_and_a_zero_up_are_read_as_mitsuba_reads_them() {
    let scratch = Scratch::new();
    let body = "<shape type=\"sphere\"><bsdf type=\"diffuse\"><float name=\"reflectance\" \
                value=\"0.1\"/></bsdf></shape>\n<emitter type=\"constant\"><integer \
                name=\"radiance\" value=\"2\"/></emitter>\n<emitter type=\"point\"><float \
                name=\"intensity\" value=\"3\"/></emitter>\n<shape type=\"sphere\"><emitter \
                type=\"area\"><float name=\"radiance\" value=\"1\"/></emitter><transform \
                name=\"to_world\"><lookat origin=\"0,0,4\" target=\"0,0,0\" up=\"0,0,0\"/>\
                </transform></shape>";
    scratch.write("s.xml", m3(body));
    accepted_in(&scratch, &["info", "s.xml"]);
    // Mitsuba reads each number of the version as `stoul` does: a suffix is let through.
    scratch.write("dev.xml", m3("").replace("3.0.0", "3.0.0-dev"));
    accepted_in(&scratch, &["info", "dev.xml"]);
}

/// A Mitsuba bitmap may be an EXR file, read as TOML's textures read one (it was refused
/// as an unsupported image format).
#[test]
fn an_exr_bitmap_is_read() {
    let scratch = Scratch::new();
    scratch.write("sky.xml", m3("<emitter type=\"constant\"/>\n<shape type=\"sphere\"/>"));
    accepted_in(&scratch, &["render", "sky.xml", "-o", "t.exr", "--aovs", "none", "-q"]);
    let textured = "<shape type=\"sphere\"><bsdf type=\"diffuse\"><texture type=\"bitmap\" \
                    name=\"reflectance\"><string name=\"filename\" value=\"t.exr\"/><string \
                    name=\"filter_type\" value=\"nearest\"/></texture></bsdf></shape>";
    scratch.write("s.xml", m3(textured));
    accepted_in(&scratch, &["info", "s.xml"]);
    // The reader found the file: a missing one is still refused.
    scratch.write("m.xml", m3(&textured.replace("t.exr", "missing.exr")));
    refused_in(&scratch, &["info", "m.xml"], &["m.xml", "missing.exr", "(line 3)"]);
}
