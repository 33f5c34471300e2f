//! Reading a texture's image (PNG, JPEG or BMP, through the `image` crate) into `TextureImage`,
//! its size checked against `MAX_TEXTURE_TEXELS` before any texel is decoded.

use super::image_cache::Reading;
use crate::scene::desc::TextureImage;
use crate::scene::error::{Line, SceneError};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The most texels one texture image may have (12 bytes each once decoded: 384 MiB), a
/// 8192 × 4096 image; larger ones are refused before decoding.
pub const MAX_TEXTURE_TEXELS: u64 = 1 << 25;

pub use super::image_ref::ImageRef;

/// The image `at` names as `reading` reads it, decoded by `decode` from the file's bytes
/// unless it is held already (`image_cache`).
fn shared(
    at: &ImageRef,
    reading: Reading,
    decode: impl FnOnce(&[u8]) -> Result<(Arc<TextureImage>, bool), SceneError>,
) -> Result<(Arc<TextureImage>, bool), SceneError> {
    let bytes = crate::scene::read_input_bytes(&at.image).map_err(|e| at.error(e.to_string()))?;
    super::image_cache::shared(&at.image, &bytes, reading, decode)
}

/// sRGB's transfer function, from an encoded value in [0, 1] to linear.
fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// The image `at` names, whose file holds `bytes`, decoded (its size checked first).
fn decode(at: &ImageRef, bytes: &[u8]) -> Result<image::DynamicImage, SceneError> {
    let checked = || crate::image_decode::reader(bytes).map_err(|e| at.error(e));
    let (width, height) = checked()?.into_dimensions().map_err(|e| at.error(e.to_string()))?;
    let texels = u64::from(width) * u64::from(height);
    if texels == 0 || texels > MAX_TEXTURE_TEXELS {
        return Err(at.error(format!(
            "{width} × {height} texels; a texture takes 1 to {MAX_TEXTURE_TEXELS} texels"
        )));
    }
    at.check_room(width.into(), height.into(), crate::limits::BYTES_PER_TEXEL)?;
    let mut reader = checked()?;
    reader.limits(crate::image_decode::limits(width, height));
    reader.decode().map_err(|e| at.error(e.to_string()))
}

fn is_sixteen_bit(decoded: &image::DynamicImage) -> bool {
    matches!(
        decoded.color(),
        image::ColorType::L16
            | image::ColorType::La16
            | image::ColorType::Rgb16
            | image::ColorType::Rgba16
    )
}

/// What a raw texel of any integer image runs up to: 16-bit files are scaled to it, so
/// that every normalizer (the CENG795 `Normalizer`, Mitsuba's raw bitmaps, a TOML
/// `normalizer`) means the same for a 16-bit file as for the 8-bit file of the same picture.
pub const RAW_FULL_SCALE: f32 = 255.0;

/// Per channel, how many of a decoded image's units make one of `RAW_FULL_SCALE`'s
/// (65535 / 257 = 255 exactly).
fn units_per_raw_unit(decoded: &image::DynamicImage) -> f32 {
    if is_sixteen_bit(decoded) { 257.0 } else { 1.0 }
}

/// The image `at` names. `decode_srgb`: texels become linear [0, 1] through sRGB's curve;
/// otherwise they run from 0 to `RAW_FULL_SCALE` (a 16-bit file's values divided by 257,
/// keeping their fractions).
pub fn load(at: &ImageRef, decode_srgb: bool) -> Result<Arc<TextureImage>, SceneError> {
    let reading = Reading::Colour { srgb: decode_srgb };
    let (image, _) = shared(at, reading, |bytes| Ok((colour(at, bytes, decode_srgb)?, false)))?;
    Ok(image)
}

