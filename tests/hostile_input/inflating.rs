//! Small files that declare, or decode to, far more than they hold: a PLY element of no
//! properties and a vast count (it hung), a serialized mesh whose zlib stream inflates to
//! gigabytes and an EXR of many channels (both aborted on a failed allocation). Each is
//! refused, naming the file, before the memory is spent.

use crate::harness::{Run, Scratch, refused_cases, refused_in, scene, with_mesh};
use std::io::Read;

const PLY_HEADER: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty \
                          float y\nproperty float z\nelement face 1\nproperty list uchar int \
                          vertex_indices\n";

/// A binary PLY of one triangle (its bytes all text: zero coordinates, small indices), and
/// `tail` after it.
fn binary_ply(tail: &str) -> String {
    let header = PLY_HEADER.replace("ascii", "binary_little_endian");
    let zero = "\0".repeat(4);
    let face = ["\u{3}", "\0\0\0\0", "\u{1}\0\0\0", "\u{2}\0\0\0"].concat();
    format!("{header}end_header\n{}{face}{tail}", zero.repeat(9))
}

refused_cases! {
    ply_element_of_no_properties: ["s.toml" => with_mesh("m.ply"), "m.ply" => format!("{PLY_HEADER}element junk 18446744073709551615\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")], ["render", "s.toml"]
        => ["m.ply", "element 'junk' has 18446744073709551615 records but no properties", "line 9"];
    ply_binary_data_left_over: ["s.toml" => with_mesh("m.ply"), "m.ply" => binary_ply("more faces")], ["render", "s.toml"]
        => ["m.ply", "goes on after the last element", "10 bytes are left"];
}

/// The binary PLY of `binary_ply` itself loads, a final line end after its data included.
#[test]
fn a_binary_ply_with_a_final_line_end_loads() {
    let scratch = Scratch::new();
    scratch.write("s.toml", with_mesh("m.ply"));
    scratch.write("m.ply", binary_ply("\n"));
    crate::harness::accepted_in(&scratch, &["info", "s.toml"]);
}

/// A Mitsuba scene of the serialized mesh `m.serialized`.
const SERIALIZED_SCENE: &str = r#"<scene version="3.0.0">
<sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/>
<integer name="height" value="8"/></film></sensor>
<shape type="serialized"><string name="filename" value="m.serialized"/></shape>
</scene>"#;

/// A version-4 serialized mesh declaring `vertices` and `faces`, its stream holding the
/// counts and nothing after them.
fn serialized(vertices: u64, faces: u64) -> Vec<u8> {
    // Flags 0, an empty name, the counts.
    let body = [&[0u8; 5][..], &vertices.to_le_bytes(), &faces.to_le_bytes()].concat();
    let mut stream = flate2::read::ZlibEncoder::new(&body[..], flate2::Compression::fast());
    let mut file = vec![0x1C, 0x04, 0x04, 0x00];
    stream.read_to_end(&mut file).unwrap();
    file
}

/// What a serialized mesh declares is bounded before it is decoded: in total (2 GiB, as
/// other mesh files), and against the memory there is.
#[test]
fn a_serialized_mesh_declaring_gigabytes_is_refused_before_decoding() {
    let scratch = Scratch::new();
    scratch.write("s.xml", SERIALIZED_SCENE);
    scratch.write("m.serialized", serialized(178_956_970, 1));
    let expected = ["m.serialized", "178956970 vertices and 1 triangles declared", "2 GiB"];
    refused_in(&scratch, &["render", "s.xml"], &expected);
    scratch.write("m.serialized", serialized(10_000_000, 1));
    let before = scratch.snapshot();
    let mut command = scratch.command(&["info", "s.xml"]);
    let run = Run::from(command.env("EMBRAY_MAX_MEMORY", "104857600").output().unwrap());
    run.assert_no_panic();
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    run.assert_says(&["m.serialized", "need 228 MiB decoded, but only 100 MiB"]);
    assert_eq!(scratch.snapshot(), before);
}

/// An EXR of `channels` half-float channels (R, G, B and others), 64 × 64, all zero.
fn exr_of_channels(channels: usize) -> Vec<u8> {
    use exr::prelude::*;
    let names = ["R", "G", "B"].map(String::from).into_iter();
    let names = names.chain((3..channels).map(|i| format!("extra{i:03}")));
    let list = names
        .map(|name| AnyChannel::new(name.as_str(), FlatSamples::F16(vec![f16::ZERO; 64 * 64])));
    let image = Image::from_channels((64, 64), AnyChannels::sort(list.collect()));
    let mut bytes = std::io::Cursor::new(Vec::new());
    image.write().to_buffered(&mut bytes).unwrap();
    bytes.into_inner()
}

/// Every channel of an EXR is decoded, so the memory that takes is checked before: an
/// environment map of 200 channels needs 6 MiB, refused under a 5 MiB budget; its three
/// channels alone are read.
#[test]
fn an_exr_of_many_channels_is_refused_before_decoding() {
    let scratch = Scratch::new();
    let extra = "[[lights]]\ntype = \"environment\"\nfile = \"sky.exr\"\n";
    scratch.write("s.toml", scene(extra));
    let read = |channels: usize| {
        scratch.write("sky.exr", exr_of_channels(channels));
        let mut command = scratch.command(&["info", "s.toml"]);
        Run::from(command.env("EMBRAY_MAX_MEMORY", "5242880").output().unwrap())
    };
    let run = read(200);
    run.assert_no_panic();
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    run.assert_says(&["sky.exr", "64 × 64 pixels of 200 channels need about 6 MiB to read"]);
    let three = read(3);
    assert_eq!(three.code, Some(0), "three channels fit: {}", three.stderr);
}
