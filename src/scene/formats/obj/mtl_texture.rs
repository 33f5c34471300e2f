//! MTL texture statements (`map_Kd`, `map_d`, `bump`, `norm`, `map_Ke`): their options and
//! their images (PNG, JPEG or BMP), texel-centred bilinear, repeating. OBJ texture
//! coordinates run up the image where embray's run down, so every image is kept upside down
//! (`TextureImage::rows_flipped`).

use crate::scene::error::{Line, SceneError};
use crate::scene::texture_image::{
    DataImage, ImageRef, RAW_FULL_SCALE, load, load_data, with_rows_flipped,
};
use crate::scene::{Interpolation, Pattern, TextureDesc, TextureMode};
use glam::DAffine3;
use std::path::Path;

/// A texture statement's options and file.
#[derive(Debug, PartialEq)]
pub(super) struct MapStatement<'a> {
    /// As written, spaces included (file names may have them).
    pub file: &'a str,
    /// `-bm`: a bump map's multiplier.
    pub bump_multiplier: Option<f32>,
    /// The other options, as written: embray applies none of them.
    pub unused: Vec<String>,
}

/// How many values an option takes (the MTL specification's options).
fn arity(option: &str) -> Option<(usize, usize)> {
    match option {
        "-blendu" | "-blendv" | "-cc" | "-clamp" | "-imfchan" | "-type" | "-bm" | "-boost"
        | "-texres" => Some((1, 1)),
        "-mm" => Some((2, 2)),
        "-o" | "-s" | "-t" => Some((1, 3)),
        _ => None,
    }
}

/// The first word of `text` and what follows it.
fn split_word(text: &str) -> (&str, &str) {
    let text = text.trim_start();
    let end = text.find(char::is_whitespace).unwrap_or(text.len());
    (&text[..end], &text[end..])
}

/// Splits `value` (what follows the keyword) into options and the file name.
pub(super) fn parse_map(value: &str) -> Result<MapStatement<'_>, String> {
    let mut rest = value;
    let mut map = MapStatement { file: "", bump_multiplier: None, unused: Vec::new() };
    loop {
        let (option, after) = split_word(rest);
        let Some((least, most)) = arity(option) else { break };
        rest = after;
        let mut values = Vec::new();
        while values.len() < most {
            let (word, after) = split_word(rest);
            // Beyond the required values, only numbers belong to the option (`-s 2 file`).
            if word.is_empty() || (values.len() >= least && word.parse::<f32>().is_err()) {
                break;
            }
            values.push(word);
            rest = after;
        }
        if values.len() < least {
            return Err(format!("gives {option} without its {least} value(s)"));
        }
        if option == "-bm" {
            let bm = values[0].parse::<f32>().ok().filter(|v| v.is_finite()).ok_or_else(|| {
                format!("gives -bm '{}', not a finite number", crate::excerpt::excerpt(values[0]))
            })?;
            map.bump_multiplier = Some(bm);
        } else {
            map.unused.push(std::iter::once(option).chain(values).collect::<Vec<_>>().join(" "));
        }
    }
    map.file = rest.trim();
    if map.file.is_empty() {
        return Err("names no image file".to_owned());
    }
    Ok(map)
}

/// Where a texture statement names its image, for the image's errors.
pub(super) struct MapAt<'a> {
    pub mtl: &'a Path,
    pub material: &'a str,
    pub keyword: &'a str,
    pub line: usize,
}

impl MapAt<'_> {
    fn image_ref(&self, file: &str) -> ImageRef<'_> {
        ImageRef {
            image: self.mtl.parent().unwrap_or(Path::new("")).join(file),
            scene: self.mtl,
            item: format!(
                "{} of material '{}'",
                self.keyword,
                crate::excerpt::excerpt(self.material)
            ),
            line: Line(Some(self.line)),
        }
    }
}

fn image_texture(
    image: std::sync::Arc<crate::scene::TextureImage>,
    normalizer: f32,
) -> TextureDesc {
    TextureDesc {
        pattern: Pattern::Image {
            image: with_rows_flipped(&image),
            interpolation: Interpolation::BilinearCentered,
            normalizer,
        },
        mode: TextureMode::Replace,
        texture_from_object: DAffine3::IDENTITY,
    }
}

