//! Previews: `--crop` gives the whole render's pixels bit for bit, `--resolution` keeps the
//! view, `--camera` picks one camera of a CENG795 file (and `-o` then works).

mod common;

use common::command::{GOOD_SCENE, embray, temp_dir};
use embray::bench::convergence::read_reference;
use embray::choice::Choice;
use embray::render::TILE_SIZE;

fn run_ok(args: &[&str], dir: &std::path::Path) {
    let out = embray(args, dir);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn a_crop_is_the_whole_renders_pixels_bit_for_bit() {
    let dir = temp_dir("crop");
    // 3×2 tiles (40×28 for tiles of 16), tiles cut by the window on every side.
    let t = TILE_SIZE;
    let (width, height) = (t * 5 / 2, t * 7 / 4);
    let (x0, y0, x1, y1) = (t * 7 / 16, t * 5 / 16, t * 33 / 16, t * 21 / 16);
    let resolution = format!("[{width}, {height}]");
    std::fs::write(dir.join("s.toml"), GOOD_SCENE.replace("[16, 12]", &resolution)).unwrap();
    let window = format!("{x0},{y0},{x1},{y1}");
    for backend in common::backends() {
        let name = backend.name();
        let whole = ["render", "s.toml", "--spp", "3", "-q", "--backend", name, "-o", "whole.exr"];
        run_ok(&whole, &dir);
        let crop = [
            "render",
            "s.toml",
            "--spp",
            "3",
            "-q",
            "--backend",
            name,
            "--crop",
            &window,
            "-o",
            "crop.exr",
        ];
        run_ok(&crop, &dir);
        let (whole, crop) = (
            read_reference(&dir.join("whole.exr")).unwrap(),
            read_reference(&dir.join("crop.exr")).unwrap(),
        );
        assert_eq!((crop.width, crop.height), (x1 - x0, y1 - y0));
        for y in 0..crop.height {
            for x in 0..crop.width {
                let (c, w) = (crop.index(x, y), whole.index(x + x0, y + y0));
                assert_eq!(
                    crop.color[c].to_array().map(f32::to_bits),
                    whole.color[w].to_array().map(f32::to_bits)
                );
                assert_eq!(crop.depth[c].to_bits(), whole.depth[w].to_bits(), "{name} ({x}, {y})");
            }
        }
    }
}

/// The columns of `film` where the sphere is (lit).
fn lit_columns(film: &embray::film::Film) -> u32 {
    (0..film.width)
        .filter(|&x| (0..film.height).any(|y| film.pixel(x, y).max_element() > 0.05))
        .count() as u32
}

#[test]
fn another_resolution_keeps_the_view() {
    let dir = temp_dir("resolution");
    std::fs::write(dir.join("s.toml"), GOOD_SCENE.replace("[16, 12]", "[64, 48]")).unwrap();
    run_ok(&["render", "s.toml", "--spp", "2", "-q", "-o", "a.exr"], &dir);
    // Twice as wide an aspect: the same view, stretched.
    run_ok(
        &["render", "s.toml", "--spp", "2", "-q", "--resolution", "128x48", "-o", "b.exr"],
        &dir,
    );
    let (a, b) =
        (read_reference(&dir.join("a.exr")).unwrap(), read_reference(&dir.join("b.exr")).unwrap());
    assert_eq!((b.width, b.height), (128, 48));
    let (wa, wb) = (lit_columns(&a), lit_columns(&b));
    assert!(wa > 10 && (wb as i64 - 2 * wa as i64).abs() <= 2, "{wa} columns, then {wb}");
}

const TWO_CAMERAS: &str = r#"<Scene>
  <MaxRecursionDepth>1</MaxRecursionDepth>
  <BackgroundColor>0 0 0</BackgroundColor>
  <Cameras>
    <Camera id="1">
      <Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>
      <NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance>
      <ImageResolution>8 8</ImageResolution><ImageName>front.png</ImageName>
    </Camera>
    <Camera id="2">
      <Position>0 0 0</Position><Gaze>0.2 0 -1</Gaze><Up>0 1 0</Up>
      <NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance>
      <ImageResolution>8 8</ImageResolution><ImageName>side.png</ImageName>
    </Camera>
  </Cameras>
  <Lights><AmbientLight>25 25 25</AmbientLight>
    <PointLight id="1"><Position>0 2 0</Position><Intensity>1000 1000 1000</Intensity></PointLight>
  </Lights>
  <Materials>
    <Material id="1"><AmbientReflectance>1 1 1</AmbientReflectance>
      <DiffuseReflectance>1 1 1</DiffuseReflectance><SpecularReflectance>0 0 0</SpecularReflectance></Material>
  </Materials>
  <VertexData>0 0 -3</VertexData>
  <Objects><Sphere id="1"><Material>1</Material><Center>1</Center><Radius>1</Radius></Sphere></Objects>
</Scene>
"#;

#[test]
fn one_camera_of_several_is_chosen_by_name_or_position() {
    let dir = temp_dir("camera-choice");
    std::fs::write(dir.join("s.xml"), TWO_CAMERAS).unwrap();
    run_ok(&["render", "s.xml", "-q", "--camera", "side"], &dir);
    assert!(dir.join("side.png").exists() && !dir.join("front.png").exists());
    // With one camera chosen, -o names its image (it was refused for a multi-camera file).
    run_ok(&["render", "s.xml", "-q", "--camera", "1", "-o", "first.exr"], &dir);
    assert_eq!(read_reference(&dir.join("first.exr")).unwrap().width, 8);
    // Parts of two cameras of one file (same size) do not merge.
    run_ok(
        &[
            "render", "s.xml", "-q", "--camera", "front", "--part", "0/2", "--split", "samples",
            "--spp", "2", "-o", "p0.exr",
        ],
        &dir,
    );
    run_ok(
        &[
            "render", "s.xml", "-q", "--camera", "side", "--part", "1/2", "--split", "samples",
            "--spp", "2", "-o", "p1.exr",
        ],
        &dir,
    );
    let out = embray(&["merge", "p0.exr", "p1.exr", "-o", "m.exr"], &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("camera differs"), "{stderr}");
    let out = embray(&["render", "s.xml", "--camera", "top"], &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr.contains("--camera 'top'") && stderr.contains("front.png, side.png"),
        "{stderr}"
    );
}

#[test]
fn bad_previews_are_refused() {
    let dir = temp_dir("preview-refused");
    std::fs::write(dir.join("s.toml"), GOOD_SCENE).unwrap();
    let cases: [(&[&str], &str); 4] = [
        (
            &["--crop", "0,0,17,12"],
            "--crop is '0,0,17,12', but must be X0,Y0,X1,Y1 with X0 < X1 ≤ 16",
        ),
        (&["--crop", "1,1,5,5", "--part", "0/2"], "--crop cannot be used with --part"),
        (&["--resolution", "0x5"], "--resolution is '0x5', but must be WIDTHxHEIGHT"),
        (&["--camera", "2"], "--camera chooses among the cameras of a CENG795 .xml file"),
    ];
    common::command::assert_render_refusals(&dir, &cases);
}

/// A crop the scene asks for (TOML `[render] crop`, Mitsuba's film crop) is rendered as
/// `--crop` renders it; `--crop` overrides it; a crop outside the image is refused.
#[test]
fn a_scenes_own_crop_is_rendered_unless_the_command_line_says_otherwise() {
    let dir = temp_dir("scene-crop");
    let scene = GOOD_SCENE.replace("[16, 12]", "[40, 28]");
    std::fs::write(dir.join("s.toml"), &scene).unwrap();
    let own = format!("{scene}\n[render]\ncrop = [7, 5, 33, 21]\n");
    std::fs::write(dir.join("own.toml"), &own).unwrap();
    run_ok(&["render", "s.toml", "--spp", "2", "-q", "--crop", "7,5,33,21", "-o", "a.exr"], &dir);
    run_ok(&["render", "own.toml", "--spp", "2", "-q", "-o", "b.exr"], &dir);
    let (a, b) =
        (read_reference(&dir.join("a.exr")).unwrap(), read_reference(&dir.join("b.exr")).unwrap());
    assert_eq!((b.width, b.height), (26, 16));
    assert_eq!(a.color, b.color);
    run_ok(&["render", "own.toml", "--spp", "1", "-q", "--crop", "0,0,4,4", "-o", "c.exr"], &dir);
    assert_eq!(read_reference(&dir.join("c.exr")).unwrap().width, 4);
    std::fs::write(dir.join("bad.toml"), own.replace("33, 21]", "41, 21]")).unwrap();
    let out = embray(&["render", "bad.toml", "--spp", "1", "-q", "-o", "d.exr"], &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && stderr.contains("render.crop"), "{stderr}");
}
