//! Which image format a path asks for, by its extension: the EXR (linear, with AOVs) or a
//! display image (PNG or JPEG, tone-mapped).

use std::path::Path;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageFormat {
    Exr,
    Png,
    Jpeg,
}

impl ImageFormat {
    /// The format of `path`'s extension (any case); `None` without an extension. An
    /// extension that names none of them is an error naming `flag`.
    pub fn of_path(path: &Path, flag: &str) -> Result<Option<Self>, String> {
        let Some(extension) = path.extension() else { return Ok(None) };
        match extension.to_string_lossy().to_ascii_lowercase().as_str() {
            "exr" => Ok(Some(ImageFormat::Exr)),
            "png" => Ok(Some(ImageFormat::Png)),
            "jpg" | "jpeg" => Ok(Some(ImageFormat::Jpeg)),
            other => Err(format!(
                "{flag} '{}': the extension '.{other}' names no image format embray writes \
                 (.exr, .png, .jpg or .jpeg)",
                path.display()
            )),
        }
    }

    /// The display format (PNG or JPEG) `path` asks for, PNG without an extension, for a
    /// `flag` whose file is a tone-mapped 8-bit image: an `.exr` would hold PNG bytes under
    /// an EXR's name, so it is refused, saying `exr_hint` (where an EXR comes from).
    pub fn display_of_path(path: &Path, flag: &str, exr_hint: &str) -> Result<Self, String> {
        match Self::of_path(path, flag)? {
            Some(ImageFormat::Exr) => {
                Err(format!("{flag} '{}' names an EXR: {exr_hint}", path.display()))
            }
            Some(format) => Ok(format),
            None => Ok(ImageFormat::Png),
        }
    }

    /// A display format (PNG or JPEG): tone-mapped 8-bit pixels.
    pub fn is_display(self) -> bool {
        self != ImageFormat::Exr
    }
}

/// Encodes 8-bit RGB pixels as `format` (PNG or JPEG at quality 95) into `sink`.
pub fn encode_display_rgb8(
    pixels: &[u8],
    width: u32,
    height: u32,
    format: ImageFormat,
    sink: &mut dyn super::WriteSeek,
) -> std::io::Result<()> {
    use image::ImageEncoder;
    let color = image::ExtendedColorType::Rgb8;
    let result = match format {
        ImageFormat::Jpeg => image::codecs::jpeg::JpegEncoder::new_with_quality(sink, 95)
            .write_image(pixels, width, height, color),
        _ => image::codecs::png::PngEncoder::new(sink).write_image(pixels, width, height, color),
    };
    result.map_err(|e| match e {
        image::ImageError::IoError(io) => io,
        other => std::io::Error::other(other.to_string()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extensions_choose_the_format_and_others_are_refused() {
        let of = |p: &str| ImageFormat::of_path(Path::new(p), "-o");
        assert_eq!(of("a.exr"), Ok(Some(ImageFormat::Exr)));
        assert_eq!(of("dir.d/a.PNG"), Ok(Some(ImageFormat::Png)));
        assert_eq!(of("a.jpeg"), Ok(Some(ImageFormat::Jpeg)));
        assert_eq!(of("a.JPG"), Ok(Some(ImageFormat::Jpeg)));
        assert_eq!(of("/dev/null"), Ok(None));
        let err = of("a.tif").unwrap_err();
        assert!(err.contains("-o 'a.tif'") && err.contains("'.tif'"), "{err}");
        let display = |p: &str| ImageFormat::display_of_path(Path::new(p), "-o", "hint");
        assert_eq!(display("a.jpg"), Ok(ImageFormat::Jpeg));
        assert_eq!(display("/dev/stdout"), Ok(ImageFormat::Png));
        assert_eq!(display("a.EXR"), Err("-o 'a.EXR' names an EXR: hint".to_owned()));
        assert!(display("a.tif").is_err());
    }
}
