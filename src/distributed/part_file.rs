//! The part file: an EXR whose channels hold a part's exact per-pixel sums (each 128-bit
//! fixed-point sum as four 32-bit words, `sum.R.0` lowest) and sample counts (`count`,
//! `count.Z`), with the part's metadata as JSON in the `embray.part` attribute. Any EXR
//! reader can open it; only `embray merge` makes an image of it.

use super::metadata::PartMeta;
use super::part::Split;
use crate::output::WriteSeek;
use crate::sample_sums::{FilmSums, PixelSums};
use std::path::Path;

/// The header attribute holding the metadata.
const META_ATTRIBUTE: &str = "embray.part";
/// The summed quantities, in `PixelSums` order.
const QUANTITIES: [&str; 13] = [
    "R", "G", "B", "Z", "N.X", "N.Y", "N.Z", "albedo.R", "albedo.G", "albedo.B", "square.R",
    "square.G", "square.B",
];
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

/// Where the file's pixels come from: the file's width and height, and for each of its pixels
/// (row-major) the image pixel it holds, `None` for padding. A sample-range part holds the
/// whole image as it is. A tile part holds only its own tiles, each padded to a full tile and
/// stacked top to bottom in tile order, so a part file's size follows the part's share of
/// the image, not the image (a 1000-part render does not read 1000 images to merge).
pub fn file_layout(meta: &PartMeta) -> ((u32, u32), Vec<Option<usize>>) {
    let (width, height) = (meta.width, meta.height);
    if meta.part.split == Split::Samples {
        let n = width as usize * height as usize;
        return ((width, height), (0..n).map(Some).collect());
    }
    let size = meta.tile_size;
    let tiles = meta.part.tiles(&crate::film::tiles(width, height, size));
    let mut map = Vec::with_capacity(tiles.len() * (size * size) as usize);
    for tile in &tiles {
        for y in tile.y0..tile.y0 + size {
            for x in tile.x0..tile.x0 + size {
                let inside = x < tile.x1 && y < tile.y1;
                map.push(inside.then(|| y as usize * width as usize + x as usize));
            }
        }
    }
    ((size, size * tiles.len() as u32), map)
}

fn quantity(sums: &PixelSums, q: usize) -> i128 {
    match q {
        0..=2 => sums.color[q],
        3 => sums.depth,
        4..=6 => sums.normal[q - 4],
        7..=9 => sums.albedo[q - 7],
        _ => sums.square[q - 10],
    }
}

