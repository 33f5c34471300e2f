//! `--lut FILE.cube` grades the PNG last: a table that swaps red and blue swaps them in the
//! rendered PNG (and leaves the EXR alone); a broken table is refused naming the file and
//! the line, before anything is rendered or written.

mod common;

use common::command::{GOOD_SCENE, embray, temp_dir};

/// A size-2 table mapping (r, g, b) to (b, g, r): exact under trilinear interpolation.
const SWAP_RED_BLUE: &str = "TITLE \"swap\"\nLUT_3D_SIZE 2\n\
    0 0 0\n0 0 1\n0 1 0\n0 1 1\n1 0 0\n1 0 1\n1 1 0\n1 1 1\n";

fn rgb(path: &std::path::Path) -> Vec<[u8; 3]> {
    let image = image::open(path).unwrap().to_rgb8();
    image.pixels().map(|p| p.0).collect()
}

#[test]
fn a_red_blue_swap_table_swaps_red_and_blue_in_the_png() {
    let dir = temp_dir("lut");
    // A red sphere, so the two channels differ.
    let scene = GOOD_SCENE.replace("albedo = [0.8, 0.8, 0.8]", "albedo = [0.8, 0.3, 0.05]");
    std::fs::write(dir.join("scene.toml"), scene).unwrap();
    std::fs::write(dir.join("swap.cube"), SWAP_RED_BLUE).unwrap();
    for args in [vec!["-o", "plain.exr"], vec!["-o", "graded.exr", "--lut", "swap.cube"]] {
        let mut all = vec!["render", "scene.toml", "-q", "--spp", "2"];
        all.extend(args);
        let out = embray(&all, &dir);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    }
    assert_eq!(
        std::fs::read(dir.join("plain.exr")).unwrap(),
        std::fs::read(dir.join("graded.exr")).unwrap()
    );
    let (plain, graded) = (rgb(&dir.join("plain.png")), rgb(&dir.join("graded.png")));
    assert!(plain.iter().any(|p| p[0] > p[2] + 50), "the sphere is red");
    for (p, g) in plain.iter().zip(&graded) {
        assert_eq!(*g, [p[2], p[1], p[0]]);
    }
}

#[test]
fn a_broken_table_is_refused_with_its_line_before_rendering() {
    let dir = temp_dir("lut-bad");
    std::fs::write(dir.join("scene.toml"), GOOD_SCENE).unwrap();
    std::fs::write(dir.join("bad.cube"), "LUT_3D_SIZE 2\n0 0 0\n0 0 one\n").unwrap();
    let out = embray(&["render", "scene.toml", "-q", "--lut", "bad.cube"], &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("bad.cube, line 3: a table entry: 'one' is not a number"), "{stderr}");
    assert!(!dir.join("scene.exr").exists() && !dir.join("scene.png").exists());
    let out =
        embray(&["render", "scene.toml", "-q", "--lut", "scene.toml", "-o", "scene.toml"], &dir);
    assert!(!out.status.success());
    assert_eq!(
        std::fs::read_to_string(dir.join("scene.toml")).unwrap(),
        GOOD_SCENE,
        "inputs are never overwritten"
    );
}

#[test]
fn a_table_starting_with_a_byte_order_mark_is_read() {
    let dir = temp_dir("lut-bom");
    std::fs::write(dir.join("scene.toml"), GOOD_SCENE).unwrap();
    // As Windows editors save UTF-8: it was "line 1: table values before LUT_3D_SIZE".
    std::fs::write(dir.join("bom.cube"), format!("\u{feff}{SWAP_RED_BLUE}")).unwrap();
    std::fs::write(dir.join("swap.cube"), SWAP_RED_BLUE).unwrap();
    for (lut, png) in [("bom.cube", "bom.png"), ("swap.cube", "swap.png")] {
        let out =
            embray(&["render", "scene.toml", "-q", "--spp", "1", "--lut", lut, "--png", png], &dir);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    }
    assert_eq!(rgb(&dir.join("bom.png")), rgb(&dir.join("swap.png")));
}
