//! `embray render --part` and `embray merge` as a user runs them: the merged EXR is the
//! whole render's, byte for byte; parts that do not make one render are refused with a
//! message naming the problem, a non-zero exit and no output.

mod common;

use common::command::{GOOD_SCENE, TempDir, embray, temp_dir};
use embray::render::TILE_SIZE;
use std::path::Path;

fn ok(args: &[&str], dir: &Path) {
    let out = embray(args, dir);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
}

/// The image's size: three tiles across (the last one cut), two down (the lower one cut).
const WIDTH: u32 = 2 * TILE_SIZE + TILE_SIZE / 2;
const HEIGHT: u32 = TILE_SIZE + TILE_SIZE / 2;

/// Three tiles across, and four samples a pixel.
fn scene() -> String {
    let resolution = format!("resolution = [{WIDTH}, {HEIGHT}]");
    format!("{}\n[render]\nspp = 4\n", GOOD_SCENE.replace("resolution = [16, 12]", &resolution))
}

/// A folder with the scene, its whole render, and its three tile parts.
fn rendered(name: &str) -> TempDir {
    let dir = temp_dir(name);
    std::fs::write(dir.join("scene.toml"), scene()).unwrap();
    ok(&["render", "scene.toml", "-q", "-o", "whole.exr"], &dir);
    for i in 0..3 {
        let part = format!("{i}/3");
        ok(&["render", "scene.toml", "-q", "--part", &part, "-o", &format!("p{i}.exr")], &dir);
    }
    dir
}

