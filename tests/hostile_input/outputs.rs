//! Output targets that are not plain new files: devices are written in place and never
//! replaced, links are followed or refused, long names work, a full disk is an error that
//! leaves every earlier file as it was.

use crate::harness::{Scratch, accepted_in, assert_no_temp_files, refused_in, run_limited, scene};
use std::os::unix::fs::FileTypeExt;
use std::path::Path;

fn is_char_device(path: &str) -> bool {
    std::fs::metadata(path).unwrap().file_type().is_char_device()
}

/// A folder with a scene and the outputs of an earlier good run (out.exr, out.png).
fn with_earlier_outputs() -> Scratch {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    scratch.write("out.exr", "earlier exr");
    scratch.write("out.png", "earlier png");
    scratch
}

#[test]
fn dev_null_is_written_in_place_not_replaced() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    accepted_in(&scratch, &["render", "s.toml", "-o", "/dev/null", "--png", "/dev/null", "-q"]);
    assert!(is_char_device("/dev/null"));
    assert!(!Path::new("/dev/null.png").exists());
}

#[test]
fn dev_null_without_a_png_name_is_refused() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    refused_in(&scratch, &["render", "s.toml", "-o", "/dev/null"], &["-o '/dev/null'", "--png"]);
    assert!(is_char_device("/dev/null") && !Path::new("/dev/null.png").exists());
}

#[test]
fn dev_full_as_the_exr_is_an_error_and_nothing_changes() {
    let scratch = with_earlier_outputs();
    refused_in(
        &scratch,
        &["render", "s.toml", "-o", "/dev/full", "--png", "out.png"],
        &["/dev/full", "No space left on device"],
    );
    assert!(is_char_device("/dev/full"));
}

#[test]
fn a_failing_png_commits_no_exr() {
    let scratch = with_earlier_outputs();
    refused_in(
        &scratch,
        &["render", "s.toml", "-o", "out.exr", "--png", "/dev/full"],
        &["/dev/full", "No space left on device"],
    );
}

#[test]
fn a_failing_stats_json_commits_no_image() {
    let scratch = with_earlier_outputs();
    refused_in(
        &scratch,
        &["render", "s.toml", "-o", "out.exr", "--stats-json", "/dev/full"],
        &["/dev/full", "No space left"],
    );
}

#[test]
fn a_dangling_symbolic_link_is_refused_not_replaced() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    std::os::unix::fs::symlink("missing/x.exr", scratch.path("out.exr")).unwrap();
    refused_in(
        &scratch,
        &["render", "s.toml", "-o", "out.exr"],
        &["-o 'out.exr'", "symbolic link"],
    );
}

#[test]
fn a_symbolic_link_to_a_file_is_followed_and_kept() {
    let scratch = with_earlier_outputs();
    std::os::unix::fs::symlink("out.png", scratch.path("link.png")).unwrap();
    accepted_in(&scratch, &["render", "s.toml", "-o", "new.exr", "--png", "link.png", "-q"]);
    assert!(std::fs::symlink_metadata(scratch.path("link.png")).unwrap().file_type().is_symlink());
    assert!(image::open(scratch.path("out.png")).is_ok(), "the link's target holds the PNG");
}

#[test]
fn a_directory_as_output_is_refused() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    std::fs::create_dir(scratch.path("d.exr")).unwrap();
    refused_in(&scratch, &["render", "s.toml", "-o", "d.exr"], &["-o 'd.exr'", "is a directory"]);
}

#[test]
fn an_output_in_a_missing_folder_is_refused() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    refused_in(
        &scratch,
        &["render", "s.toml", "-o", "nowhere/x.exr"],
        &["nowhere", "No such file"],
    );
}

#[test]
fn a_245_character_name_works() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    let name = format!("{}.exr", "n".repeat(241));
    let png = format!("{}.png", "n".repeat(241));
    accepted_in(&scratch, &["render", "s.toml", "-o", &name, "-q"]);
    assert!(scratch.path(&name).is_file() && scratch.path(&png).is_file());
}

#[test]
fn a_name_longer_than_the_system_allows_is_refused() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    let name = format!("{}.exr", "n".repeat(300));
    refused_in(&scratch, &["render", "s.toml", "-o", &name], &["file names have at most 255"]);
}

#[test]
fn convert_writes_the_toml_and_its_meshes_together() {
    let scratch = Scratch::new();
    scratch.write("s.xml", crate::scenes::mirror_box_xml(1));
    accepted_in(&scratch, &["convert", "s.xml", "-o", "out/s.toml"]);
    assert!(scratch.path("out/s.toml").is_file());
    assert!(scratch.path("out/s_meshes/mesh_0.obj").is_file());
}

#[test]
fn a_full_disk_is_an_error_and_keeps_the_earlier_images() {
    let scratch = with_earlier_outputs();
    let before = scratch.snapshot();
    let run =
        run_limited(&scratch, &["render", "s.toml", "-o", "out.exr"], libc::RLIMIT_FSIZE, 200);
    run.assert_no_panic();
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    run.assert_says(&["cannot write", "File too large"]);
    assert_eq!(scratch.snapshot(), before);
}

#[test]
fn a_full_disk_while_writing_a_heat_map_is_an_error() {
    let scratch = Scratch::new();
    let noise = image::RgbImage::from_fn(64, 64, |x, y| {
        image::Rgb([((x * 37) ^ (y * 91)) as u8, (x * y) as u8, 7])
    });
    noise.save(scratch.path("a.png")).unwrap();
    image::RgbImage::new(64, 64).save(scratch.path("b.png")).unwrap();
    scratch.write("heat.png", "earlier heat map");
    let before = scratch.snapshot();
    let args = ["compare", "a.png", "b.png", "--heatmap", "heat.png"];
    let run = run_limited(&scratch, &args, libc::RLIMIT_FSIZE, 100);
    run.assert_no_panic();
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    run.assert_says(&["heat.png", "File too large"]);
    assert!(!run.stderr.contains("wrote"));
    assert_eq!(scratch.snapshot(), before);
    assert_no_temp_files(&scratch);
}
