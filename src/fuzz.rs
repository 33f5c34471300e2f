//! Every reader of a file from outside, as one entry point taking the file's bytes: what
//! the property tests (`tests/reader_fuzz.rs`, in `cargo test`) and the coverage-guided
//! `cargo fuzz` targets (`fuzz/`) both drive. The seed corpus is `fuzz/corpus/<reader>/`.
//!
//! A reader's contract, whatever the bytes: a value or an error naming the file, short;
//! never a panic, an abort or an allocation sized by the file beyond what it can hold.

use std::path::Path;

/// A reader, named as its corpus folder is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reader {
    TomlScene,
    CourseXml,
    MitsubaXml,
    Obj,
    Mtl,
    Ply,
    Serialized,
    SdfVol,
    Texture,
    RadianceMap,
    CompareImage,
    ReferenceExr,
    PartFile,
    Lut,
    JobFile,
}

impl Reader {
    pub const ALL: [Reader; 15] = [
        Reader::TomlScene,
        Reader::CourseXml,
        Reader::MitsubaXml,
        Reader::Obj,
        Reader::Mtl,
        Reader::Ply,
        Reader::Serialized,
        Reader::SdfVol,
        Reader::Texture,
        Reader::RadianceMap,
        Reader::CompareImage,
        Reader::ReferenceExr,
        Reader::PartFile,
        Reader::Lut,
        Reader::JobFile,
    ];

    /// The corpus folder's name (and the `cargo fuzz` target's).
    pub fn name(self) -> &'static str {
        match self {
            Reader::TomlScene => "toml_scene",
            Reader::CourseXml => "course_xml",
            Reader::MitsubaXml => "mitsuba_xml",
            Reader::Obj => "obj",
            Reader::Mtl => "mtl",
            Reader::Ply => "ply",
            Reader::Serialized => "serialized",
            Reader::SdfVol => "sdf_vol",
            Reader::Texture => "texture",
            Reader::RadianceMap => "radiance_map",
            Reader::CompareImage => "compare_image",
            Reader::ReferenceExr => "reference_exr",
            Reader::PartFile => "part_file",
            Reader::Lut => "lut",
            Reader::JobFile => "job_file",
        }
    }

    pub fn by_name(name: &str) -> Option<Reader> {
        Reader::ALL.into_iter().find(|r| r.name() == name)
    }

    /// The name the file under test has (the one an error must name).
    pub fn file_name(self) -> &'static str {
        match self {
            Reader::TomlScene => "fuzz.toml",
            Reader::CourseXml => "fuzz.xml",
            Reader::MitsubaXml => "fuzz_mitsuba.xml",
            Reader::Obj => "fuzz.obj",
            Reader::Mtl => "fuzz.mtl",
            Reader::Ply => "fuzz.ply",
            Reader::Serialized => "fuzz.serialized",
            Reader::SdfVol => "fuzz.vol",
            Reader::Texture => "fuzz_texture.img",
            Reader::RadianceMap => "fuzz_radiance.img",
            Reader::CompareImage => "fuzz_compare.img",
            Reader::ReferenceExr => "fuzz_reference.exr",
            Reader::PartFile => "fuzz_part.exr",
            Reader::Lut => "fuzz.cube",
            Reader::JobFile => "job.json",
        }
    }

    /// Reads as [`Reader::read`] and panics if the reader broke its contract: an error
    /// that does not name the file, or an overlong one (a panic inside the reader is one
    /// too). What the property tests and the fuzz targets assert.
    pub fn read_and_check(self, bytes: &[u8], dir: &Path) {
        if let Err(message) = self.read(bytes, dir) {
            assert!(
                message.contains(self.file_name()),
                "{}: the error does not name {}: {message}",
                self.name(),
                self.file_name()
            );
            assert!(message.len() < 4000, "{}: a {}-byte message", self.name(), message.len());
        }
    }

    /// Writes `bytes` as this reader's file in `dir` (an empty folder of the caller's) and
    /// reads it as embray reads such a file. `Ok` if it was accepted; the error otherwise.
    pub fn read(self, bytes: &[u8], dir: &Path) -> Result<(), String> {
        let path = dir.join(self.file_name());
        std::fs::write(&path, bytes).map_err(|e| format!("writing {}: {e}", path.display()))?;
        let text = || String::from_utf8_lossy(bytes).into_owned();
        let err = |e: &dyn std::fmt::Display| e.to_string();
        match self {
            Reader::TomlScene => {
                crate::scene::load_str_with_warnings(&text(), &path).map(drop).map_err(|e| err(&e))
            }
            Reader::CourseXml => crate::scene::ceng795::load_str_with_warnings(&text(), &path)
                .map(drop)
                .map_err(|e| err(&e)),
            Reader::MitsubaXml => {
                crate::scene::mitsuba::load(&path, &text(), &[]).map(drop).map_err(|e| err(&e))
            }
            Reader::Obj | Reader::Mtl | Reader::Ply => {
                let mesh = match self {
                    Reader::Mtl => {
                        let obj =
                            "mtllib fuzz.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
                        let at = dir.join("uses_mtl.obj");
                        std::fs::write(&at, obj)
                            .map_err(|e| format!("writing {}: {e}", at.display()))?;
                        "uses_mtl.obj"
                    }
                    _ => self.file_name(),
                };
                let scene = format!(
                    "[camera]\nlookfrom = [0.0, 0.0, 4.0]\nlookat = [0.0, 0.0, 0.0]\n\
                     vfov = 40.0\nresolution = [8, 8]\n\n[[objects]]\ntype = \"mesh\"\n\
                     file = \"{mesh}\"\n"
                );
                crate::scene::load_str_with_warnings(&scene, &dir.join("mesh.toml"))
                    .map(drop)
                    .map_err(|e| err(&e))
            }
            Reader::Serialized | Reader::SdfVol => {
                let kind = if self == Reader::SdfVol { "sdfgrid" } else { "serialized" };
                let scene = format!(
                    "<scene version=\"3.0.0\"><sensor type=\"perspective\"/>\
                     <shape type=\"{kind}\"><string name=\"filename\" value=\"{}\"/>\
                     </shape></scene>",
                    self.file_name()
                );
                crate::scene::mitsuba::load(&dir.join("mesh.xml"), &scene, &[])
                    .map(drop)
                    .map_err(|e| err(&e))
            }
            Reader::Texture | Reader::RadianceMap => {
                use crate::scene::texture_image::{ImageRef, load, load_radiance};
                let scene = dir.join("image.toml");
                let at = ImageRef {
                    image: path.clone(),
                    scene: &scene,
                    item: "fuzz".into(),
                    line: crate::scene::Line(None),
                };
                match self {
                    Reader::Texture => load(&at, true),
                    _ => load_radiance(&at, true),
                }
                .map(drop)
                .map_err(|e| err(&e))
            }
            Reader::CompareImage => crate::compare::read_rgb(&path).map(drop).map_err(|e| err(&e)),
            Reader::ReferenceExr => {
                crate::bench::convergence::read_reference(&path).map(drop).map_err(|e| err(&e))
            }
            Reader::PartFile => {
                let meta = crate::distributed::read_part_meta(&path).map_err(|e| err(&e))?;
                crate::distributed::read_part_sums(&path, &meta).map(drop).map_err(|e| err(&e))
            }
            Reader::Lut => crate::output::Lut3d::read(&path).map(drop).map_err(|e| err(&e)),
            Reader::JobFile => crate::distributed::slurm::JobFile::read(dir).map(drop),
        }
    }
}
