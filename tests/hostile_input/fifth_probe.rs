//! Holes a fifth hostile probe found: inputs whose cost grew faster than their size. One
//! image named by many materials was decoded, and held, once each before the memory check;
//! a Mitsuba file's line numbers and an MTL's materials were found by reading from the
//! start each time (n² in the elements or the materials). Each case runs well within a
//! second now; the bounds below are the minutes those cost before, not speed goals.

use crate::harness::{Scratch, accepted_in, scene};
use std::time::{Duration, Instant};

/// 40 materials of one 1024² PNG (12 MiB of texels each as decoded) render under a budget
/// of 200 MB: the image is decoded once and shared, and counted once by the estimate (it
/// was 40 images of 12 MiB: refused, after 480 MiB were spent).
#[test]
fn an_image_named_by_many_materials_is_decoded_once() {
    let scratch = Scratch::new();
    let texels = image::RgbImage::from_fn(1024, 1024, |x, y| image::Rgb([x as u8, y as u8, 7]));
    texels.save(scratch.path("tex.png")).unwrap();
    let mut materials = String::new();
    for i in 0..40 {
        materials += &format!(
            "[materials.t{i}]\ntexture = {{ type = \"image\", file = \"tex.png\" }}\n\
             [[objects]]\ntype = \"sphere\"\nmaterial = \"t{i}\"\n\
             center = [0.0, 0.0, {z}]\nradius = 0.01\n",
            z = 0.5 + i as f64 * 0.01
        );
    }
    scratch.write("s.toml", scene(&materials));
    let mut command = scratch.command(&["render", "s.toml", "-o", "s.exr"]);
    let output = command.env("EMBRAY_MAX_MEMORY", "200000000").output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    assert!(scratch.path("s.exr").exists());
}

/// Runs `embray info` on `file` in `scratch`: it must succeed within `bound`.
fn info_within(scratch: &Scratch, file: &str, bound: Duration) {
    let start = Instant::now();
    accepted_in(scratch, &["info", file]);
    assert!(start.elapsed() < bound, "{file}: {:?}", start.elapsed());
}

/// 100,000 Mitsuba elements: each one's line was counted from the file's start (8 s for
/// 50,000; 33 s for these). Now one index of the line breaks.
#[test]
fn a_mitsuba_file_of_many_elements_is_read_in_linear_time() {
    let scratch = Scratch::new();
    let mut xml = String::from(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><film type=\"hdrfilm\">\
         <integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/></film>\
         </sensor>\n<shape type=\"sphere\"><bsdf type=\"diffuse\"/></shape>\n\
         <emitter type=\"constant\"/>\n",
    );
    for _ in 0..100_000 {
        xml += "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.5\"/></bsdf>\n";
    }
    xml += "</scene>\n";
    scratch.write("s.xml", xml);
    info_within(&scratch, "s.xml", Duration::from_secs(10));
}

/// An OBJ whose 40,000 triangles each use their own MTL material: each material's block
/// was found by skipping lines from the MTL's start, and each `usemtl` checked against the
/// list (19 s). Now by offsets and a set.
#[test]
fn an_obj_of_many_materials_is_read_in_linear_time() {
    let scratch = Scratch::new();
    let n = 40_000;
    let mtl: String = (0..n).map(|i| format!("newmtl m{i}\nKd 0.5 0.5 0.5\n")).collect();
    scratch.write("many.mtl", mtl);
    let faces: String = (0..n).map(|i| format!("usemtl m{i}\nf -3 -2 -1\n")).collect();
    scratch.write("many.obj", format!("mtllib many.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n{faces}"));
    let object = "[[objects]]\ntype = \"mesh\"\nfile = \"many.obj\"\n";
    scratch.write("s.toml", scene(object));
    info_within(&scratch, "s.toml", Duration::from_secs(10));
}
