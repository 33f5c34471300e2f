//! The image being rendered: HDR colour plus depth and normal AOVs, one value per pixel.

use glam::Vec3;

#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    pub width: u32,
    pub height: u32,
    /// Linear radiance, row-major from the top-left pixel.
    pub color: Vec<Vec3>,
    /// Mean distance from the camera to the first hit; +∞ where every sample missed.
    pub depth: Vec<f32>,
    /// Mean world-space shading normal at the first hit (zero where every sample missed).
    pub normal: Vec<Vec3>,
    /// Mean first-hit albedo (zero where every sample missed).
    pub albedo: Vec<Vec3>,
    /// The sample variance of each pixel's samples, per channel.
    pub variance: Vec<Vec3>,
    /// The fraction of samples that hit something.
    pub alpha: Vec<f32>,
}

impl Film {
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Film {
            width,
            height,
            color: vec![Vec3::ZERO; n],
            depth: vec![f32::INFINITY; n],
            normal: vec![Vec3::ZERO; n],
            albedo: vec![Vec3::ZERO; n],
            variance: vec![Vec3::ZERO; n],
            alpha: vec![0.0; n],
        }
    }

    pub fn index(&self, x: u32, y: u32) -> usize {
        y as usize * self.width as usize + x as usize
    }

    pub fn pixel(&self, x: u32, y: u32) -> Vec3 {
        self.color[self.index(x, y)]
    }

    /// The pixels with a NaN or infinite channel: how many, and the first (x, y) in row
    /// order; `None` when every pixel is finite.
    pub fn non_finite(&self) -> Option<NonFinite> {
        let mut bad = self.color.iter().enumerate().filter(|(_, c)| !c.is_finite());
        let (first, _) = bad.next()?;
        let width = self.width.max(1) as usize;
        let first = ((first % width) as u32, (first / width) as u32);
        Some(NonFinite { count: 1 + bad.count(), first })
    }
}

/// A film's pixels with a NaN or infinite channel (`Film::non_finite`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NonFinite {
    pub count: usize,
    /// The first, (x, y), in row order.
    pub first: (u32, u32),
}

impl std::fmt::Display for NonFinite {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (x, y) = self.first;
        write!(
            f,
            "{} pixel(s) with a NaN or infinite value (the first at x {x}, y {y})",
            self.count
        )
    }
}

/// A rectangle of pixels rendered by one task.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tile {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl Tile {
    /// Its pixels (`x`, `y`), row by row from the top-left one: the order of a tile's sums.
    pub fn pixels(&self) -> impl Iterator<Item = (u32, u32)> + use<> {
        let (x0, x1) = (self.x0, self.x1);
        (self.y0..self.y1).flat_map(move |y| (x0..x1).map(move |x| (x, y)))
    }

    /// Whether the two share a pixel.
    pub fn meets(&self, other: &Tile) -> bool {
        self.x0 < other.x1 && other.x0 < self.x1 && self.y0 < other.y1 && other.y0 < self.y1
    }
}

impl Film {
    /// The pixels of `window` (inside the film) as a film of their own.
    pub fn cropped(&self, window: Tile) -> Film {
        let mut out = Film::new(window.x1 - window.x0, window.y1 - window.y0);
        for y in window.y0..window.y1 {
            for x in window.x0..window.x1 {
                let (from, to) = (self.index(x, y), out.index(x - window.x0, y - window.y0));
                out.color[to] = self.color[from];
                out.depth[to] = self.depth[from];
                out.normal[to] = self.normal[from];
                out.albedo[to] = self.albedo[from];
                out.variance[to] = self.variance[from];
                out.alpha[to] = self.alpha[from];
            }
        }
        out
    }
}

/// Square tiles of side `size` covering the image, in row-major order.
pub fn tiles(width: u32, height: u32, size: u32) -> Vec<Tile> {
    let mut out = Vec::new();
    for y0 in (0..height).step_by(size as usize) {
        for x0 in (0..width).step_by(size as usize) {
            out.push(Tile { x0, y0, x1: (x0 + size).min(width), y1: (y0 + size).min(height) });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_cover_every_pixel_once() {
        let mut seen = vec![0u8; 37 * 19];
        for t in tiles(37, 19, 16) {
            for y in t.y0..t.y1 {
                for x in t.x0..t.x1 {
                    seen[(y * 37 + x) as usize] += 1;
                }
            }
        }
        assert!(seen.iter().all(|&n| n == 1));
    }

    #[test]
    fn a_tiles_pixels_go_row_by_row() {
        let tile = Tile { x0: 3, y0: 5, x1: 5, y1: 8 };
        let pixels: Vec<(u32, u32)> = tile.pixels().collect();
        assert_eq!(pixels, [(3, 5), (4, 5), (3, 6), (4, 6), (3, 7), (4, 7)]);
        assert_eq!(Tile { x0: 2, y0: 2, x1: 2, y1: 9 }.pixels().count(), 0);
    }
}
