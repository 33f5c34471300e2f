//! Memory counted while a scene's files are read, before what they ask for is made: the
//! reading's own cost, and what a few bytes can ask for (copies, instances).

use crate::limits::{BASE_BYTES, BYTES_PER_OBJECT, memory_available};
use crate::scene::SceneError;
use std::path::Path;

/// Refuses to read `file` when `needed` bytes (estimated from `what`) exceed what the
/// process may use: checked before the memory is spent.
pub(crate) fn check_reading(
    file: &Path,
    needed: u64,
    what: impl FnOnce() -> String,
) -> Result<(), SceneError> {
    match memory_available() {
        Some(available) if needed > available => Err(SceneError::ReadMemory {
            file: file.to_path_buf(),
            needed,
            what: what(),
            available,
        }),
        _ => Ok(()),
    }
}

/// Refuses a scene whose object placements, counted before they are made, would need more
/// memory than the process may use: a 2 KB scene can ask for ten million copies (a `repeat`
/// grid, a Mitsuba shapegroup instanced), which the estimate of the finished scene would
/// refuse only after they were made. `at` says where the last of them were asked for.
pub(crate) fn check_placements(
    file: &Path,
    placements: u64,
    at: impl FnOnce() -> String,
) -> Result<(), SceneError> {
    let needed = BASE_BYTES.saturating_add(placements.saturating_mul(BYTES_PER_OBJECT));
    check_reading(file, needed, || {
        format!("{placements} object placements, the last asked for by {}", at())
    })
}
