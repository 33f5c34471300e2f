//! Texture values mean what they say: a 16-bit image what the 8-bit image of the same
//! picture does, a constant colour only within the range the other colours keep, an image
//! texture only where texture coordinates say where it goes; what a reader would otherwise
//! drop without a word (MTL statements outside a material, a material defined twice, indices
//! beside a plyFile, an image name that names no file) is said.

use crate::harness::{Scratch, accepted_in, refused_cases, refused_in, scene, xml_scene};

/// A 2×2 grey PNG: 8-bit `grey8`, or 16-bit `grey16` where given.
fn grey_png(scratch: &Scratch, name: &str, grey8: u8, grey16: Option<u16>) {
    let path = scratch.path(name);
    match grey16 {
        Some(g) => image::ImageBuffer::<image::Luma<u16>, _>::from_pixel(2, 2, image::Luma([g]))
            .save(path)
            .unwrap(),
        None => image::GrayImage::from_pixel(2, 2, image::Luma([grey8])).save(path).unwrap(),
    }
}

/// The mean of an EXR the run wrote.
fn exr_mean(scratch: &Scratch, name: &str) -> f32 {
    let bytes = std::fs::read(scratch.path(name)).unwrap();
    let (_, _, pixels) = embray::exr_rgb::read(&bytes).unwrap();
    pixels.iter().map(|p| p.x + p.y + p.z).sum::<f32>() / (3 * pixels.len()) as f32
}

/// A CENG795 quad in front of the camera, textured by `texture` (replace_kd), with the
/// `texcoords` given (none: no `<TexCoordData>`).
fn textured_quad_xml(image_name: &str, texture: &str, texcoords: Option<&str>) -> String {
    let texcoords =
        texcoords.map_or(String::new(), |t| format!("<TexCoordData>{t}</TexCoordData>"));
    let textures = format!(
        "<Textures><Images><Image id=\"1\">{texture}</Image></Images><TextureMap id=\"1\" \
         type=\"image\"><ImageId>1</ImageId><DecalMode>replace_kd</DecalMode></TextureMap>\
         </Textures>\n{texcoords}"
    );
    xml_scene(&[image_name], &textures).replace(
        "<Sphere id=\"1\"><Material>1</Material><Center>1</Center><Radius>1</Radius></Sphere>",
        "<Mesh id=\"1\"><Material>1</Material><Textures>1</Textures>\n<Faces>2 3 4 2 4 5</Faces></Mesh>",
    )
    .replace(
        "<VertexData>0 0 -3</VertexData>",
        "<VertexData>0 0 -3 -1 1 -2 -1 -1 -2 1 -1 -2 1 1 -2</VertexData>",
    )
}

/// The texcoords of `textured_quad_xml`'s five vertices (the first, unused, too).
const QUAD_TEXCOORDS: &str = "0 0 0 0 0 1 1 1 1 0";

/// A 16-bit PNG was read in 0–65535 units and divided by 255, so grey 0.5 was a
/// reflectance of 128 (CENG795 `Normalizer`, Mitsuba's raw bitmap, TOML raw images alike).
#[test]
fn a_sixteen_bit_image_texture_reflects_what_the_eight_bit_one_does() {
    let scratch = Scratch::new();
    grey_png(&scratch, "g8.png", 128, None);
    grey_png(&scratch, "g16.png", 0, Some(32768));
    scratch.write("a.xml", textured_quad_xml("a.png", "g8.png", Some(QUAD_TEXCOORDS)));
    scratch.write("b.xml", textured_quad_xml("b.png", "g16.png", Some(QUAD_TEXCOORDS)));
    let material = "[materials.grey]\nalbedo = [0.5, 0.5, 0.5]\n";
    for (name, file) in [("c.toml", "g8.png"), ("d.toml", "g16.png")] {
        let texture = format!(
            "{material}texture = {{ type = \"image\", file = \"{file}\", encoding = \"raw\" }}\n"
        );
        scratch.write(name, scene("").replace(material, &texture));
    }
    for xml in ["a.xml", "b.xml"] {
        accepted_in(&scratch, &["render", xml, "-q"]);
    }
    for (toml, exr) in [("c.toml", "c.exr"), ("d.toml", "d.exr")] {
        accepted_in(&scratch, &["render", toml, "-o", exr, "--aovs", "none", "-q"]);
    }
    for (eight, sixteen) in [("a.exr", "b.exr"), ("c.exr", "d.exr")] {
        let (eight, sixteen) = (exr_mean(&scratch, eight), exr_mean(&scratch, sixteen));
        // 32768 / 257 = 127.5 of 255: within 1/255 of grey 128.
        let ratio = sixteen / eight;
        assert!(eight > 0.0 && (0.99..=1.0).contains(&ratio), "{eight} vs {sixteen}");
    }
}