/// `load` of the file's `bytes`.
fn colour(at: &ImageRef, bytes: &[u8], decode_srgb: bool) -> Result<Arc<TextureImage>, SceneError> {
    let decoded = decode(at, bytes)?;
    let (width, height) = (decoded.width(), decoded.height());
    let per_raw_unit = units_per_raw_unit(&decoded);
    // Straight from the decoded channels to linear texels: no f32 copy of the image between
    // (the peak was the file, the decoded image and two 12-byte copies per texel).
    let texel = |c: [f32; 3]| {
        let c = glam::Vec3::from_array(c);
        if decode_srgb {
            // One division by the file's full scale (65535 or 255, exact in f32), as before
            // raw texels were scaled: 16-bit sRGB textures keep their values bit for bit.
            let c = c / (per_raw_unit * RAW_FULL_SCALE);
            glam::Vec3::new(srgb_to_linear(c.x), srgb_to_linear(c.y), srgb_to_linear(c.z))
        } else {
            c / per_raw_unit
        }
    };
    let texels: Vec<glam::Vec3> = if is_sixteen_bit(&decoded) {
        let rgb = decoded.into_rgb16();
        rgb.pixels().map(|p| texel(p.0.map(f32::from))).collect()
    } else {
        let rgb = decoded.into_rgb8();
        rgb.pixels().map(|p| texel(p.0.map(f32::from))).collect()
    };
    Ok(Arc::new(TextureImage {
        file: at.image.clone(),
        width,
        height,
        texels,
        srgb_decoded: decode_srgb,
        hdr: false,
        rows_flipped: false,
    }))
}

/// An image of data rather than colour (`load_data`).
pub struct DataImage {
    /// Texels from 0 to `RAW_FULL_SCALE`, no sRGB curve.
    pub image: Arc<TextureImage>,
    /// Every texel is the file's alpha (as grey), not its colour.
    pub alpha: bool,
}

/// The image `at` names as data (normals, heights, coverage). With `alpha`, a file that has
/// an alpha channel gives its alpha, as grey: a coverage mask is the alpha of a PNG more
/// often than its colour.
pub fn load_data(at: &ImageRef, alpha: bool) -> Result<DataImage, SceneError> {
    let (image, alpha) = shared(at, Reading::Data { alpha }, |bytes| data(at, bytes, alpha))?;
    Ok(DataImage { image, alpha })
}

/// `load_data` of the file's `bytes`: the image, and whether it is the alpha channel.
fn data(at: &ImageRef, bytes: &[u8], alpha: bool) -> Result<(Arc<TextureImage>, bool), SceneError> {
    let decoded = decode(at, bytes)?;
    let (width, height) = (decoded.width(), decoded.height());
    let per_raw_unit = units_per_raw_unit(&decoded);
    let alpha = alpha && decoded.color().has_alpha();
    let texel = |[r, g, b, a]: [f32; 4]| {
        let texel = if alpha { glam::Vec3::splat(a) } else { glam::Vec3::new(r, g, b) };
        texel / per_raw_unit
    };
    let texels: Vec<glam::Vec3> = if is_sixteen_bit(&decoded) {
        let rgba = decoded.into_rgba16();
        rgba.pixels().map(|p| texel(p.0.map(f32::from))).collect()
    } else {
        let rgba = decoded.into_rgba8();
        rgba.pixels().map(|p| texel(p.0.map(f32::from))).collect()
    };
    let image = Arc::new(TextureImage::plain(at.image.clone(), width, height, texels));
    Ok((image, alpha))
}

/// `image` upside down (`TextureImage::rows_flipped`): for texture coordinates whose v runs
/// up the image.
pub fn with_rows_flipped(image: &TextureImage) -> Arc<TextureImage> {
    let width = image.width as usize;
    let texels = image.texels.chunks_exact(width).rev().flatten().copied().collect();
    Arc::new(TextureImage {
        texels,
        rows_flipped: !image.rows_flipped,
        file: image.file.clone(),
        ..*image
    })
}

/// `image` in grey, each texel its luminance (`color::luminance`): a colour image read as a
/// number, as Mitsuba reads one (its `eval_1`).
pub fn as_luminance(image: &TextureImage) -> Arc<TextureImage> {
    let grey = |c: &glam::Vec3| glam::Vec3::splat(crate::color::luminance(*c));
    Arc::new(TextureImage {
        texels: image.texels.iter().map(grey).collect(),
        file: image.file.clone(),
        ..*image
    })
}

/// The first four bytes of every OpenEXR file.
const EXR_MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];

/// A radiance map: an EXR file's linear values as they are (R, G, B, or Y for grey
/// images), a Radiance RGBE file's, or a PNG/JPEG read as `load` reads textures. Non-finite values are refused;
/// negative ones (left by some HDR tools' filtering) become 0.
pub fn load_radiance(at: &ImageRef, decode_srgb: bool) -> Result<Arc<TextureImage>, SceneError> {
    let reading = Reading::Radiance { srgb: decode_srgb };
    let (image, _) = shared(at, reading, |bytes| Ok((radiance(at, bytes, decode_srgb)?, false)))?;
    Ok(image)
}

