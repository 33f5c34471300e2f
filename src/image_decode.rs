//! The checks every PNG, JPEG or BMP input gets before the `image` crate decodes it
//! (textures, radiance maps, `compare`'s images): a known format, and a JPEG that is not
//! cut short (its decoder fills what a cut file lacks with grey and says nothing).

use image::{ImageFormat, ImageReader};
use std::io::Cursor;

/// The most a header may make the decoder hold before the image's size is known (a PNG's
/// ICC profile is inflated as its header is read).
const HEADER_BYTES: u64 = 16 << 20;

/// A reader of `bytes` whose format is known and which, if a JPEG, is complete; its limits
/// let it read the header (`into_dimensions`): give it `limits` for the size it says
/// before decoding.
pub fn reader(bytes: &[u8]) -> Result<ImageReader<Cursor<&[u8]>>, String> {
    let mut reader =
        ImageReader::new(Cursor::new(bytes)).with_guessed_format().map_err(|e| e.to_string())?;
    let mut header = image::Limits::default();
    header.max_alloc = Some(HEADER_BYTES);
    reader.limits(header);
    match reader.format() {
        None => Err("not a PNG, JPEG or BMP image".into()),
        // Its texels are linear and unbounded: read only as radiance (`rgbe`), never into
        // an 8-bit texture or a compared image, which would clamp them.
        Some(ImageFormat::Hdr) => Err("a Radiance RGBE image, which embray reads only as a \
                                       radiance map (an environment or a Mitsuba bitmap)"
            .into()),
        Some(ImageFormat::Jpeg) if !jpeg_is_complete(bytes) => {
            Err("the JPEG ends before its end-of-image marker: the file is cut short".into())
        }
        Some(_) => Ok(reader),
    }
}

/// Decoding limits for an image of `width` × `height` (from its header): what its widest
/// texel format takes (16-bit RGBA, 8 bytes), plus 16 MiB for everything else the decoder
/// holds, so that no compressed chunk inflates past them (a 4 × 4 PNG's ICC profile
/// inflated to 500 MB).
pub fn limits(width: u32, height: u32) -> image::Limits {
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(width);
    limits.max_image_height = Some(height);
    limits.max_alloc = Some(u64::from(width) * u64::from(height) * 8 + HEADER_BYTES);
    limits
}

/// Whether a JPEG's last scan is followed by the end-of-image marker (FF D9). Inside scan
/// data an FF byte is always followed by 00 or a restart marker, so FF D9 after the last
/// start-of-scan (FF DA) is the end of the image, never pixel data; an embedded thumbnail's
/// markers all come before the main image's scans.
fn jpeg_is_complete(bytes: &[u8]) -> bool {
    let last = |marker: u8| bytes.windows(2).rposition(|w| w == [0xFF, marker]);
    match (last(0xDA), last(0xD9)) {
        (Some(scan), Some(end)) => end > scan,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_radiance_file_is_refused_where_texels_would_be_clamped() {
        let file = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n\x80\x80\x80\x81";
        let err = super::reader(file).err().expect("refused");
        assert!(err.contains("Radiance RGBE") && err.contains("only as a radiance map"), "{err}");
    }
}
