//! Numbers in a file are checked before they are used: counts whose product wraps, part
//! counts that would size a table, images whose pixels are all NaN, empty images.

use crate::harness::{Run, Scratch, accepted_in, refused_cases, refused_in, scene, xml_scene};
use embray::film::Film;
use glam::Vec3;

/// An EXR of `width`×`height` pixels of `color`, with `bad` pixels (row order) set to `value`.
fn exr(scratch: &Scratch, name: &str, color: Vec3, bad: usize, value: f32) {
    let mut film = Film::new(8, 4);
    film.color.fill(color);
    for c in film.color.iter_mut().take(bad) {
        *c = Vec3::splat(value);
    }
    embray::output::write_exr(&film, &scratch.path(name)).unwrap();
}

#[test]
fn repeat_counts_whose_product_wraps_u64_are_refused_with_the_true_product() {
    // 2²² × 2²¹ × 2²¹ = 2⁶⁴: 0 in u64 arithmetic, under the copy limit.
    let scratch = Scratch::new();
    let text = scene("").replace(
        "v = [2.0, 0.0, 0.0]",
        "v = [2.0, 0.0, 0.0]\nrepeat = { count = [4194304, 2097152, 2097152], spacing = [1.0, 1.0, 1.0] }",
    );
    scratch.write("s.toml", text);
    refused_in(
        &scratch,
        &["render", "s.toml"],
        &["repeat.count", "4194304 × 2097152 × 2097152 = 18446744073709551616 copies"],
    );
}

#[test]
fn a_job_file_with_an_absurd_part_count_is_refused_before_it_sizes_anything() {
    let scratch = Scratch::new();
    let job = r#"{"embray": "/bin/embray", "scene": "/s.toml", "parts": 4000000000,
        "split": "tiles", "render_args": [], "sbatch": {"partition": null, "time": null,
        "cpus_per_task": 1, "max_running": null, "extra": []}, "submissions": []}"#;
    scratch.write("job/job.json", job);
    refused_in(&scratch, &["slurm", "status", "job"], &["parts is 4000000000", "1 to 100000"]);
}

#[test]
fn tonemap_of_an_exr_that_is_all_nan_is_refused_not_black() {
    let scratch = Scratch::new();
    exr(&scratch, "nan.exr", Vec3::ONE, 32, f32::NAN);
    refused_in(&scratch, &["tonemap", "nan.exr", "-o", "out.png"], &["every pixel", "nan.exr"]);
}

#[test]
fn tonemap_of_an_exr_with_some_nan_says_how_many_and_where() {
    let scratch = Scratch::new();
    exr(&scratch, "some.exr", Vec3::splat(0.5), 3, f32::INFINITY);
    let run = accepted_in(&scratch, &["tonemap", "some.exr", "-o", "out.png"]);
    run.assert_says(&["3 pixel(s) with a NaN or infinite value", "x 0, y 0"]);
    assert!(scratch.path("out.png").exists());
}

#[test]
fn compare_of_exrs_with_no_finite_pixel_in_common_is_refused_not_zero() {
    let scratch = Scratch::new();
    exr(&scratch, "a.exr", Vec3::ONE, 32, f32::NAN);
    exr(&scratch, "b.exr", Vec3::ONE, 0, 0.0);
    refused_in(
        &scratch,
        &["compare", "a.exr", "b.exr"],
        &["nothing to compare", "32 in the first"],
    );
}

#[test]
fn an_empty_exr_is_named_as_empty() {
    let scratch = Scratch::new();
    scratch.write("empty.exr", "");
    let run: Run =
        refused_in(&scratch, &["tonemap", "empty.exr", "-o", "out.png"], &["empty.exr", "empty"]);
    assert!(!run.stderr.contains("missing bytes"), "{}", run.stderr);
}

#[test]
fn a_lut_entry_of_ten_thousand_digits_is_quoted_short() {
    let scratch = Scratch::new();
    exr(&scratch, "in.exr", Vec3::splat(0.5), 0, 0.0);
    let huge = format!("1{}", "0".repeat(10_000));
    let mut lut = String::from("LUT_3D_SIZE 2\n");
    for i in 0..8 {
        lut += &if i == 5 { format!("0 {huge} 0\n") } else { "0 0 0\n".to_owned() };
    }
    scratch.write("look.cube", lut);
    let run = refused_in(
        &scratch,
        &["tonemap", "in.exr", "-o", "out.png", "--lut", "look.cube"],
        &["look.cube", "line 7", "is not finite"],
    );
    assert!(run.stderr.len() < 400, "the number was echoed whole: {} bytes", run.stderr.len());
}

/// `scene` with `fields` added to its camera.
fn camera_with(fields: &str) -> String {
    scene("").replace("resolution = [8, 8]", &format!("resolution = [8, 8]\n{fields}"))
}

// A lens beyond the coordinate range put ray origins beyond it (1e12) or traced no ray at
// all and gave a black image (1e20).
refused_cases! {
    lens_aperture_beyond_the_coordinate_range: ["s.toml" => camera_with("aperture = 1e12")], ["render", "s.toml"]
        => ["s.toml", "camera.aperture", "at most 1e8", "(line 6)"];
    lens_focal_length_over_f_number_beyond_it: ["s.toml" => camera_with("f_number = 1.0\nfocal_length = 1e20")], ["render", "s.toml"]
        => ["s.toml", "camera.f_number", "at most 1e8", "(line 6)"];
    lens_focus_distance_beyond_it: ["s.toml" => camera_with("aperture = 0.1\nfocus_distance = 1e39")], ["render", "s.toml"]
        => ["s.toml", "camera.focus_distance", "at most 1e8", "(line 7)"];
    lens_shift_beyond_it: ["s.toml" => camera_with("shift = [1e20, 0.0]")], ["render", "s.toml"]
        => ["s.toml", "camera.shift[0]", "in [-1e8, 1e8]", "(line 6)"];
    ceng795_aperture_size_beyond_it: ["s.xml" => xml_scene(&["a.png"], "").replace("<NearDistance>1</NearDistance>", "<NearDistance>1</NearDistance><ApertureSize>1e30</ApertureSize><FocusDistance>2</FocusDistance>")], ["render", "s.xml"]
        => ["s.xml", "ApertureSize", "at most 1e8", "(line 10)"];
}
