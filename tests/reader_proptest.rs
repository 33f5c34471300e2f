//! Property tests of the readers of files other than scenes, on mutated valid files: part
//! files (header and pixels), EXR images read as references (`compare`, `tonemap`, `bench
//! convergence`), `.cube` LUTs and Slurm job records. Whatever the bytes, a read returns a
//! value or an error naming the file; it never panics, never aborts on a size taken from
//! the file, and its message stays short.
//!
//! `cargo test --test reader_proptest` runs 256 cases per reader from a fixed seed (under a
//! second, so CI stays reproducible and fast); `EMBRAY_PROPTEST_CASES=20000
//! EMBRAY_PROPTEST_SEED=random cargo test --release --test reader_proptest` runs longer.

mod common;

use common::command::{embray, temp_dir};
use embray::distributed::slurm::JobFile;
use embray::distributed::{read_part_meta, read_part_sums};
use embray::film::Film;
use embray::output::Lut3d;
use glam::Vec3;
use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

fn config() -> ProptestConfig {
    common::proptest_config(256, 34)
}

/// One change to a file's bytes: at a position (a fraction of its length) delete some bytes
/// and insert others: sizes at the limits of the integer types, or random bytes.
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
        .chain(["4000000000", "-1", "1e39", "nan", "99999", "\"", "{", "}"].map(|t| t.into()))
        .collect();
    let insert = prop_oneof![
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

/// The seed files, made once: a part file by `embray render --part`, an EXR by the writer.
struct Seeds {
    part: Vec<u8>,
    exr: Vec<u8>,
}

fn seeds() -> &'static Seeds {
    static SEEDS: OnceLock<Seeds> = OnceLock::new();
    SEEDS.get_or_init(|| {
        let dir = temp_dir("reader-proptest-seeds");
        std::fs::write(dir.join("s.toml"), common::command::GOOD_SCENE).unwrap();
        let out = embray(
            &[
                "render", "s.toml", "--spp", "2", "--part", "0/2", "--split", "samples", "-o",
                "p.exr",
            ],
            &dir,
        );
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let mut film = Film::new(6, 4);
        film.color.iter_mut().enumerate().for_each(|(i, c)| *c = Vec3::splat(i as f32 * 0.1));
        embray::output::write_exr(&film, &dir.join("r.exr")).unwrap();
        let seeds = Seeds {
            part: std::fs::read(dir.join("p.exr")).unwrap(),
            exr: std::fs::read(dir.join("r.exr")).unwrap(),
        };
        std::fs::remove_dir_all(&dir).unwrap();
        seeds
    })
}

const LUT_SEED: &str = "TITLE \"t\"\nLUT_3D_SIZE 2\nDOMAIN_MIN 0 0 0\nDOMAIN_MAX 1 1 1\n\
0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n";

const JOB_SEED: &str = r#"{"embray": "/bin/embray", "scene": "/s.toml", "parts": 4, "split": "tiles",
"render_args": ["--spp", "4"], "sbatch": {"partition": null, "time": null, "cpus_per_task": 1,
"max_running": null, "extra": []}, "submissions": [{"array_job": "7", "parts": [0, 1, 2, 3],
"merge_job": "8"}]}"#;

/// A file of its own for each thread.
fn file(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "embray-reader-proptest-{}-{:?}",
        std::process::id(),
        std::thread::current().id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[track_caller]
fn assert_names(message: &str, path: &Path) {
    let name = path.file_name().unwrap().to_string_lossy();
    assert!(message.contains(name.as_ref()), "the error does not name {name}: {message}");
    assert!(message.len() < 4000, "an overlong message ({} bytes)", message.len());
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn part_files_read_or_name_the_file(edits in proptest::collection::vec(edit(), 1..4)) {
        let path = file("part.exr");
        std::fs::write(&path, mutate(&seeds().part, &edits)).unwrap();
        match read_part_meta(&path) {
            Err(e) => assert_names(&e.to_string(), &path),
            Ok(meta) => {
                if let Err(e) = read_part_sums(&path, &meta) {
                    assert_names(&e.to_string(), &path);
                }
            }
        }
    }

    #[test]
    fn reference_exrs_read_or_name_the_file(edits in proptest::collection::vec(edit(), 1..4)) {
        let path = file("ref.exr");
        std::fs::write(&path, mutate(&seeds().exr, &edits)).unwrap();
        if let Err(e) = embray::bench::convergence::read_reference(&path) {
            assert_names(&e.to_string(), &path);
        }
    }

    #[test]
    fn luts_read_or_name_the_file(edits in proptest::collection::vec(edit(), 1..6)) {
        let path = file("look.cube");
        std::fs::write(&path, mutate(LUT_SEED.as_bytes(), &edits)).unwrap();
        if let Err(e) = Lut3d::read(&path) {
            assert_names(&e.to_string(), &path);
        }
    }

    #[test]
    fn job_files_read_or_name_the_file(edits in proptest::collection::vec(edit(), 1..6)) {
        let path = file("job.json");
        std::fs::write(&path, mutate(JOB_SEED.as_bytes(), &edits)).unwrap();
        if let Err(e) = JobFile::read(path.parent().unwrap()) {
            assert_names(&e, &path);
        }
    }
}

#[test]
fn the_seeds_themselves_read() {
    let path = file("seed-part.exr");
    std::fs::write(&path, &seeds().part).unwrap();
    let meta = read_part_meta(&path).unwrap();
    read_part_sums(&path, &meta).unwrap();
    let path = file("seed-ref.exr");
    std::fs::write(&path, &seeds().exr).unwrap();
    embray::bench::convergence::read_reference(&path).unwrap();
    let path = file("seed.cube");
    std::fs::write(&path, LUT_SEED).unwrap();
    Lut3d::read(&path).unwrap();
    let path = file("job.json");
    std::fs::write(&path, JOB_SEED).unwrap();
    JobFile::read(path.parent().unwrap()).unwrap();
}

/// Found by a 200,000-case run: four bytes changed in the seed EXR's pixel data made the
/// `exr` crate fail an internal assertion (a panic in every build) instead of an error.
#[test]
fn an_exr_that_trips_the_decoders_own_assertion_is_an_error() {
    let edits = [Edit { at: 0.567_937_356_478_694_6, delete: 4, insert: vec![0, 0, 16, 0] }];
    let path = file("tripped.exr");
    std::fs::write(&path, mutate(&seeds().exr, &edits)).unwrap();
    let error = embray::bench::convergence::read_reference(&path).unwrap_err().to_string();
    assert_names(&error, &path);
}
