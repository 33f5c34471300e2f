//! An image's texels, decoded: what textures and environment lights look up.

use glam::Vec3;
use std::path::PathBuf;

/// Decoded texels, row-major from the top-left, in the file's own units (0–255 for 8-bit
/// files, 0–65535 for 16-bit ones, linear values for float ones) unless the loader was
/// asked to decode sRGB into linear [0, 1]. `file` is kept for messages and for writing
/// the scene back out.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureImage {
    pub file: PathBuf,
    pub width: u32,
    pub height: u32,
    pub texels: Vec<Vec3>,
    /// True if the texels were decoded from sRGB to linear [0, 1].
    pub srgb_decoded: bool,
    /// True if the texels are an EXR file's linear values (high dynamic range).
    pub hdr: bool,
}
