//! All the outputs of one run, committed together: each file is written in full under a
//! temporary name beside its target (every write, the flush and the sync checked), devices'
//! bytes are kept in memory, and only when every output has been written are the devices
//! written and the temporary files renamed over their targets. On any failure, or when the
//! set is dropped uncommitted, the temporary files (and folders it created) are removed and
//! no target has changed.

use super::cleanup;
use super::target::{Target, TargetKind};
use super::{OutputError, write_error};
use std::io::{Cursor, Seek, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// A sink the encoders can write to (EXR needs to seek back to its offset table).
pub trait WriteSeek: Write + Seek {}
impl<T: Write + Seek> WriteSeek for T {}

/// Numbers temporary files within the process, so their names stay short (a legal target
/// name of 255 bytes must not give an illegal temporary name).
static NEXT_TEMP: AtomicU64 = AtomicU64::new(0);

enum Staged {
    /// Written in full to `temp`, to be renamed to `final_path`.
    File { temp: PathBuf, final_path: PathBuf, shown: PathBuf },
    /// A device or FIFO: its bytes, written in place at commit.
    Stream { path: PathBuf, bytes: Vec<u8> },
}

/// The outputs of one run, written but not yet committed.
#[derive(Default)]
pub struct OutputSet {
    staged: Vec<Staged>,
    /// Folders created for outputs, deepest last; removed (when empty) on failure.
    created_folders: Vec<PathBuf>,
}

impl OutputSet {
    pub fn new() -> Self {
        Self::default()
    }

    /// Writes one output with `encode`; nothing is visible at `target` before `commit`.
    pub fn write(
        &mut self,
        target: &Target,
        encode: impl FnOnce(&mut dyn WriteSeek) -> std::io::Result<()>,
    ) -> Result<(), OutputError> {
        match &target.kind {
            TargetKind::Stream => {
                let mut buffer = Cursor::new(Vec::new());
                encode(&mut buffer).map_err(|e| write_error(&target.path, e))?;
                self.staged
                    .push(Staged::Stream { path: target.path.clone(), bytes: buffer.into_inner() });
                Ok(())
            }
            TargetKind::File { final_path } => {
                let folder = match final_path.parent() {
                    Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
                    _ => PathBuf::from("."),
                };
                self.create_folders(&folder).map_err(|e| write_error(&target.path, e))?;
                let n = NEXT_TEMP.fetch_add(1, Ordering::Relaxed);
                let temp = folder.join(format!(".embray-{}-{n}.tmp", std::process::id()));
                cleanup::register(&temp);
                let result = write_file(&temp, encode);
                // Staged even on failure, so that dropping the set removes it.
                self.staged.push(Staged::File {
                    temp,
                    final_path: final_path.clone(),
                    shown: target.path.clone(),
                });
                result.map_err(|e| write_error(&target.path, e))
            }
        }
    }

    /// Writes the devices, then renames every file into place. On an error the files not
    /// yet renamed are removed (renames within one folder fail only in rare cases, e.g. the
    /// folder was removed meanwhile; the earlier renames of the set then stay).
    pub fn commit(mut self) -> Result<(), OutputError> {
        for staged in &self.staged {
            if let Staged::Stream { path, bytes } = staged {
                let written = std::fs::OpenOptions::new()
                    .write(true)
                    .open(path)
                    .and_then(|mut f| f.write_all(bytes).and_then(|()| f.flush()));
                written.map_err(|e| write_error(path, e))?;
            }
        }
        // The lock is released before `self` drops (its cleanup takes it again).
        self.rename_all(&mut cleanup::pending())?;
        self.created_folders.clear();
        Ok(())
    }

    fn rename_all(&mut self, pending: &mut Vec<PathBuf>) -> Result<(), OutputError> {
        while !self.staged.is_empty() {
            if let Staged::File { temp, final_path, shown } = &self.staged[0] {
                std::fs::rename(temp, final_path).map_err(|e| write_error(shown, e))?;
                cleanup::unregister(pending, temp);
            }
            self.staged.remove(0);
        }
        Ok(())
    }

    /// Creates `folder` and its missing ancestors, remembering which were new.
    fn create_folders(&mut self, folder: &Path) -> std::io::Result<()> {
        let mut missing = Vec::new();
        let mut current = Some(folder);
        while let Some(dir) = current.filter(|d| !d.as_os_str().is_empty() && !d.exists()) {
            missing.push(dir.to_path_buf());
            current = dir.parent();
        }
        for dir in missing.into_iter().rev() {
            std::fs::create_dir(&dir)?;
            self.created_folders.push(dir);
        }
        Ok(())
    }
}

impl Drop for OutputSet {
    fn drop(&mut self) {
        let mut pending = cleanup::pending();
        for staged in self.staged.drain(..) {
            if let Staged::File { temp, .. } = staged {
                let _ = std::fs::remove_file(&temp);
                cleanup::unregister(&mut pending, &temp);
            }
        }
        for dir in self.created_folders.drain(..).rev() {
            let _ = std::fs::remove_dir(dir);
        }
    }
}

/// Creates `temp` (it must not exist), lets `encode` fill it, and checks the flush and the
/// sync: a full disk surfaces at one of them.
fn write_file(
    temp: &Path,
    encode: impl FnOnce(&mut dyn WriteSeek) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let file = std::fs::OpenOptions::new().write(true).create_new(true).open(temp)?;
    let mut writer = std::io::BufWriter::new(file);
    encode(&mut writer)?;
    writer.flush()?;
    let file = writer.into_inner().map_err(|e| e.into_error())?;
    file.sync_all()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::target::classify;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("embray-tx-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn nothing_changes_until_every_output_is_written() {
        let dir = scratch("all");
        let (a, b) = (dir.join("a.txt"), dir.join("b.txt"));
        std::fs::write(&a, "old a").unwrap();
        let mut set = OutputSet::new();
        set.write(&classify("a", &a, false).unwrap(), |w| w.write_all(b"new a")).unwrap();
        let failed =
            set.write(&classify("b", &b, false).unwrap(), |_| Err(std::io::Error::other("boom")));
        assert!(failed.unwrap_err().to_string().contains("boom"));
        drop(set);
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "old a");
        assert_eq!(entries(&dir), ["a.txt"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn commit_renames_everything_and_keeps_links() {
        let dir = scratch("commit");
        let real = dir.join("real.txt");
        std::fs::write(&real, "old").unwrap();
        let link = dir.join("link.txt");
        std::os::unix::fs::symlink(&real, &link).unwrap();
        let mut set = OutputSet::new();
        set.write(&classify("l", &link, false).unwrap(), |w| w.write_all(b"new")).unwrap();
        set.write(&classify("n", &dir.join("sub/new.txt"), true).unwrap(), |w| w.write_all(b"n"))
            .unwrap();
        set.write(&classify("d", Path::new("/dev/null"), false).unwrap(), |w| w.write_all(b"x"))
            .unwrap();
        set.commit().unwrap();
        assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        assert_eq!(std::fs::read_to_string(&real).unwrap(), "new");
        assert_eq!(std::fs::read_to_string(dir.join("sub/new.txt")).unwrap(), "n");
        assert_eq!(entries(&dir), ["link.txt", "real.txt", "sub"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_full_device_is_an_error_and_folders_made_for_nothing_are_removed() {
        let dir = scratch("full");
        let mut set = OutputSet::new();
        set.write(&classify("n", &dir.join("new/x.txt"), true).unwrap(), |w| w.write_all(b"x"))
            .unwrap();
        set.write(&classify("f", Path::new("/dev/full"), false).unwrap(), |w| w.write_all(b"x"))
            .unwrap();
        let err = set.commit().unwrap_err().to_string();
        assert!(err.contains("/dev/full") && err.contains("No space left"), "{err}");
        assert!(entries(&dir).is_empty(), "{:?}", entries(&dir));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
