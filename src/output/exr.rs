//! The linear EXR: float RGB plus depth `Z` and world-space normals `N.X N.Y N.Z`.

use super::{OutputError, write_atomically};
use crate::film::Film;
use std::path::Path;

pub fn write_exr(film: &Film, path: &Path) -> Result<(), OutputError> {
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
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(channels),
    );
    let image = Image::from_layer(layer);
    write_atomically(path, |temp| image.write().to_file(temp).map_err(|e| e.to_string()))
}
