//! The part file: an EXR whose channels hold a part's exact per-pixel sums (each 128-bit
//! fixed-point sum as four 32-bit words, `sum.R.0` lowest) and sample counts (`count`,
//! `count.Z`), with the part's metadata as JSON in the `embray.part` attribute. Any EXR
//! reader can open it; only `embray merge` makes an image of it.

use super::metadata::PartMeta;
use crate::output::WriteSeek;
use crate::sample_sums::{FilmSums, PixelSums};
use std::path::Path;

/// The header attribute holding the metadata.
const META_ATTRIBUTE: &str = "embray.part";
/// The summed quantities, in `PixelSums` order.
const QUANTITIES: [&str; 7] = ["R", "G", "B", "Z", "N.X", "N.Y", "N.Z"];
const WORDS: usize = 4;
/// Bytes a pixel takes in the file before compression (the size cap on reading it).
pub const BYTES_PER_PIXEL: u64 = ((QUANTITIES.len() * WORDS + 2) * 4) as u64;

#[derive(Debug, thiserror::Error)]
pub enum PartFileError {
    #[error("cannot read part file '{}': {message}", .path.display())]
    Read { path: std::path::PathBuf, message: String },
    #[error(
        "'{}' is not an embray part file (no '{META_ATTRIBUTE}' attribute): parts are made by \
         `embray render SCENE --part I/N`", .path.display()
    )]
    NotAPart { path: std::path::PathBuf },
    #[error("part file '{}' is damaged: {message}", .path.display())]
    Damaged { path: std::path::PathBuf, message: String },
}

fn quantity(sums: &PixelSums, q: usize) -> i128 {
    match q {
        0..=2 => sums.color[q],
        3 => sums.depth,
        _ => sums.normal[q - 4],
    }
}

fn set_quantity(sums: &mut PixelSums, q: usize, value: i128) {
    match q {
        0..=2 => sums.color[q] = value,
        3 => sums.depth = value,
        _ => sums.normal[q - 4] = value,
    }
}

/// Encodes a part into `sink`.
pub fn encode_part(
    meta: &PartMeta,
    sums: &FilmSums,
    sink: &mut dyn WriteSeek,
) -> std::io::Result<()> {
    use exr::prelude::*;
    let json = serde_json::to_string(meta).map_err(std::io::Error::other)?;
    let mut channels = Vec::new();
    for (q, name) in QUANTITIES.iter().enumerate() {
        for w in 0..WORDS {
            let words: Vec<u32> =
                sums.pixels.iter().map(|p| (quantity(p, q) as u128 >> (32 * w)) as u32).collect();
            channels
                .push(AnyChannel::new(format!("sum.{name}.{w}").as_str(), FlatSamples::U32(words)));
        }
    }
    let counts =
        |pick: fn(&PixelSums) -> u32| -> Vec<u32> { sums.pixels.iter().map(pick).collect() };
    channels.push(AnyChannel::new("count", FlatSamples::U32(counts(|p| p.samples))));
    channels.push(AnyChannel::new("count.Z", FlatSamples::U32(counts(|p| p.depth_samples))));
    let mut attributes = LayerAttributes::named("embray part");
    attributes.other.insert(
        Text::new_or_panic(META_ATTRIBUTE),
        AttributeValue::Text(Text::from_slice_unchecked(json.as_bytes())),
    );
    let layer = Layer::new(
        Vec2(sums.width as usize, sums.height as usize),
        attributes,
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(SmallVec::from_vec(channels)),
    );
    Image::from_layer(layer).write().to_buffered(sink).map_err(|e| match e {
        exr::error::Error::Io(io) => io,
        other => std::io::Error::other(other.to_string()),
    })
}

fn read_error(path: &Path, e: impl ToString) -> PartFileError {
    PartFileError::Read { path: path.to_path_buf(), message: e.to_string() }
}

/// The metadata of the part file `path`, read from its header alone.
pub fn read_part_meta(path: &Path) -> Result<PartMeta, PartFileError> {
    use exr::prelude::*;
    check_readable(path)?;
    let meta = MetaData::read_from_file(path, false).map_err(|e| read_error(path, e))?;
    let header = meta.headers.first().ok_or_else(|| read_error(path, "the file has no layer"))?;
    let value = header.own_attributes.other.get(&Text::new_or_panic(META_ATTRIBUTE));
    let Some(AttributeValue::Text(text)) = value else {
        return Err(PartFileError::NotAPart { path: path.to_path_buf() });
    };
    let damaged = |message: String| PartFileError::Damaged { path: path.to_path_buf(), message };
    let json = std::str::from_utf8(text.bytes()).map_err(|e| damaged(e.to_string()))?;
    let meta: PartMeta = serde_json::from_str(json)
        .map_err(|e| damaged(format!("its metadata does not parse ({e})")))?;
    let size = header.layer_size;
    if (size.0, size.1) != (meta.width as usize, meta.height as usize) {
        return Err(damaged(format!(
            "the image is {}x{} but its metadata says {}x{}",
            size.0, size.1, meta.width, meta.height
        )));
    }
    Ok(meta)
}

/// Refuses what is not a regular file before an EXR reader opens it (a FIFO would block).
fn check_readable(path: &Path) -> Result<(), PartFileError> {
    let kind = std::fs::metadata(path).map_err(|e| read_error(path, e))?.file_type();
    if !kind.is_file() {
        return Err(read_error(path, "not a regular file"));
    }
    Ok(())
}

/// The sums stored in the part file `path`, whose metadata `meta` has been read and checked
/// (its size bounds what is read: larger files are refused before decoding).
pub fn read_part_sums(path: &Path, meta: &PartMeta) -> Result<FilmSums, PartFileError> {
    use exr::prelude::*;
    let pixels = meta.width as u64 * meta.height as u64;
    let len = std::fs::metadata(path).map_err(|e| read_error(path, e))?.len();
    // Compression can grow incompressible data a little; headers are small.
    let cap = pixels * BYTES_PER_PIXEL * 2 + (1 << 20);
    let damaged = |message: String| PartFileError::Damaged { path: path.to_path_buf(), message };
    if len > cap {
        return Err(damaged(format!(
            "{len} bytes, more than a {}x{} part can take",
            meta.width, meta.height
        )));
    }
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .map_err(|e| read_error(path, e))?;
    let channels = &image.layer_data.channel_data.list;
    let channel = |name: &str| -> std::result::Result<&[u32], PartFileError> {
        let found = channels.iter().find(|c| c.name.to_string() == name);
        match found.map(|c| &c.sample_data) {
            Some(FlatSamples::U32(values)) if values.len() as u64 == pixels => Ok(values),
            Some(_) => Err(damaged(format!("channel '{name}' is not {pixels} 32-bit integers"))),
            None => Err(damaged(format!("channel '{name}' is missing"))),
        }
    };
    let mut sums = FilmSums::new(meta.width, meta.height);
    for (q, name) in QUANTITIES.iter().enumerate() {
        let words: Vec<&[u32]> = (0..WORDS)
            .map(|w| channel(&format!("sum.{name}.{w}")))
            .collect::<std::result::Result<_, _>>()?;
        for (i, p) in sums.pixels.iter_mut().enumerate() {
            let bits = (0..WORDS).fold(0u128, |acc, w| acc | (u128::from(words[w][i]) << (32 * w)));
            set_quantity(p, q, bits as i128);
        }
    }
    let (count, depth_count) = (channel("count")?, channel("count.Z")?);
    for (i, p) in sums.pixels.iter_mut().enumerate() {
        p.samples = count[i];
        p.depth_samples = depth_count[i];
    }
    Ok(sums)
}
