//! The linear RGB of a Radiance RGBE (`.hdr`) file held in memory, for radiance maps
//! (environments, Mitsuba's bitmaps), decoded by the `image` crate. Callers check `size`
//! against their own limit before `read` allocates for the pixels.

use glam::Vec3;
use image::ImageDecoder;
use image::codecs::hdr::HdrDecoder;
use std::io::Cursor;

/// Whether `bytes` start as a Radiance file does (`#?RADIANCE`, or `#?RGBE` from older
/// writers).
pub fn is_rgbe(bytes: &[u8]) -> bool {
    bytes.starts_with(b"#?")
}

fn decoder(bytes: &[u8]) -> Result<HdrDecoder<Cursor<&[u8]>>, String> {
    let reader = Cursor::new(bytes);
    let decoder = if bytes.starts_with(b"#?RADIANCE") {
        HdrDecoder::new(reader)
    } else {
        // Other signatures: the header is read without checking the first line.
        HdrDecoder::new_nonstrict(reader)
    };
    decoder.map_err(|e| format!("not a readable Radiance RGBE file ({e})"))
}

/// The image's width and height, from its header alone.
pub fn size(bytes: &[u8]) -> Result<(u64, u64), String> {
    let (width, height) = decoder(bytes)?.dimensions();
    Ok((width.into(), height.into()))
}

/// Every texel, row by row from the top.
pub fn read(bytes: &[u8]) -> Result<Vec<Vec3>, String> {
    let image = image::DynamicImage::from_decoder(decoder(bytes)?)
        .map_err(|e| format!("a broken Radiance RGBE file ({e})"))?;
    Ok(image.into_rgb32f().pixels().map(|p| Vec3::from_array(p.0)).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat (uncompressed) 2 × 1 file: texels 1.0 and (0.5, 0.25, 255/256).
    fn two_texels(signature: &str) -> Vec<u8> {
        let mut file = format!("{signature}\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n").into_bytes();
        file.extend([128, 128, 128, 129, 128, 64, 255, 128]);
        file
    }

    #[test]
    fn reads_sizes_and_linear_texels() {
        for signature in ["#?RADIANCE", "#?RGBE"] {
            let file = two_texels(signature);
            assert!(is_rgbe(&file));
            assert_eq!(size(&file).unwrap(), (2, 1));
            let texels = read(&file).unwrap();
            assert_eq!(texels, [Vec3::ONE, Vec3::new(0.5, 0.25, 0.99609375)], "{signature}");
        }
    }

    #[test]
    fn a_cut_file_is_an_error() {
        let file = two_texels("#?RADIANCE");
        let err = read(&file[..file.len() - 3]).unwrap_err();
        assert!(err.contains("broken Radiance RGBE"), "{err}");
        assert!(size(b"#?RADIANCE\nno header end").is_err());
    }
}
