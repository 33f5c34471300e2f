//! Images decoded once while they are in use: a file that many textures name (40 materials
//! of one PNG, a Mitsuba `<texture>` that many BSDFs `<ref>`) was decoded, and held, once per
//! texture: 40 copies of a 2048² image took 2 GB before the memory estimate was made (which
//! then counted them 40 times). The decoded images are shared instead, by the file, its
//! bytes' SHA-256 (a file rewritten between two scenes of one process is read again) and
//! the way it was read.

use crate::scene::error::SceneError;
use crate::texels::TextureImage;
use sha2::{Digest, Sha256};
use std::collections::HashMap;
use std::path::Path;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, PoisonError, Weak};

/// How an image's file was read into texels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Reading {
    Colour { srgb: bool },
    Data { alpha: bool },
    Radiance { srgb: bool },
}

type Key = (PathBuf, [u8; 32], Reading);

/// The images decoded and still held somewhere, with the flag their reading gave (a data
/// image's: whether it is the file's alpha), and the bytes of their texels: counted as each
/// is added and recounted when images no longer held are swept, so between sweeps it may
/// count some of those (it never counts less than is held).
#[derive(Default)]
struct Decoded {
    images: HashMap<Key, (Weak<TextureImage>, bool)>,
    held_bytes: u64,
}

impl Decoded {
    fn sweep(&mut self) {
        self.images.retain(|_, (image, _)| image.strong_count() > 0);
        let held = self.images.values().filter_map(|(image, _)| image.upgrade());
        self.held_bytes = held.map(|image| texel_bytes(&image)).sum();
    }
}

fn texel_bytes(image: &TextureImage) -> u64 {
    std::mem::size_of_val(image.texels.as_slice()) as u64
}

static DECODED: Mutex<Option<Decoded>> = Mutex::new(None);

/// Refuses to decode an image whose decoding needs `decoding` bytes when that and the
/// images held already pass the memory the process may use (`limits::memory_available`),
/// before any texel is decoded: a scene of images is otherwise read in full before its
/// estimate is made. `Err` gives the bytes of the images held and the bytes available.
pub(crate) fn check_room(decoding: u64) -> Result<(), (u64, u64)> {
    let Some(available) = crate::limits::memory_available() else { return Ok(()) };
    let mut decoded = DECODED.lock().unwrap_or_else(PoisonError::into_inner);
    let decoded = decoded.get_or_insert_default();
    if decoded.held_bytes.saturating_add(decoding) > available {
        // The count may include images no longer held: counted exactly before refusing.
        decoded.sweep();
    }
    match decoded.held_bytes.saturating_add(decoding) > available {
        true => Err((decoded.held_bytes, available)),
        false => Ok(()),
    }
}

/// The image of `file`, which holds `bytes`, as `reading` reads it: the one decoded already
/// if it is still held, else `decode` of the bytes.
pub(crate) fn shared(
    file: &Path,
    bytes: &[u8],
    reading: Reading,
    decode: impl FnOnce(&[u8]) -> Result<(Arc<TextureImage>, bool), SceneError>,
) -> Result<(Arc<TextureImage>, bool), SceneError> {
    let key: Key = (file.to_path_buf(), Sha256::digest(bytes).into(), reading);
    let held = |decoded: &mut Option<Decoded>| {
        let (image, flag) = decoded.get_or_insert_default().images.get(&key)?;
        Some((image.upgrade()?, *flag))
    };
    if let Some(found) = held(&mut DECODED.lock().unwrap_or_else(PoisonError::into_inner)) {
        return Ok(found);
    }
    let (image, flag) = decode(bytes)?;
    let mut decoded = DECODED.lock().unwrap_or_else(PoisonError::into_inner);
    let decoded = decoded.get_or_insert_default();
    // Images no longer held are forgotten as others are added: when the map reaches a power
    // of two, so that the sweeps cost O(1) an image (a sweep at every image made a scene of
    // n distinct images cost n²).
    if decoded.images.len().is_power_of_two() {
        decoded.sweep();
    }
    decoded.held_bytes += texel_bytes(&image);
    decoded.images.insert(key, (Arc::downgrade(&image), flag));
    Ok((image, flag))
}
