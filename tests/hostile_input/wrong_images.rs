//! Inputs that used to give a wrong image with exit 0: very bright pixels, coordinates
//! beyond the supported range (on both backends alike), huge offsets.

use crate::harness::{Scratch, accepted_in, refused_in, scene};

#[test]
fn a_blinding_emitter_is_white_not_black() {
    let scratch = Scratch::new();
    // The quad fills the view and emits 3e38: ACES used to compute inf / inf = NaN → black.
    let text = scene("").replace(
        "albedo = [0.5, 0.5, 0.5]",
        "albedo = [0.5, 0.5, 0.5]\nemission = [3e38, 3e38, 3e38]",
    );
    scratch.write("s.toml", text);
    accepted_in(&scratch, &["render", "s.toml", "-q"]);
    let png = image::open(scratch.path("s.png")).unwrap().to_rgb8();
    let centre = png.get_pixel(4, 4).0;
    assert_eq!(centre, [255, 255, 255], "the emitter's pixel");
}

fn refused_on_both_backends(text: &str, extra: &[&str], expected: &[&str]) {
    // Every backend this build has (both by default; obvhs alone without C libraries).
    for backend in embray::accel::BackendKind::compiled() {
        let backend = embray::choice::Choice::name(backend);
        let scratch = Scratch::new();
        scratch.write("s.toml", text);
        let mut args = vec!["render", "s.toml", "--backend", backend];
        args.extend_from_slice(extra);
        refused_in(&scratch, &args, expected);
    }
}

#[test]
fn a_floor_of_ten_billion_units_is_refused_on_both_backends() {
    let text = scene(
        "[[objects]]\ntype = \"quad\"\nmaterial = \"grey\"\ncorner = [-1e10, -1.0, -1e10]\n\
         u = [0.0, 0.0, 2e10]\nv = [2e10, 0.0, 0.0]\n",
    );
    refused_on_both_backends(
        &text,
        &[],
        &["s.toml", "objects[1] is 1.0", "from the camera", "coordinate range ±1e8", "(line 24)"],
    );
}

#[test]
fn an_instance_at_1e36_is_refused_on_both_backends() {
    let text = scene("").replace(
        "v = [2.0, 0.0, 0.0]",
        "v = [2.0, 0.0, 0.0]\ntransform = [{ translate = [1e36, 0.0, 0.0] }]",
    );
    refused_on_both_backends(
        &text,
        &[],
        &["s.toml", "objects[0] is 1e36", "coordinate range", "(line 13)"],
    );
}

#[test]
fn an_offset_of_1e19_is_refused_on_both_backends() {
    refused_on_both_backends(
        &scene(""),
        &["--offset", "1e19,0,0"],
        &["s.toml", "after --offset", "supported range"],
    );
}

#[test]
fn an_offset_of_1e300_is_refused() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    refused_in(&scratch, &["render", "s.toml", "--offset", "0,1e300,0"], &["supported range"]);
}

#[test]
fn an_offset_of_1e7_still_renders() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    accepted_in(&scratch, &["render", "s.toml", "--offset", "1e7,1e7,1e7", "-q"]);
}

#[test]
fn an_offset_of_1e11_renders_in_cameraworld_and_is_refused_in_world() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    accepted_in(&scratch, &["render", "s.toml", "--offset", "1e11,0,-1e11", "-q"]);
    refused_in(
        &scratch,
        &["render", "s.toml", "--offset", "1e11,0,-1e11", "--render-space", "world", "-q"],
        &["s.toml", "±1e8 (world render space", "render in cameraworld"],
    );
}

/// A mesh whose file holds a vertex out of range: the message names the mesh file as well as
/// the object (found by the loader property test, which once had only `objects[0]`).
#[test]
fn an_obj_vertex_at_4e10_names_the_mesh_file() {
    let scratch = Scratch::new();
    scratch.write("far.obj", "v 0 0 0\nv 1 0 0\nv 0 42949672960 0\nf 1 2 3\n");
    scratch.write(
        "s.toml",
        "[camera]\nlookfrom = [0.0, 0.0, 4.0]\nlookat = [0.0, 0.0, 0.0]\nvfov = 40.0\n\
         resolution = [8, 8]\n\n[[objects]]\ntype = \"mesh\"\nfile = \"far.obj\"\n",
    );
    refused_in(
        &scratch,
        &["render", "s.toml"],
        &[
            "s.toml",
            "objects[0] is 4.29",
            "(at the farthest corner of objects[0] (far.obj",
            "coordinate range",
            "line 7",
        ],
    );
}

/// A JPEG cut short decodes with its missing rows grey: `compare` measured a difference
/// against an image the file does not hold (a texture cut short was already refused).
#[test]
fn compare_refuses_a_jpeg_cut_short() {
    let scratch = Scratch::new();
    let noise =
        image::RgbImage::from_fn(64, 64, |x, y| image::Rgb([(x * 7) as u8, (y * 5) as u8, 9]));
    let mut jpeg = Vec::new();
    noise.write_to(&mut std::io::Cursor::new(&mut jpeg), image::ImageFormat::Jpeg).unwrap();
    scratch.write("whole.jpg", &jpeg);
    scratch.write("cut.jpg", &jpeg[..jpeg.len() * 2 / 3]);
    accepted_in(&scratch, &["compare", "whole.jpg", "whole.jpg"]);
    refused_in(&scratch, &["compare", "whole.jpg", "cut.jpg"], &["cut.jpg", "cut short"]);
}
