//! Files that ask for far more memory than they take: counted against the budget before it
//! is spent, not refused (or aborted) after. Each case took the starting binary past its
//! budget: 3.1 GB for a 1.9 KB scene of `repeat` grids, 1 GB for Mitsuba instances, 1.5 GB for
//! values grown by `$name`s, 492 and 747 MB for PLY attributes counted nowhere.

use crate::harness::{
    Scratch, accepted_in, refused_under_memory, run_limited_with, scene, with_mesh,
};

/// Runs `args` under an address space of `bytes` (`ulimit -v`) and, if given, a memory
/// budget (`EMBRAY_MAX_MEMORY`): a refusal, exit 1, that says every one of `expected`, where
/// the starting binary aborted (134) when an allocation failed.
#[track_caller]
fn refused_within_address_space(
    scratch: &Scratch,
    args: &[&str],
    (bytes, budget): (u64, Option<u64>),
    expected: &[&str],
) {
    let mut command = scratch.command(args);
    if let Some(budget) = budget {
        command.env("EMBRAY_MAX_MEMORY", budget.to_string());
    }
    let run = run_limited_with(command, libc::RLIMIT_AS, bytes);
    run.assert_no_panic();
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    run.assert_says(expected);
}

/// Ten spheres of a million copies each (1.9 KB): the copies were made before the estimate.
#[test]
fn repeat_copies_are_counted_before_they_are_made() {
    let scratch = Scratch::new();
    let sphere = "[[objects]]\ntype = \"sphere\"\nmaterial = \"grey\"\ncenter = [0.0, 0.0, 1.0]\n\
                  radius = 0.0001\nrepeat = { count = [1000, 1000, 1], spacing = [0.0003, 0.0003, 0.0] }\n";
    scratch.write("s.toml", scene(&sphere.repeat(10)));
    let expected = ["s.toml", "1000001 object placements", "objects[1].repeat (line 29)"];
    refused_within_address_space(&scratch, &["info", "s.toml"], (800_000_000, None), &expected);
}

/// A shapegroup of 1,000 spheres instanced 3,000 times (3 million placements from 240 KB).
#[test]
fn mitsuba_instances_are_counted_before_they_are_made() {
    let scratch = Scratch::new();
    let spheres: String = (0..1000)
        .map(|i| format!("<shape type=\"sphere\"><point name=\"center\" x=\"{i}\" y=\"0\" z=\"0\"/></shape>\n"))
        .collect();
    let instances = "<shape type=\"instance\"><ref id=\"g\"/></shape>\n".repeat(3000);
    scratch.write(
        "s.xml",
        format!(
            "<scene version=\"3.0.0\">\n<shape type=\"shapegroup\" id=\"g\">\n{spheres}</shape>\n\
             {instances}<emitter type=\"constant\"/>\n</scene>\n"
        ),
    );
    let expected = ["s.xml", "object placements", "<shape type=\"instance\"> (line"];
    refused_within_address_space(&scratch, &["info", "s.xml"], (800_000_000, None), &expected);
}

/// A 1,000-byte default doubled ten times (1 MB, under the cap of one value), named by 1,500
/// elements: 1.5 GB held from 91 KB.
#[test]
fn values_grown_by_names_are_counted() {
    let scratch = Scratch::new();
    let mut defaults = format!("<default name=\"a0\" value=\"{}\"/>\n", "x".repeat(1000));
    for i in 1..=10 {
        let last = i - 1;
        defaults.push_str(&format!("<default name=\"a{i}\" value=\"$a{last}$a{last}\"/>\n"));
    }
    let uses = "<bsdf type=\"diffuse\"><string name=\"s\" value=\"$a10\"/></bsdf>\n".repeat(1500);
    scratch.write("s.xml", format!("<scene version=\"3.0.0\">\n{defaults}{uses}</scene>\n"));
    let expected = ["s.xml", "added to values by `$name`s, the last at line"];
    // The budget is held to; the address space shows that it was (threads reserve more
    // than they use, so the address space alone is no budget to refuse by).
    let limits = (1_500_000_000, Some(500_000_000));
    refused_within_address_space(&scratch, &["info", "s.xml"], limits, &expected);
}

