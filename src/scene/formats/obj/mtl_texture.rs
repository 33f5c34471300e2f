//! An MTL material's `map_Kd`: its diffuse colour from an image (PNG, JPEG or BMP), sRGB,
//! texel-centred bilinear, repeating. OBJ texture coordinates run up the image where embray's run down,
//! so the image is kept upside down (`TextureImage::rows_flipped`).

use crate::scene::error::{Line, SceneError};
use crate::scene::texture_image::{ImageRef, load, with_rows_flipped};
use crate::scene::{Interpolation, Pattern, TextureDesc, TextureMode};
use glam::DAffine3;
use std::path::Path;

/// The texture `m`'s `map_Kd` names (relative to the MTL file `mtl`, whose text is
/// `mtl_text`); options before the file name (`-s`, `-o`, `-bm`, …) are warned about and
/// left out.
pub(super) fn diffuse_texture(
    m: &tobj::Material,
    mtl: &Path,
    mtl_text: &str,
    warnings: &mut Vec<String>,
) -> Result<Option<TextureDesc>, SceneError> {
    let Some(value) = m.diffuse_texture.as_deref() else { return Ok(None) };
    let line = line_of(mtl_text, &m.name, "map_Kd");
    let tokens: Vec<&str> = value.split_whitespace().collect();
    let Some((file, options)) = tokens.split_last() else { return Ok(None) };
    if !options.is_empty() {
        warnings.push(format!(
            "{}{}: material '{}': map_Kd options '{}' are not supported; the image is used \
             as it is",
            mtl.display(),
            line.map_or(String::new(), |l| format!(" line {l}")),
            crate::excerpt::excerpt(&m.name),
            crate::excerpt::excerpt(&options.join(" ")),
        ));
    }
    let at = ImageRef {
        image: mtl.parent().unwrap_or(Path::new("")).join(file),
        scene: mtl,
        item: format!("map_Kd of material '{}'", crate::excerpt::excerpt(&m.name)),
        line: Line(line),
    };
    let image = load(&at, true)?;
    Ok(Some(TextureDesc {
        pattern: Pattern::Image {
            image: with_rows_flipped(&image),
            interpolation: Interpolation::BilinearCentered,
            normalizer: 1.0,
        },
        mode: TextureMode::Replace,
        texture_from_object: DAffine3::IDENTITY,
    }))
}

/// The line (from 1) of `statement` in material `name`'s block of an MTL text.
fn line_of(text: &str, name: &str, statement: &str) -> Option<usize> {
    let mut inside = false;
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("newmtl") => inside = words.collect::<Vec<_>>().join(" ") == name,
            Some(word) if inside && word == statement => return Some(i + 1),
            _ => {}
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::line_of;

    #[test]
    fn the_line_of_a_statement_is_found_in_its_material() {
        let text = "newmtl a\nKd 1 1 1\nmap_Kd a.png\n\nnewmtl b c\n  map_Kd b.png\n";
        assert_eq!(line_of(text, "a", "map_Kd"), Some(3));
        assert_eq!(line_of(text, "b c", "map_Kd"), Some(6));
        assert_eq!(line_of(text, "d", "map_Kd"), None);
    }
}
