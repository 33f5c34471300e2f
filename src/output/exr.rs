//! The linear EXR: float RGB plus depth `Z` and world-space normals `N.X N.Y N.Z`.

use super::{OutputError, WriteSeek, write_one};
use crate::film::Film;
use std::path::Path;

/// Writes `film` as EXR to `path` on its own (see `OutputSet` for a run's several outputs).
pub fn write_exr(film: &Film, path: &Path) -> Result<(), OutputError> {
    write_one(path, |w| encode_exr(film, w))
}

/// Encodes `film` as EXR into `sink`; every write error is returned.
pub fn encode_exr(film: &Film, sink: &mut dyn WriteSeek) -> std::io::Result<()> {
    use exr::prelude::*;
    let size = Vec2(film.width as usize, film.height as usize);
    let channel = |name: &str, values: Vec<f32>| AnyChannel::new(name, FlatSamples::F32(values));
    let component = |pick: fn(&glam::Vec3) -> f32, data: &[glam::Vec3]| -> Vec<f32> {
        data.iter().map(pick).collect()
    };
    let channels = SmallVec::from_vec(vec![
        channel("R", component(|c| c.x, &film.color)),
        channel("G", component(|c| c.y, &film.color)),
        channel("B", component(|c| c.z, &film.color)),
        channel("Z", film.depth.clone()),
        channel("N.X", component(|c| c.x, &film.normal)),
        channel("N.Y", component(|c| c.y, &film.normal)),
        channel("N.Z", component(|c| c.z, &film.normal)),
    ]);
    let layer = Layer::new(
        size,
        LayerAttributes::named("embray"),
        // Chunks in increasing order: with the default (unspecified) order they are written
        // as the compressor threads finish, and the same image gives different files.
        Encoding { line_order: LineOrder::Increasing, ..Encoding::FAST_LOSSLESS },
        AnyChannels::sort(channels),
    );
    let image = Image::from_layer(layer);
    image.write().to_buffered(sink).map_err(|e| match e {
        exr::error::Error::Io(io) => io,
        other => std::io::Error::other(other.to_string()),
    })
}
