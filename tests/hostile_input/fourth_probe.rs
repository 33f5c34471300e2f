//! What the fourth probe of the binary found: an exposure past f32's range that turned black
//! pixels white, a spawn offset that put every ray outside the scene, a variance file named
//! as the reference, and a near-singular matrix reported with its determinant as 335 digits
//! (or a regular one of columns far apart in size as singular, "determinant 1"), a Mitsuba
//! `<default>` without a name and a `$` without one, and lights too small for f32 to hold
//! their area (they rendered as nothing), now refused or named as they are.

use crate::harness::{Run, Scratch, accepted_in, refused_cases, refused_in, scene};
use crate::scenes::MITSUBA_WITH_SPP;

const NEAR_SINGULAR: &str = "[[1e200, 0, 0, 0], [0, 1e-200, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]";

refused_cases! {
    exposure_past_f32: ["s.toml" => scene("")], ["render", "s.toml", "-o", "s.png", "--exposure", "128"]
        => ["--exposure is 128", "[-64, 64]"];
    matrix_of_columns_far_apart_in_size: ["s.toml" => scene("").replace("v = [2.0, 0.0, 0.0]", &format!("v = [2.0, 0.0, 0.0]\ntransform = [{{ matrix = {NEAR_SINGULAR} }}]"))], ["render", "s.toml"]
        => ["s.toml", "the composed transform is singular in f32"];
    matrix_of_nearly_parallel_columns: ["s.toml" => scene("").replace("v = [2.0, 0.0, 0.0]", "v = [2.0, 0.0, 0.0]\ntransform = [{ matrix = [[1, 1, 0, 0], [0, 1e-14, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]] }]")], ["render", "s.toml"]
        => ["s.toml", "matrix is singular (determinant 1e-14, but its columns are nearly parallel)"];
    constant_sky_past_f32_over_the_sphere: ["s.toml" => scene("[[lights]]\ntype = \"environment\"\nradiance = [1e38, 1e38, 1e38]\n")], ["render", "s.toml"]
        => ["s.toml", "radiance is [1e38, 1e38, 1e38]", "4π × scale × radiance"];
    mitsuba_default_without_a_name: ["s.xml" => MITSUBA_WITH_SPP.replace("name=\"spp\"", "name=\"\"")], ["render", "s.xml"]
        => ["s.xml", "a <default> needs a name (it is empty)", "line 2"];
    mitsuba_dollar_without_a_name: ["s.xml" => MITSUBA_WITH_SPP.replace("$spp", "$")], ["render", "s.xml"]
        => ["s.xml", "a `$` must be followed by a parameter's name", "line 4"];
    quad_too_small_for_f32: ["s.toml" => scene("").replace("u = [0.0, 2.0, 0.0]", "u = [0.0, 1e-30, 0.0]").replace("v = [2.0, 0.0, 0.0]", "v = [1e-30, 0.0, 0.0]")], ["render", "s.toml"]
        => ["s.toml", "span an area of 1.0000000000000001e-60, too small for f32"];
    sphere_light_too_small_for_f32: ["s.toml" => scene("[[lights]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1e-37\nemission = [1.0, 1.0, 1.0]\n")], ["render", "s.toml"]
        => ["s.toml", "lights[1].radius is", "but must be > 0 and at least 1.0842021724855044e-19"];
    first_image_unreadable: ["a.exr" => "not an image", "b.exr" => "not an image"], ["compare", "a.exr", "b.exr"]
        => ["cannot read the first image 'a.exr'"];
}

/// An offset past the coordinate range is a usage error (exit 2, as every option clap
/// refuses), named with the range.
#[test]
fn a_spawn_offset_past_the_coordinate_range_is_refused() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    let run = Run::from(
        scratch.command(&["render", "s.toml", "--spawn", "epsilon=1e30"]).output().unwrap(),
    );
    run.assert_no_panic();
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    run.assert_says(&["'1e30' is beyond the coordinate range", "at most 1e8"]);
    assert!(!scratch.path("s.exr").exists());
}

/// `tonemap` checks its own exposure, shown in scientific notation when huge.
#[test]
fn tonemap_exposure_past_f32_is_refused() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    accepted_in(&scratch, &["render", "s.toml", "-o", "a.exr"]);
    let args = ["tonemap", "a.exr", "-o", "t.png", "--exposure", "-1e30"];
    refused_in(&scratch, &args, &["--exposure is -1e30", "[-64, 64]"]);
}

/// Each file of a Mitsuba-rule comparison is named by its role when it cannot be read.
#[test]
fn an_unreadable_variance_is_named_as_the_variance() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    accepted_in(&scratch, &["render", "s.toml", "-o", "a.exr"]);
    scratch.write("v.exr", "not an image");
    let args = ["compare", "a.exr", "a.exr", "--variance", "v.exr", "--spp", "1"];
    refused_in(&scratch, &args, &["cannot read the variance 'v.exr'"]);
    refused_in(&scratch, &["tonemap", "v.exr", "-o", "t.png"], &["cannot read the input 'v.exr'"]);
}

/// Parameters substitute as in Mitsuba: the longest name first, any name a `<default>` gives
/// (a `.` in it too), an escaped `\$` left a dollar sign.
#[test]
fn mitsuba_parameters_substitute_longest_first() {
    let scratch = Scratch::new();
    let xml = MITSUBA_WITH_SPP
        .replace(r#"<default name="spp" value="1"/>"#, r#"<default name="spp" value="1"/><default name="w" value="4"/><default name="w_x" value="6"/><default name="spp.hi" value="\$9"/>"#)
        .replace(r#"name="width" value="8""#, r#"name="width" value="$w_x""#)
        .replace(r#"name="height" value="8""#, r#"name="height" value="$w""#);
    scratch.write("s.xml", xml);
    let run = accepted_in(&scratch, &["info", "s.xml"]);
    assert!(run.stdout.contains("camera: 6x4"), "{}", run.stdout);
}