fn assert_refused(dir: &Path, parts: &[&str], expected: &[&str]) {
    let mut args = vec!["merge"];
    args.extend(parts);
    args.extend(["-o", "merged.exr", "--png", "merged.png"]);
    let out = embray(&args, dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{parts:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    for text in expected {
        assert!(stderr.contains(text), "{parts:?}: '{text}' not in: {stderr}");
    }
    assert!(!dir.join("merged.exr").exists() && !dir.join("merged.png").exists());
}

#[test]
fn merged_parts_are_the_whole_render_byte_for_byte() {
    let dir = rendered("same");
    ok(&["merge", "p2.exr", "p0.exr", "p1.exr", "-o", "merged.exr", "--png", "merged.png"], &dir);
    let whole = std::fs::read(dir.join("whole.exr")).unwrap();
    assert_eq!(std::fs::read(dir.join("merged.exr")).unwrap(), whole);
    assert_eq!(
        std::fs::read(dir.join("merged.png")).unwrap(),
        std::fs::read(dir.join("whole.png")).unwrap()
    );
    for i in 0..2 {
        let part = format!("{i}/2");
        let path = format!("s{i}.exr");
        ok(
            &["render", "scene.toml", "-q", "--part", &part, "--split", "samples", "-o", &path],
            &dir,
        );
    }
    ok(&["merge", "s0.exr", "s1.exr", "-o", "merged-s.exr"], &dir);
    assert_eq!(std::fs::read(dir.join("merged-s.exr")).unwrap(), whole);
}

#[test]
fn parts_that_do_not_make_one_render_are_refused() {
    let dir = rendered("refused");
    assert_refused(&dir, &["p0.exr", "p2.exr"], &["1 of the 3 parts is missing: 1/3"]);
    assert_refused(&dir, &["p0.exr", "p1.exr", "p1.exr", "p2.exr"], &["part 1/3 is given twice"]);
    ok(&["render", "scene.toml", "-q", "--part", "1/3", "--seed", "5", "-o", "seed.exr"], &dir);
    assert_refused(
        &dir,
        &["p0.exr", "seed.exr", "p2.exr"],
        &[
            "'seed.exr' does not belong with 'p0.exr'",
            "the render options differ (--seed 5 vs --seed 0)",
        ],
    );
    std::fs::write(dir.join("other.toml"), scene().replace("radius = 1.0", "radius = 0.9"))
        .unwrap();
    ok(&["render", "other.toml", "-q", "--part", "1/3", "-o", "other.exr"], &dir);
    assert_refused(&dir, &["p0.exr", "other.exr", "p2.exr"], &["scene contents (SHA-256) differs"]);
    ok(&["render", "scene.toml", "-q", "--part", "1/2", "-o", "half.exr"], &dir);
    assert_refused(
        &dir,
        &["p0.exr", "half.exr", "p2.exr"],
        &["split differs (tiles into 2 parts vs tiles into 3 parts)"],
    );
    assert_refused(
        &dir,
        &["p0.exr", "whole.exr", "p2.exr"],
        &["'whole.exr' is not an embray part file"],
    );
    // A part whose pixel data is damaged (its header intact) is refused, not merged.
    let mut bytes = std::fs::read(dir.join("p1.exr")).unwrap();
    let n = bytes.len();
    for b in &mut bytes[n - 200..] {
        *b ^= 0x5a;
    }
    std::fs::write(dir.join("bad.exr"), bytes).unwrap();
    assert_refused(&dir, &["p0.exr", "bad.exr", "p2.exr"], &["bad.exr"]);
    assert_refused(&dir, &["p0.exr", "missing.exr"], &["cannot read part file 'missing.exr'"]);
    // -o is the EXR: a display extension there would have been EXR bytes in a .png file.
    for (output, expected) in [
        ("merged.png", "merge writes the EXR there"),
        ("merged.tif", "'.tif' names no image format"),
    ] {
        let out = embray(&["merge", "p0.exr", "p1.exr", "p2.exr", "-o", output], &dir);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{output}: {stderr}");
        assert!(stderr.contains(expected), "{output}: {stderr}");
        assert!(!dir.join(output).exists());
    }
    ok(&["merge", "p0.exr", "p1.exr", "p2.exr", "-o", "m.exr", "--png", "m.jpg"], &dir);
    assert_eq!(std::fs::read(dir.join("m.jpg")).unwrap()[..3], [0xFF, 0xD8, 0xFF]);
}

/// Parts rendered with different options are refused naming the options as the command
/// line writes them, not as Rust's debug text (`DVec3(1.0` cut at its comma, `Fast }`).
#[test]
fn parts_of_other_options_are_refused_in_command_line_words() {
    let dir = rendered("option-words");
    for (options, expected) in [
        (&["--offset", "1,1,1"][..], "(--offset 1,1,1 vs --offset 0,0,0)"),
        (&["--clamp", "0.5"], "(--clamp 0.5 vs no --clamp)"),
        (&["--spawn", "epsilon=1"], "(--spawn epsilon=1 vs --spawn robust)"),
        (&["--build-quality", "high"], "(--build-quality high vs --build-quality medium)"),
        (&["--batch", "single"], "(--batch single vs --batch native)"),
        (&["--intersection", "fast"], "(--intersection fast vs --intersection robust)"),
    ] {
        let mut args = vec!["render", "scene.toml", "-q", "--part", "1/3", "-o", "other.exr"];
        args.extend(options);
        ok(&args, &dir);
        let expected = ["'other.exr' does not belong with 'p0.exr'", expected];
        assert_refused(&dir, &["p0.exr", "other.exr", "p2.exr"], &expected);
        let out = embray(&["merge", "p0.exr", "other.exr", "p2.exr", "-o", "m.exr"], &dir);
        let stderr = String::from_utf8_lossy(&out.stderr);
        for debug in ["DVec3", "Some(", "None", "Epsilon(", "}"] {
            assert!(!stderr.contains(debug), "{debug} in: {stderr}");
        }
    }
}

/// Options a part cannot honour are refused before it renders: among them a grading LUT
/// (the merge grades the image) and a scene's own crop window (the parts split the whole
/// image: merged, they were refused as damaged).
#[test]
fn bad_part_options_are_refused_before_rendering() {
    let dir = temp_dir("options");
    std::fs::write(dir.join("scene.toml"), scene()).unwrap();
    let cropped = scene().replace("spp = 4", "spp = 4\ncrop = [0, 0, 4, 4]");
    std::fs::write(dir.join("cropped.toml"), cropped).unwrap();
    for (args, expected) in [
        (vec!["--part", "3/3"], "the index counts from 0"),
        (vec!["--part", "x"], "is not of the form I/N"),
        (vec!["--part", "0/2", "--png", "a.png"], "--png cannot be used with --part"),
        (vec!["--part", "0/2", "--lut", "none.cube"], "--lut cannot be used with --part"),
        (vec!["cropped.toml", "--part", "0/2"], "asks for a crop window (0, 0) to (4, 4)"),
        (vec!["--part", "0/5", "--split", "samples"], "4 spp cannot be split into 5 sample ranges"),
        (vec!["--split", "samples"], "--part"),
    ] {
        let mut all = vec!["render", "-q"];
        if args[0] != "cropped.toml" {
            all.push("scene.toml");
        }
        all.extend(&args);
        let out = embray(&all, &dir);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && stderr.contains(expected), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"));
    }
    let files: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(files.len(), 2, "nothing but the scenes: {files:?}");
}

/// The RGB pixels of an EXR.
fn pixels(path: &Path) -> Vec<glam::Vec3> {
    embray::exr_rgb::read(&std::fs::read(path).unwrap()).unwrap().2
}

#[test]
fn a_partial_merge_previews_the_parts_there_are() {
    let dir = rendered("partial");
    let out = embray(&["merge", "p0.exr", "p2.exr", "--partial", "-o", "preview.exr"], &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("parts 1/3 missing") && stderr.contains("merged 2 of 3 parts"),
        "{stderr}"
    );
    // Tile t belongs to part t mod 3: the tiles of part 1 are black, the others are the
    // whole render's pixels exactly.
    let (whole, preview) = (pixels(&dir.join("whole.exr")), pixels(&dir.join("preview.exr")));
    let (width, tile_size) = (WIDTH as usize, TILE_SIZE as usize);
    let tiles_across = width.div_ceil(tile_size);
    assert_eq!(whole.len(), width * HEIGHT as usize);
    for (i, (w, p)) in whole.iter().zip(&preview).enumerate() {
        let (x, y) = (i % width, i / width);
        let tile = (y / tile_size) * tiles_across + x / tile_size;
        let expected = if tile % 3 == 1 { glam::Vec3::ZERO } else { *w };
        assert_eq!(*p, expected, "pixel ({x}, {y}) of tile {tile}");
    }
    // Of a samples split, the image of the samples there are, and the spp it holds.
    for i in 0..4 {
        let (part, path) = (format!("{i}/4"), format!("s{i}.exr"));
        ok(
            &["render", "scene.toml", "-q", "--part", &part, "--split", "samples", "-o", &path],
            &dir,
        );
    }
    let out = embray(&["merge", "s3.exr", "s1.exr", "--partial", "-o", "some.exr"], &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("parts 0/4, 2/4 missing") && stderr.contains("@ 2 spp"), "{stderr}");
    let some = pixels(&dir.join("some.exr"));
    assert!(some.iter().all(|c| c.is_finite()) && some != whole && some.iter().any(|c| c.x > 0.0));
    // With every part, --partial is the merge: the whole render.
    ok(&["merge", "s0.exr", "s1.exr", "s2.exr", "s3.exr", "--partial", "-o", "all.exr"], &dir);
    assert_eq!(
        std::fs::read(dir.join("all.exr")).unwrap(),
        std::fs::read(dir.join("whole.exr")).unwrap()
    );
    // Without --partial, still refused.
    assert_refused(&dir, &["s3.exr", "s1.exr"], &["2 of the 4 parts are missing", "--partial"]);
}