refused_cases! {
    constant_texture_above_one: ["s.toml" => scene("").replace("albedo = [0.5, 0.5, 0.5]", "albedo = [0.5, 0.5, 0.5]\ntexture = { type = \"constant\", value = [5, 5, 5] }")], ["render", "s.toml"]
        => ["s.toml", "materials.grey.texture.value[0]", "is 5", "in [0, 1]", "(line 12)"];
    constant_texture_negative: ["s.toml" => scene("").replace("albedo = [0.5, 0.5, 0.5]", "albedo = [0.5, 0.5, 0.5]\ntexture = { type = \"constant\", value = [0.5, -5, 0.5] }")], ["render", "s.toml"]
        => ["s.toml", "materials.grey.texture.value[1]", "is -5", "in [0, 1]", "(line 12)"];
    image_name_ending_in_a_folder: ["s.xml" => xml_scene(&["sub/"], "")], ["render", "s.xml"]
        => ["s.xml", "ImageName 'sub/'", "ends in a folder", "(line 12)"];
    image_name_only_an_extension: ["s.xml" => xml_scene(&["sub/.png"], "")], ["render", "s.xml"]
        => ["s.xml", "ImageName 'sub/.png'", "no name before its extension", "(line 12)"];
}

/// A colour in range is accepted; so is a constant bump height of any value, which bumps
/// nothing (`convert` writes a Mitsuba `rawconstant`, which has no range, as one).
#[test]
fn a_constant_texture_in_range_and_any_constant_height_are_accepted() {
    let scratch = Scratch::new();
    let texture =
        "albedo = [0.5, 0.5, 0.5]\ntexture = { type = \"constant\", value = [1, 0, 0.25] }";
    scratch.write("s.toml", scene("").replace("albedo = [0.5, 0.5, 0.5]", texture));
    accepted_in(&scratch, &["render", "s.toml", "-q"]);
    let height = "albedo = [0.5, 0.5, 0.5]\nbump_map = { type = \"constant\", value = [5, -2, 7] }";
    scratch.write("b.toml", scene("").replace("albedo = [0.5, 0.5, 0.5]", height));
    accepted_in(&scratch, &["info", "b.toml"]);
}

/// An image texture on a mesh without texture coordinates for every vertex rendered some
/// default without a word; the course gives no meaning to it.
#[test]
fn an_image_texture_without_texture_coordinates_is_refused() {
    let scratch = Scratch::new();
    grey_png(&scratch, "g.png", 128, None);
    scratch.write("none.xml", textured_quad_xml("a.png", "g.png", None));
    let expected = ["none.xml", "Mesh id=\"1\"", "image texture", "no <TexCoordData>", "line 29"];
    refused_in(&scratch, &["render", "none.xml"], &expected);
    scratch.write("short.xml", textured_quad_xml("a.png", "g.png", Some("0 0 0 0")));
    let expected =
        ["short.xml", "Mesh id=\"1\"", "holds 2 u v pairs", "scene vertex 3 would take pair 3"];
    refused_in(&scratch, &["render", "short.xml"], &expected);
}

/// The indices beside a plyFile were ignored without a word.
#[test]
fn inline_indices_beside_a_ply_file_are_refused() {
    let scratch = Scratch::new();
    let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
               property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
               end_header\n-1 -1 -2\n1 -1 -2\n0 1 -2\n3 0 1 2\n";
    scratch.write("m.ply", ply);
    let mesh =
        "<Mesh id=\"1\"><Material>1</Material>\n<Faces plyFile=\"m.ply\">1 1 1</Faces></Mesh>";
    let text = xml_scene(&["a.png"], "").replace(
        "<Sphere id=\"1\"><Material>1</Material><Center>1</Center><Radius>1</Radius></Sphere>",
        mesh,
    );
    scratch.write("s.xml", text);
    let expected = ["s.xml", "Faces", "vertex indices are given with a plyFile", "line 29"];
    refused_in(&scratch, &["render", "s.xml"], &expected);
}

/// Exporters write statements before the first `newmtl` and define a material twice; tobj
/// drops the first and keeps the last of the second without a word.
#[test]
fn mtl_statements_outside_a_material_and_a_material_defined_twice_are_warned_about() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene("[[objects]]\ntype = \"mesh\"\nfile = \"m.obj\"\n"));
    scratch.write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
    scratch.write("m.mtl", "Kd 1 0 0\nnewmtl a\nKd 0 1 0\nnewmtl a\nKd 0 0 1\n");
    let run = accepted_in(&scratch, &["render", "s.toml", "-q"]);
    run.assert_says(&["warning", "m.mtl", "1 statement(s) before the first newmtl", "(line 1)"]);
    run.assert_says(&["m.mtl", "material 'a' is defined again", "the one at line 2", "(line 4)"]);
}