/// `load_radiance` of the file's `bytes`.
fn radiance(
    at: &ImageRef,
    bytes: &[u8],
    decode_srgb: bool,
) -> Result<Arc<TextureImage>, SceneError> {
    let rgbe = crate::rgbe::is_rgbe(bytes);
    if !bytes.starts_with(&EXR_MAGIC) && !rgbe {
        return colour(at, bytes, decode_srgb);
    }
    let size = if rgbe { crate::rgbe::size(bytes) } else { crate::exr_rgb::size(bytes) };
    let (width, height) = size.map_err(|e| at.error(e))?;
    let texels = width * height;
    if texels == 0 || texels > MAX_TEXTURE_TEXELS {
        return Err(at.error(format!(
            "{width} × {height} texels; a radiance map takes 1 to {MAX_TEXTURE_TEXELS} texels"
        )));
    }
    at.check_room(width, height, crate::limits::BYTES_PER_HDR_TEXEL)?;
    let texels = match rgbe {
        true => crate::rgbe::read(bytes),
        false => crate::exr_rgb::read(bytes).map(|(_, _, texels)| texels),
    };
    let mut texels = texels.map_err(|e| at.error(e))?;
    for (i, c) in texels.iter_mut().enumerate() {
        if !c.is_finite() {
            let (x, y) = (i as u64 % width, i as u64 / width);
            return Err(
                at.error(format!("texel ({x}, {y}) is not finite: {} {} {}", c.x, c.y, c.z))
            );
        }
        *c = c.max(glam::Vec3::ZERO);
    }
    Ok(Arc::new(TextureImage {
        file: at.image.clone(),
        width: width as u32,
        height: height as u32,
        texels,
        srgb_decoded: false,
        hdr: true,
        rows_flipped: false,
    }))
}

