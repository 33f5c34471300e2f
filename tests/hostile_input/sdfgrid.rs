//! Mitsuba `sdfgrid` shapes whose `.vol` file is wrong: each refused with the file and what
//! is wrong, before anything the header asks for is allocated; and what a grid cannot be.

use crate::harness::{Scratch, accepted_in, refused_in};

/// The bytes of a one-channel float32 `.vol` file of `size` holding `values`.
fn write_single_channel(size: [u32; 3], values: &[f32]) -> Vec<u8> {
    let mut bytes = b"VOL\x03".to_vec();
    for word in [1, size[0] as i32, size[1] as i32, size[2] as i32, 1] {
        bytes.extend(word.to_le_bytes());
    }
    for v in [0.0f32, 0.0, 0.0, 1.0, 1.0, 1.0].iter().chain(values) {
        bytes.extend(v.to_le_bytes());
    }
    bytes
}

/// An 8×8 Mitsuba scene at 1 spp whose grid (line 3) reads `g.vol` and holds `inside`.
fn grid_scene(inside: &str) -> String {
    format!(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><film type=\"hdrfilm\">\
         <integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/></film>\
         <sampler type=\"independent\"><integer name=\"sample_count\" value=\"1\"/></sampler>\
         </sensor>\n<shape type=\"sdfgrid\"><string name=\"filename\" value=\"g.vol\"/>{inside}\
         </shape>\n</scene>\n"
    )
}

/// A 2×2×2 grid of a plane through its middle.
fn plane() -> Vec<u8> {
    write_single_channel([2, 2, 2], &[-1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0])
}

#[track_caller]
fn refused_with(vol: &[u8], inside: &str, expected: &[&str]) {
    let scratch = Scratch::new();
    scratch.write("s.xml", grid_scene(inside));
    scratch.write("g.vol", vol);
    refused_in(&scratch, &["info", "s.xml"], expected);
}

#[test]
fn a_good_grid_is_read() {
    let scratch = Scratch::new();
    scratch.write("s.xml", grid_scene(""));
    scratch.write("g.vol", plane());
    let run = accepted_in(&scratch, &["info", "s.xml"]);
    assert!(run.stdout.contains("1 signed distance grids"), "{}", run.stdout);
}

#[test]
fn a_truncated_vol_is_refused() {
    let vol = plane();
    refused_with(
        &vol[..vol.len() - 3],
        "",
        &["g.vol", "2×2×2 values", "the file has 77 bytes", "line 3"],
    );
    refused_with(&vol[..20], "", &["g.vol", "shorter than a .vol header"]);
}

#[test]
fn a_header_asking_for_more_than_the_file_holds_is_refused() {
    let mut vol = plane();
    for (at, value) in [(8, i32::MAX), (12, i32::MAX), (16, i32::MAX)] {
        vol[at..at + 4].copy_from_slice(&value.to_le_bytes());
    }
    let limit = ["g.vol", "2147483647×2147483647×2147483647", "at most 1073741824 values"];
    refused_with(&vol, "", &limit);
    let mut longer = plane();
    longer[16..20].copy_from_slice(&3i32.to_le_bytes());
    refused_with(&longer, "", &["g.vol", "2×2×3", "the file has 80 bytes"]);
    let mut negative = plane();
    negative[12..16].copy_from_slice(&(-5i32).to_le_bytes());
    refused_with(&negative, "", &["g.vol", "y size is -5"]);
}

#[test]
fn a_grid_that_is_not_one_channel_of_floats_is_refused() {
    let mut two = write_single_channel([2, 2, 1], &[-1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0]);
    two[20..24].copy_from_slice(&2i32.to_le_bytes());
    refused_with(&two, "", &["g.vol", "2 channels", "an SDF grid has 1"]);
    let mut half = plane();
    half[4..8].copy_from_slice(&2i32.to_le_bytes());
    refused_with(&half, "", &["g.vol", "encoding 2"]);
    refused_with(
        b"not a volume at all, but long enough for a header...",
        "",
        &["g.vol", "not a .vol file"],
    );
}

#[test]
fn grids_without_a_surface_or_with_bad_values_are_refused() {
    refused_with(
        &write_single_channel([2, 2, 2], &[1.0; 8]),
        "",
        &["g.vol", "no voxel", "same sign"],
    );
    let mut nan = [1.0f32; 8];
    nan[3] = f32::NAN;
    refused_with(&write_single_channel([2, 2, 2], &nan), "", &["g.vol", "value 3 is NaN"]);
    refused_with(
        &write_single_channel([1, 2, 2], &[1.0, -1.0, 1.0, -1.0]),
        "",
        &["g.vol", "1×2×2", "at least 2"],
    );
}

#[test]
fn what_a_grid_cannot_be_is_refused_by_name() {
    let emitting = "<emitter type=\"area\"/>";
    refused_with(&plane(), emitting, &["s.xml", "cannot be an area emitter", "line 3"]);
    refused_with(
        &plane(),
        "<string name=\"normals\" value=\"flat\"/>",
        &["normals is 'flat'", "analytic"],
    );
    refused_with(
        &plane(),
        "<boolean name=\"flip_normals\" value=\"true\"/>",
        &["does not take `flip_normals`"],
    );
    let scratch = Scratch::new();
    scratch.write("s.xml", grid_scene(""));
    scratch.write("g.vol", plane());
    refused_in(
        &scratch,
        &["convert", "s.xml", "-o", "out.toml"],
        &["signed distance grid", "no TOML form"],
    );
}

/// A grid of alternating signs (every voxel a primitive) too large for the memory budget:
/// refused by the budget, naming the grid's values, before its voxels are built; `info`
/// says so rather than building them.
#[test]
fn a_grid_larger_than_the_memory_budget_is_refused_before_it_is_built() {
    let n = 64u32;
    let values: Vec<f32> = (0..n * n * n)
        .map(|i| if (i % n + i / n % n + i / (n * n)).is_multiple_of(2) { 1.0 } else { -1.0 })
        .collect();
    let scratch = Scratch::new();
    scratch.write("s.xml", grid_scene(""));
    scratch.write("g.vol", write_single_channel([n; 3], &values));
    // 24 MiB fixed, 1 MiB of values and 63³ voxels at 36 bytes (9 MiB) before any BVH.
    let budget = ("EMBRAY_MAX_MEMORY", "31457280");
    for (args, expected) in [
        (&["render", "s.xml", "--threads", "1"][..], "262144 grid values"),
        (&["info", "s.xml"][..], "not prepared"),
    ] {
        let before = scratch.snapshot();
        let run = crate::harness::Run::from(
            scratch.command(args).env(budget.0, budget.1).output().unwrap(),
        );
        run.assert_no_panic();
        if args[0] == "render" {
            assert_eq!(run.code, Some(1), "{}", run.stderr);
            run.assert_says(&["s.xml", expected, "only 30.0 MiB", "signed distance grids"]);
        } else {
            assert!(run.stdout.contains(expected), "{}", run.stdout);
        }
        assert_eq!(scratch.snapshot(), before);
    }
}
