//! The one place that writes files: EXR (linear float RGB plus depth `Z` and normal
//! `N.X/N.Y/N.Z` channels), tone-mapped sRGB PNG, the statistics report, and any other file a
//! command writes. A run first checks every output path (`plan`: usable, not an input, not
//! another output), then writes each output under a temporary name beside its target and
//! commits them all together (`transaction`), so a failure never leaves a half-written,
//! mismatched or destroyed file behind. Interrupted runs remove their temporary files
//! (`cleanup`).

mod aovs;
mod cleanup;
mod exr;
mod format;
mod lut;
mod naming;
mod photographic;
mod plan;
mod png;
pub mod stats;
mod target;
pub mod tonemap;
mod transaction;

pub use aovs::Aovs;
pub use cleanup::remove_temp_files_on_signals;
pub use exr::{encode_exr, write_exr};
pub use format::{ImageFormat, encode_display_rgb8};
pub use lut::{Lut3d, LutError};
pub use naming::{camera_outputs, image_name_key, image_name_problem};
pub use photographic::Photographic;
pub use plan::OutputPlan;
pub use png::{
    DisplayLook, MAX_EXPOSURE_STOPS, encode_display, encode_png, encode_png_graded, encode_rgb8,
    exposure_in_range, to_srgb8, write_png,
};
pub use target::{NAME_MAX, Target};
pub use tonemap::ToneMap;
pub use transaction::{OutputSet, WriteSeek};

use std::path::{Path, PathBuf};

#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("cannot write '{}': {message}", .path.display())]
    Write { path: PathBuf, message: String },
    #[error("{what} '{}' {reason}", .path.display())]
    Refused { what: String, path: PathBuf, reason: String },
    #[error(
        "{first_what} '{}' and {what} '{}' are the same file; every output of a run needs its own file",
        .first_path.display(), .path.display()
    )]
    Collision { first_what: String, first_path: PathBuf, what: String, path: PathBuf },
    #[error(
        "{what} '{}' is {input_what} '{}', an input of this run; embray never overwrites its inputs",
        .path.display(), .input_path.display()
    )]
    IsInput { what: String, path: PathBuf, input_what: String, input_path: PathBuf },
}

pub(crate) fn write_error(path: &Path, message: impl ToString) -> OutputError {
    OutputError::Write { path: path.to_path_buf(), message: message.to_string() }
}

/// Writes one file on its own (checked, through a temporary file, committed): for callers
/// with a single output and no inputs to protect.
pub fn write_one(
    path: &Path,
    encode: impl FnOnce(&mut dyn WriteSeek) -> std::io::Result<()>,
) -> Result<(), OutputError> {
    let target = OutputPlan::new().output("the output", path, false)?;
    let mut set = OutputSet::new();
    set.write(&target, encode)?;
    set.commit()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::Film;

    #[test]
    fn failed_write_leaves_no_file() {
        let dir = std::env::temp_dir().join(format!("embray-out-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let target = dir.join("missing-folder").join("x.png");
        let film = Film::new(2, 2);
        assert!(write_png(&film, &target, ToneMap::Aces, 0.0, &Default::default()).is_err());
        assert!(!target.exists());
        let ok = dir.join("ok.exr");
        write_exr(&film, &ok).unwrap();
        assert!(ok.exists());
        let leftovers: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .collect();
        assert!(leftovers.is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
