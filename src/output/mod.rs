//! The one place that writes files: EXR (linear float RGB plus depth `Z` and normal
//! `N.X/N.Y/N.Z` channels), tone-mapped sRGB PNG, and the statistics report. Every file is
//! written to a temporary name in the same folder and renamed into place, so a failure never
//! leaves a half-written image behind.

mod exr;
mod naming;
mod png;
pub mod stats;
pub mod tonemap;

pub use exr::write_exr;
pub use naming::camera_outputs;
pub use png::{to_srgb8, write_png};
pub use tonemap::ToneMap;

use std::path::{Path, PathBuf};

#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("cannot write '{path}': {message}")]
    Write { path: PathBuf, message: String },
}

pub(crate) fn write_error(path: &Path, message: impl ToString) -> OutputError {
    OutputError::Write { path: path.to_path_buf(), message: message.to_string() }
}

/// Runs `write` against a temporary path beside `path`, then renames it into place.
pub(crate) fn write_atomically(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<(), OutputError> {
    let file_name =
        path.file_name().ok_or_else(|| write_error(path, "not a file name"))?.to_string_lossy();
    let temp = path.with_file_name(format!(".{file_name}.{}.tmp", std::process::id()));
    if let Err(message) = write(&temp) {
        let _ = std::fs::remove_file(&temp);
        return Err(write_error(path, message));
    }
    std::fs::rename(&temp, path).map_err(|e| {
        let _ = std::fs::remove_file(&temp);
        write_error(path, e)
    })
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
        assert!(write_png(&film, &target, ToneMap::Aces, 0.0).is_err());
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
