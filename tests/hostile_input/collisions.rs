//! Two outputs of one run, or an output and an input, that are the same file: refused before
//! anything is rendered, whatever the spelling (hard links, `./`, `..`, symbolic links).

use crate::harness::{Scratch, refused_cases, refused_in, scene, with_mesh};

refused_cases! {
    png_default_equal_to_the_exr: ["s.toml" => scene("")], ["render", "s.toml", "-o", "out.exr", "--png", "out.exr"]
        => ["-o 'out.exr'", "--png 'out.exr'", "same file"];
    exr_and_png_named_alike: ["s.toml" => scene("")], ["render", "s.toml", "-o", "x.exr", "--png", "x.exr"]
        => ["-o 'x.exr'", "--png 'x.exr'", "same file"];
    stats_json_over_the_exr: ["s.toml" => scene("")], ["render", "s.toml", "-o", "x.exr", "--stats-json", "x.exr"]
        => ["--stats-json 'x.exr'", "same file"];
    stats_json_over_the_default_png: ["s.toml" => scene("")], ["render", "s.toml", "--stats-json", "s.png"]
        => ["--stats-json 's.png'", "same file"];
    exr_over_the_scene: ["s.toml" => scene("")], ["render", "s.toml", "-o", "s.toml"]
        => ["-o 's.toml'", "the scene 's.toml'", "never overwrites its inputs"];
    png_over_the_scene: ["s.toml" => scene("")], ["render", "s.toml", "--png", "s.toml"]
        => ["--png 's.toml'", "an input of this run"];
    png_over_the_scene_spelt_differently: ["s.toml" => scene(""), "sub/keep" => ""], ["render", "s.toml", "--png", "sub/../s.toml"]
        => ["--png 'sub/../s.toml'", "an input of this run"];
    stats_json_over_the_scene: ["s.toml" => scene("")], ["render", "s.toml", "--stats-json", "./s.toml"]
        => ["--stats-json", "an input of this run"];
    convert_over_its_input: ["s.xml" => crate::harness::xml_scene(&["a.png"], "")], ["convert", "s.xml", "-o", "s.xml"]
        => ["-o 's.xml'", "the input scene", "never overwrites"];
    convert_over_its_input_spelt_differently: ["s.xml" => crate::harness::xml_scene(&["a.png"], "")], ["convert", "./s.xml", "-o", "s.xml"]
        => ["an input of this run"];
    one_camera_xml_exr_and_png_alike: ["s.xml" => crate::harness::xml_scene(&["a.png"], "")], ["render", "s.xml", "-o", "x.exr", "--png", "x.exr"]
        => ["same file"];
}

#[test]
fn heatmap_over_a_compared_image_is_refused() {
    let scratch = Scratch::new();
    let image = image::RgbImage::from_pixel(4, 4, image::Rgb([10, 20, 30]));
    image.save(scratch.path("a.png")).unwrap();
    image.save(scratch.path("b.png")).unwrap();
    for (heatmap, which) in [("a.png", "the first image"), ("./b.png", "the second image")] {
        refused_in(
            &scratch,
            &["compare", "a.png", "b.png", "--heatmap", heatmap],
            &["--heatmap", which, "never overwrites"],
        );
    }
}

#[test]
fn png_over_a_hard_link_of_the_scene_is_refused() {
    let scratch = Scratch::new();
    let scene_path = scratch.write("s.toml", scene(""));
    std::fs::hard_link(&scene_path, scratch.path("link.png")).unwrap();
    refused_in(&scratch, &["render", "s.toml", "--png", "link.png"], &["an input of this run"]);
}

#[test]
fn png_over_a_symbolic_link_to_the_scene_is_refused() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    std::os::unix::fs::symlink("s.toml", scratch.path("link.png")).unwrap();
    refused_in(&scratch, &["render", "s.toml", "--png", "link.png"], &["an input of this run"]);
}

const OBJ: &str = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";

refused_cases! {
    png_over_a_mesh_the_scene_reads: ["s.toml" => with_mesh("m.obj"), "m.obj" => OBJ, "m.mtl" => "newmtl red\nKd 1 0 0\n"], ["render", "s.toml", "--png", "m.obj"]
        => ["--png 'm.obj'", "a file the scene reads", "an input of this run"];
    stats_json_over_an_mtl_the_scene_reads: ["s.toml" => with_mesh("m.obj"), "m.obj" => OBJ, "m.mtl" => "newmtl red\nKd 1 0 0\n"], ["render", "s.toml", "--stats-json", "./m.mtl"]
        => ["--stats-json './m.mtl'", "an input of this run"];
}

#[test]
fn convergence_csv_over_its_reference_is_refused() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    crate::harness::accepted_in(&scratch, &["render", "s.toml", "-o", "ref.exr"]);
    let args = [
        "bench",
        "convergence",
        "s.toml",
        "--reference",
        "ref.exr",
        "--spps",
        "1",
        "--csv",
        "ref.exr",
    ];
    refused_in(
        &scratch,
        &args,
        &["--csv 'ref.exr'", "the reference 'ref.exr'", "never overwrites"],
    );
}

/// Two cameras whose images share a stem (`a.png`, `sub/a.png`) are converted to two TOML
/// files, each numbered by its camera, each rendering its own image: not refused as one file
/// colliding with itself.
#[test]
fn convert_of_cameras_whose_images_share_a_stem_writes_each() {
    let scratch = Scratch::new();
    scratch.write("s.xml", crate::harness::xml_scene(&["a.png", "sub/a.png"], ""));
    crate::harness::accepted_in(&scratch, &["convert", "s.xml", "-o", "o.toml"]);
    for (k, image) in [(1, "a.png"), (2, "sub/a.png")] {
        let toml = std::fs::read_to_string(scratch.path(&format!("o_a_camera{k}.toml"))).unwrap();
        assert!(toml.contains(&format!("(camera '{image}')")), "{toml}");
    }
    assert!(!scratch.path("o_a.toml").exists());
}