fn set_quantity(sums: &mut PixelSums, q: usize, value: i128) {
    match q {
        0..=2 => sums.color[q] = value,
        3 => sums.depth = value,
        4..=6 => sums.normal[q - 4] = value,
        7..=9 => sums.albedo[q - 7] = value,
        _ => sums.square[q - 10] = value,
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
    let ((file_width, file_height), layout) = file_layout(meta);
    let zero = PixelSums::default();
    let pixels: Vec<&PixelSums> =
        layout.iter().map(|i| i.map_or(&zero, |i| &sums.pixels[i])).collect();
    let mut channels = Vec::new();
    for (q, name) in QUANTITIES.iter().enumerate() {
        for w in 0..WORDS {
            let words: Vec<u32> =
                pixels.iter().map(|p| (quantity(p, q) as u128 >> (32 * w)) as u32).collect();
            channels
                .push(AnyChannel::new(format!("sum.{name}.{w}").as_str(), FlatSamples::U32(words)));
        }
    }
    let counts =
        |pick: fn(&PixelSums) -> u32| -> Vec<u32> { pixels.iter().map(|p| pick(p)).collect() };
    channels.push(AnyChannel::new("count", FlatSamples::U32(counts(|p| p.samples))));
    channels.push(AnyChannel::new("count.Z", FlatSamples::U32(counts(|p| p.depth_samples))));
    let mut attributes = LayerAttributes::named("embray part");
    attributes.other.insert(
        Text::new_or_panic(META_ATTRIBUTE),
        AttributeValue::Text(Text::from_slice_unchecked(json.as_bytes())),
    );
    let layer = Layer::new(
        Vec2(file_width as usize, file_height as usize),
        attributes,
        // RLE: the zero words (pixels of other parts, high words of small sums) shrink, and
        // unlike ZIP it costs next to nothing (ZIP took a third of a small part's time).
        Encoding { line_order: LineOrder::Increasing, ..Encoding::FAST_LOSSLESS },
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
    let meta = crate::exr_rgb::guarded(|| {
        MetaData::read_from_file(path, false).map_err(|e| e.to_string())
    })
    .map_err(|e| read_error(path, e))?;
    let header = meta.headers.first().ok_or_else(|| read_error(path, "the file has no layer"))?;
    let value = header.own_attributes.other.get(&Text::new_or_panic(META_ATTRIBUTE));
    let Some(AttributeValue::Text(text)) = value else {
        return Err(PartFileError::NotAPart { path: path.to_path_buf() });
    };
    let damaged = |message: String| PartFileError::Damaged { path: path.to_path_buf(), message };
    let json = std::str::from_utf8(text.bytes()).map_err(|e| damaged(e.to_string()))?;
    let meta: PartMeta = serde_json::from_str(json)
        .map_err(|e| damaged(format!("its metadata does not parse ({e})")))?;
    super::part_check::check_meta(&meta).map_err(damaged)?;
    let size = header.layer_size;
    let ((width, height), _) = file_layout(&meta);
    if (size.0, size.1) != (width as usize, height as usize) {
        return Err(damaged(format!(
            "its pixels are {}x{}, but part {} of a {}x{} image takes {width}x{height}",
            size.0, size.1, meta.part, meta.width, meta.height
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
/// (its size bounds what is read: larger files are refused before decoding): each of the
/// part's pixels as (index in the image, sums). Only the part's pixels are held, so merging
/// many small parts costs what they hold, not an image each.
pub fn read_part_sums(
    path: &Path,
    meta: &PartMeta,
) -> Result<Vec<(usize, PixelSums)>, PartFileError> {
    use exr::prelude::*;
    let ((file_width, file_height), layout) = file_layout(meta);
    let pixels = file_width as u64 * file_height as u64;
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
    let image = crate::exr_rgb::guarded(|| {
        read()
            .no_deep_data()
            .largest_resolution_level()
            .all_channels()
            .first_valid_layer()
            .all_attributes()
            .from_file(path)
            .map_err(|e| e.to_string())
    })
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
    // The part's own pixels (image index, sums), in file order; padding must be empty.
    let mut pixels_read: Vec<(usize, usize, PixelSums)> = Vec::new();
    for (file_index, target) in layout.iter().enumerate() {
        if let Some(image_index) = target {
            pixels_read.push((file_index, *image_index, PixelSums::default()));
        }
    }
    let padding = layout.iter().enumerate().filter(|(_, t)| t.is_none()).map(|(i, _)| i);
    for (q, name) in QUANTITIES.iter().enumerate() {
        let words: Vec<&[u32]> = (0..WORDS)
            .map(|w| channel(&format!("sum.{name}.{w}")))
            .collect::<std::result::Result<_, _>>()?;
        let bits =
            |i: usize| (0..WORDS).fold(0u128, |acc, w| acc | (u128::from(words[w][i]) << (32 * w)));
        for (file_index, _, sums) in &mut pixels_read {
            set_quantity(sums, q, bits(*file_index) as i128);
        }
        if padding.clone().any(|i| bits(i) != 0) {
            return Err(damaged("a padding pixel holds a sum".into()));
        }
    }
    let (count, depth_count) = (channel("count")?, channel("count.Z")?);
    for (file_index, _, sums) in &mut pixels_read {
        sums.samples = count[*file_index];
        sums.depth_samples = depth_count[*file_index];
    }
    if padding.clone().any(|i| count[i] != 0 || depth_count[i] != 0) {
        return Err(damaged("a padding pixel holds samples".into()));
    }
    Ok(pixels_read.into_iter().map(|(_, image_index, sums)| (image_index, sums)).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distributed::Part;
    use glam::Vec3;

    fn meta(width: u32, height: u32, part: Part) -> PartMeta {
        PartMeta {
            format: super::super::PART_FORMAT.into(),
            embray_version: "test".into(),
            embree: None,
            scene: "test".into(),
            scene_hash: "0".into(),
            options: "test".into(),
            camera: "test".into(),
            width,
            height,
            spp: 4,
            tile_size: 16,
            part,
            aovs: "depth,normal".into(),
            png: super::super::PngSettings {
                curve: "aces".into(),
                exposure: 0.0,
                photographic: [0.18, 1.0, 1.0, 2.2],
            },
            stats: Default::default(),
            timing: Default::default(),
        }
    }

    fn write(meta: &PartMeta, sums: &FilmSums, name: &str) -> std::path::PathBuf {
        let path =
            std::env::temp_dir().join(format!("embray-part-{name}-{}.exr", std::process::id()));
        let mut file = std::fs::File::create(&path).unwrap();
        encode_part(meta, sums, &mut file).unwrap();
        path
    }

    #[test]
    fn a_tile_part_stores_only_its_tiles_and_reads_back_exactly() {
        // 40×24: 3×2 tiles, the right and bottom ones cut; part 1 of 2 owns tiles 1 (16×16),
        // 3 (16×8) and 5 (8×8).
        let part = Part { index: 1, count: 2, split: Split::Tiles };
        let meta = meta(40, 24, part);
        let mut sums = FilmSums::new(40, 24);
        for t in part.tiles(&crate::film::tiles(40, 24, 16)) {
            for y in t.y0..t.y1 {
                for x in t.x0..t.x1 {
                    let i = sums.index(x, y);
                    let v = Vec3::new(x as f32, -(y as f32), 1e-3 * i as f32);
                    sums.pixels[i].add_sample(v, Some(1e9), Some(Vec3::Y), Some(v));
                }
            }
        }
        let ((w, h), layout) = file_layout(&meta);
        assert_eq!((w, h), (16, 48), "three padded tiles, stacked");
        assert_eq!(layout.iter().flatten().count(), 16 * 16 + 16 * 8 + 8 * 8);
        let path = write(&meta, &sums, "tiles");
        let read_meta = read_part_meta(&path).unwrap();
        assert_eq!(read_meta, meta);
        let mut read_back = FilmSums::new(40, 24);
        for (i, p) in read_part_sums(&path, &read_meta).unwrap() {
            read_back.pixels[i] = p;
        }
        assert_eq!(read_back, sums);
        std::fs::remove_file(&path).unwrap();
    }

    #[test]
    fn a_part_whose_pixels_do_not_match_its_metadata_is_not_merged() {
        let meta_of = |index| meta(16, 16, Part { index, count: 2, split: Split::Samples });
        let mut paths = Vec::new();
        for index in 0..2 {
            // Each part renders 2 of the 4 samples; part 1's file holds 3 at every pixel.
            let mut sums = FilmSums::new(16, 16);
            for p in &mut sums.pixels {
                for _ in 0..2 + index {
                    p.add_sample(Vec3::ONE, None, None, None);
                }
            }
            paths.push(write(&meta_of(index), &sums, &format!("coverage{index}")));
        }
        let message = match super::super::merge_parts(&paths) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("merged a damaged part"),
        };
        assert!(
            message.contains("pixel (0, 0) has 3 samples, but part 1/2 renders 2"),
            "{message}"
        );
        for path in paths {
            std::fs::remove_file(path).unwrap();
        }
    }

    #[test]
    fn metadata_out_of_range_is_refused_before_reading_pixels() {
        let part = Part { index: 0, count: 1, split: Split::Samples };
        let sums = FilmSums::new(8, 8);
        for (name, bad) in [
            ("huge", PartMeta { width: 1 << 30, height: 1 << 30, ..meta(8, 8, part) }),
            // Under the sample limit (4e10 at 1 spp) but no render's size: it would have
            // sized a 4e10-pixel table.
            ("wide", PartMeta { width: 200_000, height: 200_000, spp: 1, ..meta(8, 8, part) }),
            ("spp", PartMeta { spp: 0, ..meta(8, 8, part) }),
            ("index", PartMeta { part: Part { index: 3, count: 2, ..part }, ..meta(8, 8, part) }),
            ("size", meta(9, 8, part)),
        ] {
            let path = write(&meta(8, 8, part), &sums, name);
            // Rewrite the header's JSON with the bad metadata, pixels unchanged.
            let bytes = std::fs::read(&path).unwrap();
            let good = serde_json::to_string(&meta(8, 8, part)).unwrap();
            let evil = serde_json::to_string(&bad).unwrap();
            let text = String::from_utf8_lossy(&bytes).into_owned();
            assert!(text.contains(&good));
            let mut out = Vec::new();
            let at = bytes.windows(good.len()).position(|w| w == good.as_bytes()).unwrap();
            out.extend_from_slice(&bytes[..at - 4]);
            out.extend_from_slice(&(evil.len() as u32).to_le_bytes());
            out.extend_from_slice(evil.as_bytes());
            out.extend_from_slice(&bytes[at + good.len()..]);
            std::fs::write(&path, out).unwrap();
            let message = match read_part_meta(&path) {
                Err(e) => e.to_string(),
                Ok(m) => read_part_sums(&path, &m)
                    .map(|_| String::new())
                    .unwrap_or_else(|e| e.to_string()),
            };
            assert!(
                message.contains("damaged") || message.contains("cannot read"),
                "{name}: {message}"
            );
            std::fs::remove_file(&path).unwrap();
        }
    }
}
