//! A side-by-side strip of the same crop rendered at each offset, one row per render space,
//! so the loss of precision far from the origin can be seen.

use crate::film::Film;
use crate::output::{ToneMap, to_srgb8};
use std::path::Path;

/// The central `size`×`size` crop of a film (the whole film if smaller), as 8-bit sRGB.
fn crop(film: &Film, size: u32) -> (u32, u32, Vec<u8>) {
    let w = size.min(film.width);
    let h = size.min(film.height);
    let (x0, y0) = ((film.width - w) / 2, (film.height - h) / 2);
    let rgb = to_srgb8(film, ToneMap::Aces, 0.0, &Default::default());
    let mut out = Vec::with_capacity((w * h * 3) as usize);
    for y in y0..y0 + h {
        let row = (y * film.width + x0) as usize * 3;
        out.extend_from_slice(&rgb[row..row + w as usize * 3]);
    }
    (w, h, out)
}

/// Writes `rows[r][c]` (one row per render space, one column per offset) as one PNG,
/// each crop enlarged `scale`× with nearest-neighbour filtering and separated by a gap.
pub fn write_strip(
    path: &Path,
    rows: &[Vec<Film>],
    crop_size: u32,
    scale: u32,
) -> Result<(), String> {
    let gap = 4;
    let cols = rows.iter().map(|r| r.len()).max().unwrap_or(0) as u32;
    if cols == 0 {
        return Err("no images for the strip".into());
    }
    let cell_w = crop_size.min(rows[0][0].width) * scale;
    let cell_h = crop_size.min(rows[0][0].height) * scale;
    let width = cols * (cell_w + gap) + gap;
    let height = rows.len() as u32 * (cell_h + gap) + gap;
    let mut image = image::RgbImage::from_pixel(width, height, image::Rgb([40, 40, 40]));
    for (r, row) in rows.iter().enumerate() {
        for (c, film) in row.iter().enumerate() {
            let (w, h, pixels) = crop(film, crop_size);
            let (ox, oy) = (gap + c as u32 * (cell_w + gap), gap + r as u32 * (cell_h + gap));
            for y in 0..h * scale {
                for x in 0..w * scale {
                    let i = (((y / scale) * w + x / scale) * 3) as usize;
                    image.put_pixel(
                        ox + x,
                        oy + y,
                        image::Rgb([pixels[i], pixels[i + 1], pixels[i + 2]]),
                    );
                }
            }
        }
    }
    image.save(path).map_err(|e| format!("{}: {e}", path.display()))
}
