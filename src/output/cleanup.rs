//! Temporary files still being written, removed if the process is interrupted: a SIGINT,
//! SIGTERM or SIGHUP during a write must not leave `.embray-*.tmp` files behind. (SIGKILL
//! cannot be caught; its leftovers are recognisable by the name.)

use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The registry, locked. Committing holds the lock across its renames, so an interrupt's
/// cleanup never removes a file half-way through a commit.
pub(crate) fn pending() -> MutexGuard<'static, Vec<PathBuf>> {
    PENDING.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Records `path` before it is created.
pub(crate) fn register(path: &Path) {
    pending().push(path.to_path_buf());
}

/// Forgets `path` (renamed into place or removed).
pub(crate) fn unregister(list: &mut Vec<PathBuf>, path: &Path) {
    list.retain(|p| p != path);
}

/// Starts the thread that, on SIGINT, SIGTERM or SIGHUP, removes every pending temporary
/// file and exits with 128 + the signal number (as a shell reports a signal death). While a
/// progressive render is watching (`render_stop::Stop::watch`), the first signal only asks
/// it to stop after its current pass and write what it has.
pub fn remove_temp_files_on_signals() -> std::io::Result<()> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])?;
    std::thread::Builder::new().name("signal cleanup".into()).spawn(move || {
        for signal in signals.forever() {
            if crate::render_stop::take_signal(signal) {
                let _ = std::io::Write::write_all(
                    &mut std::io::stderr(),
                    b"\nstopping: no new tile is started, then the image is written \
                      (again to quit at once)\n",
                );
                continue;
            }
            let list = pending();
            for path in list.iter() {
                let _ = std::fs::remove_file(path);
            }
            std::process::exit(128 + signal);
        }
    })?;
    Ok(())
}
