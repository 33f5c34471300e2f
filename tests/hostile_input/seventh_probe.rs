//! Holes a seventh hostile probe found: readers that grew faster than their input (a PLY's
//! attribute names, an MTL's unknown statements, Mitsuba's `$name`s: 49 s, 33 s and 51 s on
//! files of a few MB or less), a PNG whose compressed ICC profile inflated to 500 MB while
//! its header was read, before any size was checked; and, found by the same probe and mended
//! later, bytes that are not UTF-8 without their line, benchmark sizes and `.cube` tables
//! outside the memory budget, and a failed Slurm submission's leftover job folder.

use crate::harness::{Scratch, accepted_in, run_limited, scene, with_mesh};
use std::time::{Duration, Instant};

/// The bound of each run below: a hang guard, not a speed goal (each took 30 s or more).
const HANG: Duration = Duration::from_secs(10);

/// A PLY of one triangle whose vertices declare 200,000 one-letter-postfixed properties
/// (`p0_x`, `p1_x`, …): each was compared with every earlier prefix (49 s).
#[test]
fn many_ply_attribute_names_are_grouped_in_linear_time() {
    let scratch = Scratch::new();
    let count = 200_000;
    let mut header = String::from(
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n\
         property float y\nproperty float z\n",
    );
    for i in 0..count {
        header.push_str(&format!("property uchar p{i}_x\n"));
    }
    header.push_str("element face 1\nproperty list uchar int vertex_indices\nend_header\n");
    let mut bytes = header.into_bytes();
    for vertex in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        bytes.extend(vertex.iter().flat_map(|c| c.to_le_bytes()));
        bytes.extend(std::iter::repeat_n(0u8, count));
    }
    bytes.push(3);
    bytes.extend([0i32, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    scratch.write("m.ply", bytes);
    scratch.write("s.toml", with_mesh("m.ply"));
    let start = Instant::now();
    accepted_in(&scratch, &["info", "s.toml"]);
    assert!(start.elapsed() < HANG, "{:?}", start.elapsed());
}

/// An MTL of 80,000 statements no MTL knows: its warnings were de-duplicated against each
/// other (33 s) and printed one a statement; now the first eight kinds and one for the rest.
#[test]
fn many_unknown_mtl_statements_are_few_warnings_in_linear_time() {
    let scratch = Scratch::new();
    let statements: String = (0..80_000).map(|i| format!("zz{i} 1\n")).collect();
    scratch.write("m.mtl", format!("newmtl m0\n{statements}"));
    scratch.write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m0\nf 1 2 3\n");
    scratch.write("s.toml", scene("[[objects]]\ntype = \"mesh\"\nfile = \"m.obj\"\n"));
    let start = Instant::now();
    let run = accepted_in(&scratch, &["info", "s.toml"]);
    assert!(start.elapsed() < HANG, "{:?}", start.elapsed());
    let warnings = run.stderr.lines().filter(|l| l.contains("m.mtl")).count();
    assert_eq!(warnings, 9, "{}", run.stderr);
    run.assert_says(&["other statements embray does not know", "79988 more"]);
}

/// 20,000 `<default>`s each naming the first: every `$` value tried every name (51 s).
#[test]
fn many_mitsuba_parameters_are_substituted_in_linear_time() {
    let scratch = Scratch::new();
    let defaults: String =
        (1..20_000).map(|i| format!("<default name=\"p{i}\" value=\"$p0\"/>\n")).collect();
    scratch.write(
        "s.xml",
        format!(
            "<scene version=\"3.0.0\">\n<default name=\"p0\" value=\"8\"/>\n{defaults}\
             <sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" \
             value=\"$p19999\"/><integer name=\"height\" value=\"$p7\"/></film></sensor>\n\
             <emitter type=\"constant\"/>\n</scene>\n"
        ),
    );
    let start = Instant::now();
    let run = accepted_in(&scratch, &["info", "s.xml"]);
    assert!(start.elapsed() < HANG, "{:?}", start.elapsed());
    assert!(run.stdout.contains("8x8"), "{}", run.stdout);
}

/// A 4 × 4 PNG with an iCCP chunk that inflates to `inflated` zero bytes (built from one
/// byte-aligned deflate block repeated, so that making it is quick in a debug build).
fn png_with_inflating_icc_profile(inflated: usize) -> Vec<u8> {
    use flate2::{Compress, Compression, FlushCompress};
    const BLOCK: usize = 1 << 20;
    let mut block = Vec::with_capacity(BLOCK);
    Compress::new(Compression::fast(), false)
        .compress_vec(&vec![0u8; BLOCK], &mut block, FlushCompress::Sync)
        .unwrap();
    let blocks = inflated / BLOCK;
    let mut zlib = vec![0x78, 0x01];
    for _ in 0..blocks {
        zlib.extend(&block);
    }
    // The last block: empty and final, then Adler-32 of the zeros (a = 1, b = n mod 65521).
    zlib.extend([0x03, 0x00]);
    let b = ((blocks * BLOCK) % 65521) as u32;
    zlib.extend(((b << 16) | 1).to_be_bytes());
    let mut png = Vec::new();
    image::RgbImage::new(4, 4)
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    let mut chunk = b"iCCP".to_vec();
    chunk.extend(b"bomb\0\0");
    chunk.extend(&zlib);
    let mut crc = flate2::Crc::new();
    crc.update(&chunk);
    let mut iccp = ((chunk.len() - 4) as u32).to_be_bytes().to_vec();
    iccp.extend(&chunk);
    iccp.extend(crc.sum().to_be_bytes());
    // After the signature (8 bytes) and IHDR (25).
    png.splice(33..33, iccp);
    png
}

/// The profile was inflated (500 MB) as the header was read, before the image's size was
/// checked: under a 400 MB address space the process aborted. Now a header may hold 16 MiB,
/// and a profile beyond it is dropped (embray does not manage colour).
#[test]
fn an_inflating_icc_profile_is_not_inflated() {
    // The builder's profile is a whole zlib stream of the zeros it claims.
    let small = png_with_inflating_icc_profile(3 << 20);
    let start = 33 + 8 + b"bomb\0\0".len();
    let length = u32::from_be_bytes(small[33..37].try_into().unwrap()) as usize;
    let stream = &small[start..33 + 8 + length];
    let mut inflated = Vec::new();
    std::io::Read::read_to_end(&mut flate2::read::ZlibDecoder::new(stream), &mut inflated).unwrap();
    assert!(inflated.len() == 3 << 20 && inflated.iter().all(|&b| b == 0));
    let scratch = Scratch::new();
    scratch.write("bomb.png", png_with_inflating_icc_profile(500 << 20));
    image::RgbImage::new(4, 4).save(scratch.path("ok.png")).unwrap();
    scratch.write(
        "s.toml",
        scene("").replace(
            "albedo = [0.5, 0.5, 0.5]",
            "texture = { type = \"image\", file = \"bomb.png\" }",
        ),
    );
    for args in [&["compare", "bomb.png", "ok.png"][..], &["info", "s.toml"]] {
        let run = run_limited(&scratch, args, libc::RLIMIT_AS, 400_000_000);
        run.assert_no_panic();
        assert_eq!(run.code, Some(0), "{args:?}: {}", run.stderr);
    }
}

/// A Latin-1 byte in a scene, OBJ or MTL file was reported without a line ("stream did not
/// contain valid UTF-8"): in a 100 MB OBJ the user could not find it.
#[test]
fn a_byte_that_is_not_utf8_is_reported_with_its_line() {
    let scratch = Scratch::new();
    let mut toml = scene("").into_bytes();
    toml.extend(b"# caf\xe9\n");
    scratch.write("s.toml", toml);
    crate::harness::refused_in(&scratch, &["info", "s.toml"], &["s.toml", "line 24: byte 0xE9"]);
    scratch.write("m.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\no \xff\nf 1 2 3\n");
    scratch.write("t.toml", with_mesh("m.obj"));
    let expected = ["m.obj", "line 4: byte 0xFF is not UTF-8", "t.toml"];
    crate::harness::refused_in(&scratch, &["info", "t.toml"], &expected);
}

/// `bench speed --large` and `bench queries --resolution` made their scene and rays before
/// any check: 51 GB asked for, and an abort.
#[test]
fn benchmark_sizes_are_held_against_the_memory_before_use() {
    let scratch = Scratch::new();
    let large = ["bench", "speed", "--large", "4294967296", "--only", "large", "--runs", "1"];
    crate::harness::refused_in(&scratch, &large, &["--large 4294967296 needs about", "GiB"]);
    let queries = ["bench", "queries", "--resolution", "16384x16384", "--runs", "1"];
    let expected = ["the query benchmark at 16384x16384 needs about", "only 100.0 MiB"];
    crate::harness::refused_under_memory(&scratch, &queries, 100 << 20, &expected);
}

/// A `.cube` table (up to 256³ entries, 200 MB of text) was read outside the budget: 393 MB
/// under a budget of 100 MB, then "out of memory" without a size.
#[test]
fn a_colour_table_is_held_against_the_memory_before_it_is_read() {
    let scratch = Scratch::new();
    let n = 64;
    let mut cube = format!("LUT_3D_SIZE {n}\n");
    for i in 0..n * n * n {
        let [r, g, b] = [i % n, i / n % n, i / (n * n)].map(|c| c as f64 / (n - 1) as f64);
        cube.push_str(&format!("{r:.6} {g:.6} {b:.6}\n"));
    }
    scratch.write("m.cube", cube);
    scratch.write("s.toml", scene(""));
    let args = ["render", "s.toml", "-o", "o.png", "--lut", "m.cube"];
    let expected = ["m.cube: reading it needs about", "only 4.8 MiB"];
    crate::harness::refused_under_memory(&scratch, &args, 5_000_000, &expected);
}

/// With Slurm down, a first submission failed but left its job folder (`job.json` with no
/// submission), which then blocked the retry and read as lost tasks.
#[test]
fn a_submission_slurm_refuses_leaves_no_job_folder() {
    use std::os::unix::fs::PermissionsExt;
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    let sbatch = "#!/bin/sh\nif [ \"$1\" = --version ]; then echo 'slurm 23.02.6'; exit 0; fi\n\
                  echo 'sbatch: error: Batch job submission failed: Unable to contact slurm \
                  controller' >&2\nexit 1\n";
    let fake = scratch.write("bin/sbatch", sbatch);
    std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
    let path = format!("{}:{}", scratch.path("bin").display(), std::env::var("PATH").unwrap());
    let before = scratch.snapshot();
    for _ in 0..2 {
        let args = ["slurm", "s.toml", "--parts", "2", "--split", "samples", "--out", "job"];
        let args = [&args[..], &["--no-wait", "--", "--spp", "2"]].concat();
        let run =
            crate::harness::Run::from(scratch.command(&args).env("PATH", &path).output().unwrap());
        run.assert_no_panic();
        assert_eq!(run.code, Some(1), "{}", run.stderr);
        run.assert_says(&["Unable to contact slurm controller"]);
        assert!(!run.stderr.contains("already holds a job"), "{}", run.stderr);
        assert!(!scratch.path("job").exists(), "the job folder was left");
        assert_eq!(scratch.snapshot(), before);
    }
}
