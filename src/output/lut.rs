//! A 3-D colour lookup table (`.cube`, the Adobe/Resolve format) applied to the display image
//! as the last grading step: the 8-bit tone-mapped pixels, read as [0, 1], are looked up with
//! trilinear interpolation in the table's `DOMAIN_MIN..DOMAIN_MAX` cube.
//!
//! The format: `#` comments, `TITLE "…"`, `LUT_3D_SIZE N` (2–256), optional `DOMAIN_MIN r g
//! b` and `DOMAIN_MAX r g b`, then N³ lines of three numbers, red changing fastest.

use std::path::{Path, PathBuf};

/// Largest `LUT_3D_SIZE` accepted (256³ entries, 200 MB of text).
const MAX_SIZE: usize = 256;
/// Largest `.cube` file read.
const MAX_BYTES: u64 = 256 << 20;

#[derive(Debug, thiserror::Error)]
#[error("{}{}: {message}", .path.display(), .line.map(|l| format!(", line {l}")).unwrap_or_default())]
pub struct LutError {
    pub path: PathBuf,
    pub line: Option<usize>,
    pub message: String,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Lut3d {
    size: usize,
    domain_min: [f32; 3],
    domain_max: [f32; 3],
    /// `size³` outputs, red fastest, then green, then blue.
    table: Vec<[f32; 3]>,
}

fn three(fields: &[&str], what: &str) -> Result<[f32; 3], String> {
    if fields.len() != 3 {
        return Err(format!("{what} needs three numbers, found {}", fields.len()));
    }
    let mut v = [0.0; 3];
    for (slot, f) in v.iter_mut().zip(fields) {
        let x: f32 = f
            .parse()
            .map_err(|_| format!("{what}: '{}' is not a number", crate::excerpt::excerpt(f)))?;
        if !x.is_finite() {
            return Err(format!("{what}: '{}' is not finite", crate::excerpt::excerpt(f)));
        }
        *slot = x;
    }
    Ok(v)
}

impl Lut3d {
    /// Reads and parses the `.cube` file `path`.
    pub fn read(path: &Path) -> Result<Lut3d, LutError> {
        // The text and the table, of 12 bytes an entry of at least 6 ("0 0 0\n").
        let length = std::fs::metadata(path).map_or(0, |m| m.len());
        let needed = length.saturating_mul(3);
        if let Some(available) = crate::limits::memory_available().filter(|&a| needed > a) {
            let size = crate::scene::budget::size;
            let message = format!(
                "reading it needs about {} of memory (a file of {length} bytes), but only {} \
                 are available",
                size(needed),
                size(available)
            );
            return Err(LutError { path: path.to_path_buf(), line: None, message });
        }
        let bytes = crate::input_file::read_capped(path, MAX_BYTES).map_err(|e| LutError {
            path: path.to_path_buf(),
            line: None,
            message: e.to_string(),
        })?;
        let text = String::from_utf8_lossy(&bytes);
        Self::parse(&text).map_err(|(line, message)| LutError {
            path: path.to_path_buf(),
            line,
            message,
        })
    }

    /// Parses `.cube` text; an error carries its line number (from 1) where there is one.
    pub fn parse(text: &str) -> Result<Lut3d, (Option<usize>, String)> {
        let mut size = None;
        let (mut domain_min, mut domain_max) = ([0.0f32; 3], [1.0f32; 3]);
        let mut table: Vec<[f32; 3]> = Vec::new();
        // Editors on Windows start UTF-8 text with a byte order mark; it is no keyword.
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        for (n, raw) in text.lines().enumerate() {
            let line = n + 1;
            let at = |message: String| (Some(line), message);
            let content = raw.split('#').next().unwrap_or("").trim();
            if content.is_empty() {
                continue;
            }
            let fields: Vec<&str> = content.split_whitespace().collect();
            match fields[0] {
                "TITLE" => continue,
                "LUT_1D_SIZE" => {
                    return Err(at("a 1-D LUT; --lut takes 3-D LUTs (LUT_3D_SIZE)".into()));
                }
                "LUT_3D_SIZE" => {
                    if size.is_some() || !table.is_empty() {
                        return Err(at("LUT_3D_SIZE must come once, before the table".into()));
                    }
                    let n: usize = fields
                        .get(1)
                        .and_then(|f| f.parse().ok())
                        .ok_or_else(|| at("LUT_3D_SIZE needs a whole number".into()))?;
                    if !(2..=MAX_SIZE).contains(&n) || fields.len() != 2 {
                        return Err(at(format!("LUT_3D_SIZE is {n}, but must be 2 to {MAX_SIZE}")));
                    }
                    size = Some(n);
                    // The size claims n³ entries; the text can hold one per 6 bytes ("0 0 0\n")
                    // at most, so a short file cannot make it reserve 200 MB.
                    table.reserve((n * n * n).min(text.len() / 6));
                }
                "DOMAIN_MIN" => domain_min = three(&fields[1..], "DOMAIN_MIN").map_err(at)?,
                "DOMAIN_MAX" => domain_max = three(&fields[1..], "DOMAIN_MAX").map_err(at)?,
                keyword if keyword.starts_with(|c: char| c.is_ascii_alphabetic()) => {
                    return Err(at(format!(
                        "unknown keyword '{}'",
                        crate::excerpt::excerpt(keyword)
                    )));
                }
                _ => {
                    let Some(n) = size else {
                        return Err(at("table values before LUT_3D_SIZE".into()));
                    };
                    if table.len() == n * n * n {
                        return Err(at(format!(
                            "more than the {} entries a size-{n} table has",
                            n * n * n
                        )));
                    }
                    table.push(three(&fields, "a table entry").map_err(at)?);
                }
            }
        }
        let Some(size) = size else {
            return Err((None, "no LUT_3D_SIZE line: not a 3-D .cube LUT".into()));
        };
        if (0..3).any(|c| !(domain_max[c] > domain_min[c])) {
            return Err((None, "DOMAIN_MAX must exceed DOMAIN_MIN in every channel".into()));
        }
        if table.len() != size * size * size {
            let expected = size * size * size;
            return Err((
                None,
                format!("{} table entries, but LUT_3D_SIZE {size} needs {expected}", table.len()),
            ));
        }
        Ok(Lut3d { size, domain_min, domain_max, table })
    }