/// A binary PLY header, `vertices` float positions and then `extra` more properties.
fn ply_header(vertices: usize, vertex_extra: &str, faces: usize, face_extra: &str) -> String {
    format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {vertices}\nproperty float x\n\
         property float y\nproperty float z\n{vertex_extra}element face {faces}\n\
         property list uchar uchar vertex_indices\n{face_extra}end_header\n"
    )
}

/// `groups` groups of three uchar properties `{prefix}K_x/y/z`: each a 3-channel attribute.
fn uchar_groups(prefix: char, groups: usize) -> String {
    (0..groups)
        .map(|k| format!("property uchar {prefix}{k}_x\nproperty uchar {prefix}{k}_y\nproperty uchar {prefix}{k}_z\n"))
        .collect()
}

/// 50,000 vertices with 66 groups of uchar properties (10.5 MB): 41 MB of f32 attributes that
/// the estimate did not count, read without a check.
#[test]
fn ply_vertex_attributes_are_counted_from_the_header() {
    let scratch = Scratch::new();
    let (vertices, groups) = (50_000, 66);
    let mut bytes = ply_header(vertices, &uchar_groups('p', groups), 1, "").into_bytes();
    for i in 0..vertices {
        bytes.extend([i as f32, (i % 7) as f32, 0.0].iter().flat_map(|c| c.to_le_bytes()));
        bytes.extend(std::iter::repeat_n(1u8, 3 * groups));
    }
    bytes.extend([3, 0, 1, 2]);
    scratch.write("m.ply", bytes);
    scratch.write("s.toml", with_mesh("m.ply"));
    let values = (vertices * 3 * groups).to_string();
    let info = accepted_in(&scratch, &["info", "s.toml"]);
    assert!(info.stdout.contains(&format!("{values} mesh attribute values")), "{}", info.stdout);
    let expected = ["m.ply", "its mesh needs about", "50000 vertices of 816 bytes"];
    refused_under_memory(&scratch, &["info", "s.toml"], 40_000_000, &expected);
}

/// 100 faces of 255 vertices, each with 300 groups of uchar properties (120 KB): each face's
/// 900 values copied to its 253 fan triangles (91 MB).
#[test]
fn ply_fan_triangles_are_counted_as_they_grow() {
    let scratch = Scratch::new();
    let (faces, groups) = (100, 300);
    let mut bytes = ply_header(255, "", faces, &uchar_groups('f', groups)).into_bytes();
    for i in 0..255 {
        let angle = i as f32 / 255.0 * std::f32::consts::TAU;
        bytes.extend([angle.cos(), angle.sin(), 1.0].iter().flat_map(|c| c.to_le_bytes()));
    }
    for _ in 0..faces {
        bytes.push(255);
        bytes.extend(0..=254u8);
        bytes.extend(std::iter::repeat_n(0u8, 3 * groups));
    }
    scratch.write("m.ply", bytes);
    scratch.write("s.toml", with_mesh("m.ply"));
    let expected = ["m.ply", "its mesh needs about", "triangles of 3612 bytes"];
    refused_under_memory(&scratch, &["info", "s.toml"], 50_000_000, &expected);
}

/// An OBJ was read whole, and its text parsed, before any memory was counted (5 GB for a
/// 2 GiB file of unreferenced vertices): its length is now held against the budget first.
#[test]
fn obj_files_are_counted_before_they_are_read() {
    let scratch = Scratch::new();
    let vertices = "v 0 0 0\n".repeat(400_000);
    scratch.write("m.obj", format!("{vertices}f 1 2 3\n"));
    scratch.write("s.toml", with_mesh("m.obj"));
    let expected =
        ["m.obj: reading it needs about", "a file of 3200008 bytes, named by objects[1]"];
    refused_under_memory(&scratch, &["info", "s.toml"], 10_000_000, &expected);
}
