//! The linear RGB of an OpenEXR file held in memory (R, G, B channels, or Y for grey
//! images), for every reader of EXRs that are not embray's own part files: radiance maps,
//! reference images, `compare` and `tonemap`. Callers check `size` against their own limit
//! before `read` allocates for the pixels.

use glam::Vec3;

/// Runs an OpenEXR read that may panic on hostile bytes: the `exr` crate multiplies sizes
/// from a header without overflow checks (found by fuzzing the reference reader, `tests/reader_fuzz.rs`), which panics
/// in a build with overflow checks. The panic becomes an error naming no file (the caller
/// adds it).
pub fn guarded<T>(read: impl FnOnce() -> Result<T, String>) -> Result<T, String> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(read)).unwrap_or_else(|_| {
        Err("the OpenEXR reader failed on it (sizes in its header out of range)".to_owned())
    })
}

/// An EXR's first layer's width and height, from its header alone (checked by the caller
/// against its limits before `read` allocates).
pub fn size(bytes: &[u8]) -> Result<(u64, u64), String> {
    let first = layer_sizes(bytes)?.first().copied();
    first.map(|(w, h, _)| (w, h)).ok_or_else(|| "an EXR file without layers".to_owned())
}

/// Bytes per pixel that reading an EXR with `channels` channels into a film holds at its
/// peak: every channel decoded as f32 and copied once, plus the film (colour, depth,
/// normal: 28 bytes).
pub fn read_bytes_per_pixel(channels: u64) -> u64 {
    8 * channels.max(3) + 28
}

/// Every layer's width, height and channel count, from the headers alone.
fn layer_sizes(bytes: &[u8]) -> Result<Vec<(u64, u64, u64)>, String> {
    if bytes.is_empty() {
        return Err("the file is empty".to_owned());
    }
    let meta = guarded(|| {
        exr::meta::MetaData::read_from_buffered(std::io::Cursor::new(bytes), false)
            .map_err(|e| format!("not a readable OpenEXR file ({e})"))
    })?;
    let size = |header: &exr::meta::header::Header| {
        let (w, h) = (header.layer_size.width() as u64, header.layer_size.height() as u64);
        (w, h, header.channels.list.len() as u64)
    };
    Ok(meta.headers.iter().map(size).collect())
}

/// The first layer's pixels, row-major from the top, as they are (not clamped, not checked
/// for finiteness); its width and height. Every channel is decoded: a small compressed file
/// of many channels can decode to gigabytes, so its decoded size is checked against the
/// memory there is before the decoder allocates.
pub fn read(bytes: &[u8]) -> Result<(u32, u32, Vec<Vec3>), String> {
    use exr::prelude::*;
    // The layer decoded is the first valid one, not always the first: the largest counts.
    let layers = layer_sizes(bytes)?;
    let bytes_of = |&(w, h, channels): &(u64, u64, u64)| {
        (w.saturating_mul(h)).saturating_mul(read_bytes_per_pixel(channels))
    };
    let Some(&(w, h, channels)) = layers.iter().max_by_key(|layer| bytes_of(layer)) else {
        return Err("an EXR file without layers".to_owned());
    };
    let needed = bytes_of(&(w, h, channels));
    if let Some(available) = crate::limits::memory_available()
        && needed > available
    {
        return Err(format!(
            "{w} × {h} pixels of {channels} channels need about {} MiB to read, but only {} MiB \
             are available",
            needed >> 20,
            available >> 20
        ));
    }
    let image = guarded(|| {
        exr::prelude::read()
            .no_deep_data()
            .largest_resolution_level()
            .all_channels()
            .first_valid_layer()
            .all_attributes()
            .from_buffered(std::io::Cursor::new(bytes))
            .map_err(|e| e.to_string())
    })?;
    let layer = image.layer_data;
    let (width, height) = (layer.size.width(), layer.size.height());
    let channel = |name: &str| {
        layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == name)
            .map(|c| c.sample_data.values_as_f32().collect::<Vec<f32>>())
    };
    let (r, g, b) = match (channel("R"), channel("G"), channel("B"), channel("Y")) {
        (Some(r), Some(g), Some(b), _) => (r, g, b),
        (_, _, _, Some(y)) => (y.clone(), y.clone(), y),
        _ => return Err("it has neither R, G, B channels nor a Y channel".to_owned()),
    };
    // The other channels (depth, normals, …) go before the texels are made.
    drop(layer);
    let pixels = width * height;
    if [r.len(), g.len(), b.len()].iter().any(|&n| n != pixels) {
        return Err("its channels hold fewer values than its size".to_owned());
    }
    let rgb = r.iter().zip(&g).zip(&b).map(|((r, g), b)| Vec3::new(*r, *g, *b)).collect();
    Ok((width as u32, height as u32, rgb))
}