    /// The graded colour of `rgb` (display values, normally in [0, 1]), trilinearly
    /// interpolated; inputs outside the domain are clamped to it.
    pub fn apply(&self, rgb: [f32; 3]) -> [f32; 3] {
        let last = (self.size - 1) as f32;
        let mut base = [0usize; 3];
        let mut frac = [0.0f32; 3];
        for c in 0..3 {
            let t = (rgb[c] - self.domain_min[c]) / (self.domain_max[c] - self.domain_min[c]);
            let x = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) * last };
            let i = (x as usize).min(self.size - 2);
            base[c] = i;
            frac[c] = x - i as f32;
        }
        let at = |r: usize, g: usize, b: usize| self.table[(b * self.size + g) * self.size + r];
        let mut out = [0.0f32; 3];
        for corner in 0..8 {
            let (dr, dg, db) = (corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
            let weight = [dr, dg, db]
                .iter()
                .zip(frac)
                .map(|(&d, f)| if d == 1 { f } else { 1.0 - f })
                .product::<f32>();
            let value = at(base[0] + dr, base[1] + dg, base[2] + db);
            for c in 0..3 {
                out[c] += weight * value[c];
            }
        }
        out
    }

    /// Grades 8-bit RGB pixels in place.
    pub fn apply_rgb8(&self, pixels: &mut [u8]) {
        for px in pixels.chunks_exact_mut(3) {
            let rgb = [px[0], px[1], px[2]].map(|v| v as f32 / 255.0);
            let graded = self.apply(rgb);
            for (out, v) in px.iter_mut().zip(graded) {
                // NaN becomes 0 (`as` saturates).
                *out = (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A size-`n` `.cube` whose entries are `f` of the grid point.
    fn cube(n: usize, f: impl Fn([f32; 3]) -> [f32; 3]) -> String {
        let mut text = format!("# test\nTITLE \"t\"\nLUT_3D_SIZE {n}\n");
        let step = |i: usize| i as f32 / (n - 1) as f32;
        for b in 0..n {
            for g in 0..n {
                for r in 0..n {
                    let v = f([step(r), step(g), step(b)]);
                    text += &format!("{} {} {}\n", v[0], v[1], v[2]);
                }
            }
        }
        text
    }

    #[test]
    fn identity_table_leaves_every_8_bit_value_alone() {
        let lut = Lut3d::parse(&cube(17, |c| c)).unwrap();
        let mut pixels: Vec<u8> = (0..=255u8).flat_map(|v| [v, 255 - v, v / 3]).collect();
        let before = pixels.clone();
        lut.apply_rgb8(&mut pixels);
        assert_eq!(pixels, before);
    }

    #[test]
    fn a_channel_swap_table_swaps_channels_and_interpolates_linear_maps_exactly() {
        let swap = Lut3d::parse(&cube(2, |[r, g, b]| [b, g, r])).unwrap();
        let out = swap.apply([0.2, 0.5, 0.9]);
        for (o, e) in out.iter().zip([0.9, 0.5, 0.2]) {
            assert!((o - e).abs() < 1e-6, "{out:?}");
        }
        // Between grid points of a nonlinear table, trilinear interpolation is a blend.
        let square = Lut3d::parse(&cube(3, |c| c.map(|v| v * v))).unwrap();
        let mid = square.apply([0.25, 0.25, 0.25])[0];
        assert!((mid - 0.125).abs() < 1e-6, "halfway between 0 and 0.25: {mid}");
    }

    #[test]
    fn bad_cube_files_name_the_line_and_the_field() {
        let cases = [
            ("LUT_3D_SIZE 1\n", Some(1), "must be 2 to 256"),
            ("LUT_3D_SIZE 2\n0 0 0\n1 x 1\n", Some(3), "'x' is not a number"),
            ("LUT_3D_SIZE 2\n0 0\n", Some(2), "needs three numbers"),
            ("0 0 0\n", Some(1), "before LUT_3D_SIZE"),
            ("LUT_1D_SIZE 16\n", Some(1), "1-D LUT"),
            ("LUT_3D_SIZE 2\nGAMMA 2\n", Some(2), "unknown keyword 'GAMMA'"),
            ("LUT_3D_SIZE 2\n0 0 0\n", None, "1 table entries, but LUT_3D_SIZE 2 needs 8"),
            ("TITLE \"x\"\n", None, "no LUT_3D_SIZE"),
            ("LUT_3D_SIZE 2\nDOMAIN_MIN 0 0 0\nDOMAIN_MAX 1 0 1\n", None, "DOMAIN_MAX must exceed"),
            ("LUT_3D_SIZE 2\n0 0 inf\n", Some(2), "not finite"),
        ];
        for (text, line, message) in cases {
            let (got_line, got) = Lut3d::parse(text).unwrap_err();
            assert_eq!(got_line, line, "{text:?}: {got}");
            assert!(got.contains(message), "{text:?}: {got}");
        }
        let extra = cube(2, |c| c) + "0 0 0\n";
        let (line, message) = Lut3d::parse(&extra).unwrap_err();
        assert_eq!(line, Some(12));
        assert!(message.contains("more than the 8 entries"), "{message}");
    }
}