/// A colour texture (`map_Kd`): sRGB decoded to linear.
pub(super) fn colour(at: &MapAt, file: &str) -> Result<TextureDesc, SceneError> {
    Ok(image_texture(load(&at.image_ref(file), true)?, 1.0))
}

/// A data texture (normals, heights, coverage) in [0, 1], with what `load_data` read.
pub(super) fn data(
    at: &MapAt,
    file: &str,
    alpha: bool,
) -> Result<(TextureDesc, DataImage), SceneError> {
    let data = load_data(&at.image_ref(file), alpha)?;
    Ok((image_texture(std::sync::Arc::clone(&data.image), RAW_FULL_SCALE), data))
}

/// Whether an image given as a bump map is a tangent-space normal map: exporters (Blender,
/// Sponza's) write normal maps as `map_Bump`. A height field is grey; a normal map's mean is
/// near (0.5, 0.5, 1), blue above the red and green that average half their range.
pub(super) fn looks_like_normal_map(data: &DataImage) -> bool {
    if data.alpha || data.image.texels.is_empty() {
        return false;
    }
    let sum: glam::DVec3 = data.image.texels.iter().map(|t| t.as_dvec3()).sum();
    let mean = sum / (data.image.texels.len() as f64 * f64::from(RAW_FULL_SCALE));
    let centred = |c: f64| (c - 0.5).abs() < 0.15;
    centred(mean.x) && centred(mean.y) && mean.z > 0.75 && mean.z - mean.x.max(mean.y) > 0.2
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn options_are_split_from_the_file() {
        let map = parse_map(" -s 2 2 1 -o 0.5 -bm 0.25 -clamp on my wood.png ").unwrap();
        assert_eq!(map.file, "my wood.png");
        assert_eq!(map.bump_multiplier, Some(0.25));
        assert_eq!(map.unused, ["-s 2 2 1", "-o 0.5", "-clamp on"]);
        let plain = parse_map("wood.png").unwrap();
        assert_eq!((plain.file, plain.bump_multiplier, plain.unused.len()), ("wood.png", None, 0));
        // A file name that is a number follows an option's optional values.
        assert_eq!(parse_map("-s 2 3 4 5.png").unwrap().file, "5.png");
    }

    #[test]
    fn bad_options_are_errors() {
        assert_eq!(parse_map("-bm").unwrap_err(), "gives -bm without its 1 value(s)");
        assert_eq!(parse_map("-bm x h.png").unwrap_err(), "gives -bm 'x', not a finite number");
        assert!(parse_map("-bm nan h.png").is_err());
        assert_eq!(parse_map("-s 2").unwrap_err(), "names no image file");
        assert_eq!(parse_map("  ").unwrap_err(), "names no image file");
    }

    fn data_of(texels: Vec<Vec3>, alpha: bool) -> DataImage {
        let image = crate::scene::TextureImage {
            file: "x.png".into(),
            width: texels.len() as u32,
            height: 1,
            texels,
            srgb_decoded: false,
            hdr: false,
            rows_flipped: false,
        };
        DataImage { image: std::sync::Arc::new(image), alpha }
    }

    #[test]
    fn normal_maps_are_told_from_height_fields() {
        let normals = vec![Vec3::new(128.0, 128.0, 255.0), Vec3::new(100.0, 150.0, 240.0)];
        assert!(looks_like_normal_map(&data_of(normals.clone(), false)));
        assert!(!looks_like_normal_map(&data_of(normals, true)));
        let heights = vec![Vec3::splat(30.0), Vec3::splat(250.0)];
        assert!(!looks_like_normal_map(&data_of(heights, false)));
        assert!(!looks_like_normal_map(&data_of(vec![Vec3::new(20.0, 20.0, 250.0)], false)));
        assert!(!looks_like_normal_map(&data_of(Vec::new(), false)));
    }
}
