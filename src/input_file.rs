//! Reading scene inputs (scene files, meshes, material libraries, images to compare): from
//! disk, or from the binary for the bundled scenes. Only regular files are read (a FIFO
//! would block forever and `/dev/zero` never ends), and at most `MAX_INPUT_BYTES` of them.

use std::io::{self, Read};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError};

/// Every file read from disk so far, so that a command can refuse to overwrite any input of
/// its run (a mesh or MTL file the scene names, not only the scene).
static FILES_READ: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The files this process has read from disk (scenes, meshes, MTL files, images).
pub fn files_read() -> Vec<PathBuf> {
    FILES_READ.lock().unwrap_or_else(PoisonError::into_inner).clone()
}

/// The largest input file embray reads: 2 GiB (an OBJ of about 30 million triangles).
/// Larger files are refused before memory runs out.
pub const MAX_INPUT_BYTES: u64 = 2 << 30;

/// The bytes of `path`.
pub fn read_bytes(path: &Path) -> io::Result<Vec<u8>> {
    if let Some(bytes) = crate::bundled::file(path) {
        return Ok(bytes.to_vec());
    }
    read_capped(path, MAX_INPUT_BYTES)
}

/// The bytes of the regular file `path`, refused when longer than `cap`.
pub(crate) fn read_capped(path: &Path, cap: u64) -> io::Result<Vec<u8>> {
    use std::os::unix::fs::FileTypeExt;
    // Checked before opening: opening a FIFO blocks until someone writes to it.
    let metadata = std::fs::metadata(path)?;
    let kind = metadata.file_type();
    let what = if kind.is_dir() {
        Some("a directory")
    } else if kind.is_fifo() {
        Some("a FIFO")
    } else if kind.is_char_device() || kind.is_block_device() {
        Some("a device")
    } else if !kind.is_file() {
        Some("a socket")
    } else {
        None
    };
    if let Some(what) = what {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("is {what}, not a regular file; embray reads its inputs from regular files"),
        ));
    }
    // The length the file system gives, before reading a byte: a 3 GiB file is refused at
    // once, not after 2 GiB were read (the read below still stops at the cap if it grows).
    if metadata.len() > cap {
        return Err(too_large(cap));
    }
    let file = std::fs::File::open(path)?;
    FILES_READ.lock().unwrap_or_else(PoisonError::into_inner).push(path.to_path_buf());
    let mut bytes = Vec::new();
    // One byte more than the cap tells a file at the cap from a longer one (it may grow).
    file.take(cap + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > cap {
        return Err(too_large(cap));
    }
    Ok(bytes)
}

/// The text of `path` (UTF-8).
pub(crate) fn read_text(path: &Path) -> io::Result<String> {
    String::from_utf8(read_bytes(path)?).map_err(|error| {
        let bytes = error.as_bytes();
        let at = error.utf8_error().valid_up_to();
        let line = bytes[..at].iter().filter(|&&b| b == b'\n').count() + 1;
        let message = format!(
            "line {line}: byte 0x{:02X} is not UTF-8 (text files are read as UTF-8; a Latin-1 \
             name or comment must be converted)",
            bytes[at]
        );
        io::Error::new(io::ErrorKind::InvalidData, message)
    })
}

/// The error for a file longer than `cap` bytes.
fn too_large(cap: u64) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidInput,
        format!("is larger than {} MiB, the most embray reads from one file", cap >> 20),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn devices_and_oversized_files_are_refused() {
        let err = read_bytes(Path::new("/dev/zero")).unwrap_err().to_string();
        assert!(err.contains("not a regular file"), "{err}");
        let path = std::env::temp_dir().join(format!("embray-cap-{}", std::process::id()));
        std::fs::write(&path, [0u8; 11]).unwrap();
        assert!(read_capped(&path, 11).is_ok());
        let err = read_capped(&path, 10).unwrap_err().to_string();
        assert!(err.contains("larger than"), "{err}");
        std::fs::remove_file(&path).unwrap();
    }

    #[test]
    fn a_file_over_the_cap_is_refused_by_its_length_before_any_read() {
        // A sparse 3 GiB file: reading it up to the cap would take 2 GiB of memory.
        let path = std::env::temp_dir().join(format!("embray-sparse-{}", std::process::id()));
        let file = std::fs::File::create(&path).unwrap();
        file.set_len(3 << 30).unwrap();
        drop(file);
        let err = read_bytes(&path).unwrap_err().to_string();
        assert!(err.contains("larger than 2048 MiB"), "{err}");
        // Refused before it was opened, so it is not among the files read.
        assert!(!files_read().contains(&path));
        std::fs::remove_file(&path).unwrap();
    }
}
