//! What an output path is before anything is written to it: a regular file (or none yet),
//! written under a temporary name beside it and renamed over it; or a character device or
//! FIFO (`/dev/null`, `/dev/stdout` on a pipe), written in place, never replaced. Anything
//! else (a directory, a block device, a socket, a dangling symbolic link) is refused.

use super::OutputError;
use std::os::unix::fs::{FileTypeExt, MetadataExt};
use std::path::{Path, PathBuf};

/// The longest file name most file systems take (Linux NAME_MAX).
pub const NAME_MAX: usize = 255;

/// An output path, checked.
#[derive(Clone, Debug)]
pub struct Target {
    /// The path as the user named it (for messages).
    pub path: PathBuf,
    pub(crate) kind: TargetKind,
    pub(crate) identity: Identity,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum TargetKind {
    /// A regular file or a new one. `final_path` is where the bytes go: the path itself,
    /// or, for a symbolic link to a regular file, the file it points to (so the link stays).
    File { final_path: PathBuf },
    /// A character device or a FIFO: opened and written in place at commit.
    Stream,
}

/// What makes two paths the same file: device and inode for an existing file (so hard
/// links and different spellings match), else the absolute path with its folder resolved.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Identity {
    Inode { dev: u64, ino: u64 },
    Path(PathBuf),
}

impl Target {
    /// True for a device or FIFO (written in place).
    pub fn is_stream(&self) -> bool {
        self.kind == TargetKind::Stream
    }
}

/// The identity of `path`, whether or not it exists.
pub(crate) fn identity(path: &Path) -> Identity {
    match std::fs::metadata(path) {
        Ok(meta) => Identity::Inode { dev: meta.dev(), ino: meta.ino() },
        Err(_) => Identity::Path(resolved_path(path)),
    }
}

/// `path` made absolute with its folder's symbolic links resolved (as far as it exists).
fn resolved_path(path: &Path) -> PathBuf {
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    match (absolute.parent(), absolute.file_name()) {
        (Some(parent), Some(name)) => match std::fs::canonicalize(parent) {
            Ok(parent) => parent.join(name),
            Err(_) => resolved_path(parent).join(name),
        },
        _ => absolute,
    }
}

/// Checks `path` as an output named by `what` (`-o`, `--png`, …). With `new_folders`, a
/// missing folder is fine (it is created when the file is written).
pub fn classify(what: &str, path: &Path, new_folders: bool) -> Result<Target, OutputError> {
    let refuse = |reason: String| OutputError::Refused {
        what: what.to_owned(),
        path: path.to_path_buf(),
        reason,
    };
    let Some(name) = path.file_name() else {
        return Err(refuse("does not name a file".to_owned()));
    };
    if name.len() > NAME_MAX {
        return Err(refuse(format!(
            "has a file name of {} bytes; file names have at most {NAME_MAX}",
            name.len()
        )));
    }
    match std::fs::symlink_metadata(path) {
        Ok(link) => {
            let is_link = link.file_type().is_symlink();
            let meta = if is_link {
                std::fs::metadata(path).map_err(|e| {
                    let to = std::fs::read_link(path).unwrap_or_default();
                    refuse(format!(
                        "is a symbolic link to '{}', which cannot be used ({e}); embray does \
                         not create files through symbolic links",
                        to.display()
                    ))
                })?
            } else {
                link
            };
            let identity = Identity::Inode { dev: meta.dev(), ino: meta.ino() };
            let kind = meta.file_type();
            if kind.is_file() {
                let final_path = if is_link {
                    std::fs::canonicalize(path).map_err(|e| refuse(e.to_string()))?
                } else {
                    path.to_path_buf()
                };
                Ok(Target {
                    path: path.to_path_buf(),
                    kind: TargetKind::File { final_path },
                    identity,
                })
            } else if kind.is_char_device() || kind.is_fifo() {
                Ok(Target { path: path.to_path_buf(), kind: TargetKind::Stream, identity })
            } else if kind.is_dir() {
                Err(refuse("is a directory".to_owned()))
            } else {
                Err(refuse(
                    "is a block device or a socket; embray writes regular files, character \
                     devices and FIFOs"
                        .to_owned(),
                ))
            }
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            let parent = match path.parent() {
                Some(p) if !p.as_os_str().is_empty() => p,
                _ => Path::new("."),
            };
            match std::fs::metadata(parent) {
                Ok(meta) if meta.is_dir() => {}
                Ok(_) => {
                    return Err(refuse(format!(
                        "is in '{}', which is not a folder",
                        parent.display()
                    )));
                }
                Err(e) if e.kind() == std::io::ErrorKind::NotFound && new_folders => {}
                Err(e) => {
                    return Err(refuse(format!("is in the folder '{}': {e}", parent.display())));
                }
            }
            let final_path = path.to_path_buf();
            Ok(Target {
                path: path.to_path_buf(),
                kind: TargetKind::File { final_path },
                identity: Identity::Path(resolved_path(path)),
            })
        }
        Err(e) => Err(refuse(e.to_string())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("embray-target-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn devices_are_streams_and_directories_are_refused() {
        assert!(classify("-o", Path::new("/dev/null"), false).unwrap().is_stream());
        let dir = scratch("dir");
        let err = classify("-o", &dir, false).unwrap_err().to_string();
        assert!(err.contains("is a directory"), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn hard_links_and_spellings_share_an_identity() {
        let dir = scratch("links");
        let a = dir.join("a.png");
        std::fs::write(&a, b"x").unwrap();
        std::fs::hard_link(&a, dir.join("b.png")).unwrap();
        let via_dot = dir.join(".").join("a.png");
        assert_eq!(identity(&a), identity(&dir.join("b.png")));
        assert_eq!(identity(&a), identity(&via_dot));
        std::fs::create_dir(dir.join("x")).unwrap();
        assert_eq!(identity(&dir.join("new.png")), identity(&dir.join("x/../new.png")));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn dangling_links_and_overlong_names_are_refused() {
        let dir = scratch("dangling");
        let link = dir.join("link.png");
        std::os::unix::fs::symlink(dir.join("missing/x.png"), &link).unwrap();
        let err = classify("--png", &link, false).unwrap_err().to_string();
        assert!(err.contains("symbolic link"), "{err}");
        let long = dir.join(format!("{}.png", "n".repeat(300)));
        assert!(classify("-o", &long, false).unwrap_err().to_string().contains("at most 255"));
        let legal = dir.join(format!("{}.png", "n".repeat(251)));
        assert!(classify("-o", &legal, false).is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
