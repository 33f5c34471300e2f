//! Reading scene inputs (scene files, meshes, material libraries): from disk, or from the
//! binary for the bundled scenes.

use std::io;
use std::path::Path;

/// The bytes of `path`.
pub(crate) fn read_bytes(path: &Path) -> io::Result<Vec<u8>> {
    match crate::bundled::file(path) {
        Some(bytes) => Ok(bytes.to_vec()),
        None => std::fs::read(path),
    }
}

/// The text of `path` (UTF-8).
pub(crate) fn read_text(path: &Path) -> io::Result<String> {
    String::from_utf8(read_bytes(path)?).map_err(|_| {
        io::Error::new(io::ErrorKind::InvalidData, "stream did not contain valid UTF-8")
    })
}