/// The radiance image a kind's text parameter `name` names, found by `resolve` (each
/// format's own way of finding files) for the scene file `scene`; errors name the parameter.
pub(crate) fn radiance_param(
    params: &crate::params::Params,
    name: &str,
    scene: &Path,
    resolve: impl Fn(&str) -> PathBuf,
    decode_srgb: bool,
) -> Result<Arc<TextureImage>, crate::params::ParamError> {
    let file = params.opt_text(name)?.ok_or_else(|| params.missing(name))?;
    let at = ImageRef {
        image: resolve(file),
        scene,
        item: params.field(name),
        line: Line(params.line(name)),
    };
    load_radiance(&at, decode_srgb).map_err(|e| crate::params::ParamError::Reader(Box::new(e)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write_png(name: &str, image: image::RgbImage) -> PathBuf {
        let path = std::env::temp_dir().join(format!("embray-tex-{}-{name}", std::process::id()));
        image.save(&path).unwrap();
        path
    }

    fn at(path: &Path) -> ImageRef<'_> {
        ImageRef {
            image: path.to_path_buf(),
            scene: Path::new("scene.xml"),
            item: "<TextureMap id=\"1\">".into(),
            line: Line(Some(7)),
        }
    }

    #[test]
    fn texels_keep_file_units_or_decode_srgb() {
        let mut img = image::RgbImage::new(2, 1);
        img.put_pixel(0, 0, image::Rgb([255, 128, 0]));
        img.put_pixel(1, 0, image::Rgb([10, 20, 30]));
        let path = write_png("units.png", img);
        let raw = load(&at(&path), false).unwrap();
        assert_eq!((raw.width, raw.height), (2, 1));
        assert_eq!(raw.texels[0], glam::Vec3::new(255.0, 128.0, 0.0));
        assert_eq!(raw.texels[1], glam::Vec3::new(10.0, 20.0, 30.0));
        let linear = load(&at(&path), true).unwrap();
        assert_eq!(linear.texels[0].x, 1.0);
        assert!((linear.texels[0].y - 0.2158605).abs() < 1e-5, "{}", linear.texels[0].y);
        std::fs::remove_file(path).unwrap();
    }

    #[test]
    fn data_images_keep_file_units_and_give_the_alpha_where_asked() {
        let path = std::env::temp_dir().join(format!("embray-tex-{}-a.png", std::process::id()));
        image::RgbaImage::from_pixel(1, 1, image::Rgba([10, 20, 30, 40])).save(&path).unwrap();
        let alpha = load_data(&at(&path), true).unwrap();
        assert_eq!(alpha.image.texels[0], glam::Vec3::splat(40.0));
        assert!(alpha.alpha);
        let colour = load_data(&at(&path), false).unwrap();
        assert_eq!(colour.image.texels[0], glam::Vec3::new(10.0, 20.0, 30.0));
        assert!(!colour.alpha);
        let deep =
            image::ImageBuffer::<image::Rgb<u16>, _>::from_pixel(1, 1, image::Rgb([1, 2, 65535]));
        deep.save(&path).unwrap();
        let deep = load_data(&at(&path), true).unwrap();
        assert_eq!((deep.image.texels[0].z, deep.alpha), (255.0, false));
        std::fs::remove_file(path).unwrap();
    }

    #[test]
    fn a_sixteen_bit_image_means_what_the_eight_bit_one_of_its_picture_does() {
        let path = std::env::temp_dir().join(format!("embray-tex-{}-16.png", std::process::id()));
        let deep = image::ImageBuffer::<image::Rgb<u16>, _>::from_pixel(
            1,
            1,
            image::Rgb([32896, 65535, 257 * 10 + 128]),
        );
        deep.save(&path).unwrap();
        let raw = load(&at(&path), false).unwrap();
        let expected = glam::Vec3::new(128.0, 255.0, 2698.0 / 257.0);
        assert!((raw.texels[0] - expected).abs().max_element() < 1e-5, "{}", raw.texels[0]);
        let linear = load(&at(&path), true).unwrap();
        assert_eq!(linear.texels[0].y, 1.0);
        assert!((linear.texels[0].x - 0.2158605).abs() < 1e-5, "{}", linear.texels[0].x);
        std::fs::remove_file(path).unwrap();
    }

    /// CRC-32 (PNG's chunk checksum), so that a test can write a valid header.
    fn crc32(bytes: &[u8]) -> u32 {
        let mut crc = !0u32;
        for &b in bytes {
            crc ^= u32::from(b);
            for _ in 0..8 {
                crc = if crc & 1 != 0 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
            }
        }
        !crc
    }

    #[test]
    fn an_image_too_large_is_refused_from_its_header_before_decoding() {
        // A PNG header claiming 100000 × 100000 texels (30 GB as RGB8), and no data.
        let mut ihdr = b"IHDR".to_vec();
        ihdr.extend(100_000u32.to_be_bytes());
        ihdr.extend(100_000u32.to_be_bytes());
        ihdr.extend([8, 2, 0, 0, 0]);
        let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
        png.extend(13u32.to_be_bytes());
        png.extend(&ihdr);
        png.extend(crc32(&ihdr).to_be_bytes());
        // An empty IDAT: the decoder reads the header up to the first data chunk.
        png.extend(0u32.to_be_bytes());
        png.extend(b"IDAT");
        png.extend(crc32(b"IDAT").to_be_bytes());
        let path = std::env::temp_dir().join(format!("embray-tex-{}-huge.png", std::process::id()));
        std::fs::write(&path, &png).unwrap();
        let err = load(&at(&path), false).unwrap_err().to_string();
        std::fs::remove_file(&path).unwrap();
        assert!(err.contains("100000 × 100000 texels") && err.contains("huge.png"), "{err}");
    }

    #[test]
    fn broken_and_missing_images_name_the_file_and_the_texture() {
        let path = std::env::temp_dir().join(format!("embray-tex-{}-bad.png", std::process::id()));
        std::fs::write(&path, b"\x89PNG\r\n\x1a\n garbage").unwrap();
        let err = load(&at(&path), false).unwrap_err().to_string();
        assert!(
            err.contains("bad.png")
                && err.contains("TextureMap id=\"1\"")
                && err.contains("line 7"),
            "{err}"
        );
        std::fs::remove_file(&path).unwrap();
        let err = load(&at(&path), false).unwrap_err().to_string();
        assert!(err.contains("No such file"), "{err}");
        let text = std::env::temp_dir().join(format!("embray-tex-{}-text.png", std::process::id()));
        std::fs::write(&text, b"just words").unwrap();
        let err = load(&at(&text), false).unwrap_err().to_string();
        assert!(err.contains("not a PNG, JPEG or BMP"), "{err}");
        std::fs::remove_file(&text).unwrap();
    }
}
