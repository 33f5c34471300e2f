//! Every reader of outside files (`embray::fuzz::Reader`: scenes in three formats, meshes,
//! MTL, Mitsuba `serialized`, texture and radiance images, `compare`'s images, reference
//! EXRs, part files, LUTs, Slurm job records) on mutated copies of its seed corpus
//! (`fuzz/corpus/<reader>/`, the corpus `cargo fuzz` starts from too). Whatever the bytes, a
//! read returns a value or a short error naming the file; it never panics, and never aborts
//! on a size taken from the file.
//!
//! `cargo test --test reader_fuzz` runs 256 cases per reader from a fixed seed (seconds, so
//! CI stays reproducible and fast). Longer: `EMBRAY_PROPTEST_CASES=20000
//! EMBRAY_PROPTEST_SEED=random cargo test --release --test reader_fuzz`; coverage-guided:
//! `fuzz/README.md`.

mod common;

use embray::fuzz::Reader;
use proptest::prelude::*;
use std::path::PathBuf;

fn config() -> ProptestConfig {
    common::proptest_config(256, 34)
}

/// Tokens that have broken parsers: numbers at and past the limits, syntax characters of
/// the formats, their keywords.
const TOKENS: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "-1",
    "0",
    "1e39",
    "1e308",
    "-0",
    "99999999999999999999",
    "4294967296",
    "\"",
    "'",
    "[",
    "]",
    "{",
    "}",
    "=",
    ",",
    "\n",
    "\r\n",
    " ",
    "#",
    "\\",
    "\0",
    "é",
    "v",
    "vt",
    "vn",
    "f",
    "usemtl",
    "mtllib",
    "newmtl",
    "map_Kd",
    "Ks",
    "Ns",
    "Ni",
    "Tr",
    "illum",
    "bump",
    "-bm",
    "norm",
    "map_d",
    "Pm",
    "o",
    "g",
    "1/2/3",
    "//",
    "-2",
    "ply",
    "element",
    "property",
    "list",
    "uchar",
    "float",
    "end_header",
    "binary_little_endian",
    "<",
    ">",
    "</",
    "/>",
    "<Scene>",
    "<Camera>",
    "<scene version=\"3.0.0\">",
    "<ref id=\"gold\"/>",
    "$spp",
    "&amp;",
    "&bogus;",
    "<!--",
    "]]>",
    "[[objects]]",
    "type",
    "mesh",
    "sphere",
    "repeat",
    "matrix",
    "LUT_3D_SIZE",
    "DOMAIN_MAX",
];

/// One change to a file: at a position (a fraction of its length) delete some bytes and
/// insert a token, an integer at the limits of its type (little-endian, as binary headers
/// hold them), or random bytes.
#[derive(Clone, Debug)]
struct Edit {
    at: f64,
    delete: usize,
    insert: Vec<u8>,
}

fn edit() -> impl Strategy<Value = Edit> {
    let extremes: Vec<Vec<u8>> = [0u32, 1, 0x7fff_ffff, 0xffff_ffff, 16385, 1 << 20]
        .iter()
        .map(|v| v.to_le_bytes().to_vec())
        .collect();
    let insert = prop_oneof![
        3 => proptest::sample::select(TOKENS).prop_map(|t| t.as_bytes().to_vec()),
        2 => proptest::sample::select(extremes),
        1 => proptest::collection::vec(any::<u8>(), 0..8),
    ];
    (0.0..1.0f64, 0..8usize, insert).prop_map(|(at, delete, insert)| Edit { at, delete, insert })
}

fn mutate(seed: &[u8], edits: &[Edit]) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for edit in edits {
        let at = ((bytes.len() as f64) * edit.at) as usize;
        let end = (at + edit.delete).min(bytes.len());
        bytes.splice(at..end, edit.insert.iter().copied());
    }
    bytes
}

/// The seed files of `reader`, sorted by name.
fn corpus(reader: Reader) -> Vec<Vec<u8>> {
    let dir = common::repo_path("fuzz/corpus").join(reader.name());
    let mut paths: Vec<PathBuf> =
        std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    paths.sort();
    assert!(!paths.is_empty(), "no seed in {}", dir.display());
    paths.iter().map(|p| std::fs::read(p).unwrap()).collect()
}

/// An empty folder of its own for each thread and reader.
fn folder(reader: Reader) -> common::command::TempDir {
    let thread = std::thread::current().id();
    common::command::temp_dir(&format!("reader-fuzz-{thread:?}-{}", reader.name()))
}

/// Reads a mutation of one of `reader`'s seeds.
fn read_mutated(reader: Reader, which: usize, edits: &[Edit]) {
    let seeds = corpus(reader);
    let dir = folder(reader);
    reader.read_and_check(&mutate(&seeds[which % seeds.len()], edits), &dir);
}

macro_rules! fuzz_readers {
    ($($test:ident: $reader:expr;)*) => {
        proptest! {
            #![proptest_config(config())]
            $(
                #[test]
                fn $test(which in 0..8usize, edits in proptest::collection::vec(edit(), 1..6)) {
                    read_mutated($reader, which, &edits);
                }
            )*
        }
    };
}

fuzz_readers! {
    toml_scenes_load_or_name_the_file: Reader::TomlScene;
    course_scenes_load_or_name_the_file: Reader::CourseXml;
    mitsuba_scenes_load_or_name_the_file: Reader::MitsubaXml;
    obj_meshes_load_or_name_the_file: Reader::Obj;
    mtl_files_load_or_name_the_file: Reader::Mtl;
    ply_meshes_load_or_name_the_file: Reader::Ply;
    serialized_meshes_load_or_name_the_file: Reader::Serialized;
    sdf_grids_load_or_name_the_file: Reader::SdfVol;
    textures_load_or_name_the_file: Reader::Texture;
    radiance_maps_load_or_name_the_file: Reader::RadianceMap;
    compared_images_read_or_name_the_file: Reader::CompareImage;
    reference_exrs_read_or_name_the_file: Reader::ReferenceExr;
    part_files_read_or_name_the_file: Reader::PartFile;
    luts_read_or_name_the_file: Reader::Lut;
    job_files_read_or_name_the_file: Reader::JobFile;
}

/// Every seed is a valid file of its kind (a corpus of rejected files would test only the
/// readers' first check), and every reader has a corpus.
#[test]
fn every_seed_is_read() {
    for reader in Reader::ALL {
        for (i, seed) in corpus(reader).iter().enumerate() {
            let dir = folder(reader);
            reader.read(seed, &dir).unwrap_or_else(|e| panic!("{} seed {i}: {e}", reader.name()));
        }
    }
}

/// Found by a 200,000-case run: four bytes changed in an EXR made the `exr` crate panic
/// (an overflow in its header arithmetic where overflow is checked, as in `cargo test`'s
/// builds; in release builds the product wraps and the file happens to decode). The read
/// is guarded: an error naming the file, never a panic. Kept as found.
#[test]
fn an_exr_that_made_the_decoder_panic_is_read_or_named() {
    let bytes = std::fs::read(common::repo_path("tests/data/exr_overflows_decoder.exr")).unwrap();
    let dir = folder(Reader::ReferenceExr);
    Reader::ReferenceExr.read_and_check(&bytes, &dir);
}
