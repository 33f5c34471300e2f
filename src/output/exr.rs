//! The linear EXR: float RGB plus depth `Z` and world-space normals `N.X N.Y N.Z`.

use super::Aovs;
use super::{OutputError, WriteSeek, write_one};
use crate::film::Film;
use std::path::Path;

/// Writes `film` as EXR to `path` on its own (see `OutputSet` for a run's several outputs).
pub fn write_exr(film: &Film, path: &Path) -> Result<(), OutputError> {
    write_one(path, |w| encode_exr(film, Aovs::default(), &[], w))
}

/// Encodes `film` as EXR with the AOVs `aovs` and `attributes` (what made it) into `sink`;
/// every write error is returned. The attributes go into one text attribute, `embray`, a
/// line `name: value` each: the `exr` crate writes separate attributes in hash order, which
/// would make the same image a different file each time. Characters outside Latin-1 (which
/// the format requires) become `?`.
pub fn encode_exr(
    film: &Film,
    aovs: Aovs,
    attributes: &[(String, String)],
    sink: &mut dyn WriteSeek,
) -> std::io::Result<()> {
    use exr::prelude::*;
    let size = Vec2(film.width as usize, film.height as usize);
    let channel = |name: &str, values: Vec<f32>| AnyChannel::new(name, FlatSamples::F32(values));
    let component = |pick: fn(&glam::Vec3) -> f32, data: &[glam::Vec3]| -> Vec<f32> {
        data.iter().map(pick).collect()
    };
    let mut channels = vec![
        channel("R", component(|c| c.x, &film.color)),
        channel("G", component(|c| c.y, &film.color)),
        channel("B", component(|c| c.z, &film.color)),
    ];
    // Layers of three: directions as X Y Z, colours as R G B.
    let mut three = |name: &str, [a, b, c]: [&str; 3], data: &[glam::Vec3]| {
        channels.push(channel(&format!("{name}.{a}"), component(|v| v.x, data)));
        channels.push(channel(&format!("{name}.{b}"), component(|v| v.y, data)));
        channels.push(channel(&format!("{name}.{c}"), component(|v| v.z, data)));
    };
    if aovs.normal {
        three("N", ["X", "Y", "Z"], &film.normal);
    }
    if aovs.albedo {
        three("albedo", ["R", "G", "B"], &film.albedo);
    }
    if aovs.variance {
        three("variance", ["R", "G", "B"], &film.variance);
    }
    if aovs.depth {
        // Finite: 0 where no sample hit anything (`A` tells those pixels apart).
        let depth = film.depth.iter().map(|d| if d.is_finite() { *d } else { 0.0 }).collect();
        channels.push(channel("Z", depth));
    }
    if aovs.alpha {
        channels.push(channel("A", film.alpha.clone()));
    }
    let channels = SmallVec::from_vec(channels);
    let mut layer_attributes = LayerAttributes::named("embray");
    if !attributes.is_empty() {
        let lines: String =
            attributes.iter().map(|(name, value)| format!("{name}: {value}\n")).collect();
        let latin1: String =
            lines.chars().map(|c| if (c as u32) < 256 { c } else { '?' }).collect();
        if let (Some(name), Some(value)) = (Text::new_or_none("embray"), Text::new_or_none(&latin1))
        {
            layer_attributes.other.insert(name, AttributeValue::Text(value));
        }
    }
    let layer = Layer::new(
        size,
        layer_attributes,
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
