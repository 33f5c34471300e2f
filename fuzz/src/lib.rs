//! What every fuzz target does: the bytes as the reader's file, in a folder of this
//! process's own, read and checked (`embray::fuzz::Reader::read_and_check`).

use std::path::PathBuf;
use std::sync::OnceLock;

pub fn read(reader: embray::fuzz::Reader, bytes: &[u8]) {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    let dir = DIR.get_or_init(|| {
        // libFuzzer's hook aborts on any panic, even one embray catches on purpose (the
        // `exr` crate's, guarded into an error); a panic that escapes the read still
        // aborts, in libfuzzer-sys's own `catch_unwind`.
        std::panic::set_hook(Box::new(|_| {}));
        let dir = std::env::temp_dir().join(format!("embray-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a temporary folder");
        dir
    });
    // A job folder holds only what the case wrote.
    let _ = std::fs::remove_file(dir.join(reader.file_name()));
    reader.read_and_check(bytes, dir);
}
