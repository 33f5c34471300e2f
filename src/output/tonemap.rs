//! Tone curves from linear radiance to display values, and the sRGB encoding.

use crate::choice::named_choices;
use glam::Vec3;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ToneMap {
    /// Clamp to [0, 1].
    None,
    /// x / (1 + x) per channel.
    Reinhard,
    /// Narkowicz's fit of the ACES filmic curve.
    #[default]
    Aces,
    /// The CENG795 course's output: radiance is already in 0–255 display units and is
    /// clamped to [0, 255] and truncated to an integer (as the course's reference images
    /// are; rounding makes a quarter of their pixels one step brighter), with no tone curve
    /// and no sRGB encoding.
    Clamp255,
    /// Reinhard et al.'s global photographic operator (`output::Photographic`), as the
    /// CENG795 course specifies it: over the whole image, with its own gamma.
    Photographic,
}

named_choices!(ToneMap, "tone curve", {
    None => "none",
    Reinhard => "reinhard",
    Aces => "aces",
    Clamp255 => "clamp255",
    Photographic => "photographic",
});

/// Both curves are flat (white) long before their inputs overflow f32, so inputs are
/// clamped to `SATURATED` first: without it a pixel of 1e20 (or inf) computes inf / inf = NaN
/// and turns black instead of white.
const SATURATED: f32 = 1e4;

pub(super) fn tone_map(c: Vec3, curve: ToneMap) -> Vec3 {
    match curve {
        // Clamp255 and Photographic are applied to the whole image by `to_srgb8`.
        ToneMap::None | ToneMap::Clamp255 | ToneMap::Photographic => c,
        ToneMap::Reinhard => {
            let c = c.min(Vec3::splat(SATURATED));
            c / (Vec3::ONE + c)
        }
        ToneMap::Aces => {
            let c = c.min(Vec3::splat(SATURATED));
            let (a, b, cc, d, e) = (2.51, 0.03, 2.43, 0.59, 0.14);
            (c * (a * c + b)) / (c * (cc * c + d) + e)
        }
    }
}

pub(super) fn srgb_encode(linear: f32) -> f32 {
    if linear <= 0.003_130_8 { 12.92 * linear } else { 1.055 * linear.powf(1.0 / 2.4) - 0.055 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn very_bright_pixels_are_white_not_black() {
        for curve in [ToneMap::Aces, ToneMap::Reinhard] {
            for value in [1e4, 1e20, 3e38, f32::INFINITY] {
                let mapped = tone_map(Vec3::splat(value), curve);
                assert!(mapped.min_element() >= 0.99, "{curve:?} {value}: {mapped}");
            }
        }
    }

    #[test]
    fn srgb_encoding_hits_known_points() {
        assert_eq!(srgb_encode(0.0), 0.0);
        assert!((srgb_encode(1.0) - 1.0).abs() < 1e-6);
        assert!((srgb_encode(0.18) - 0.4614).abs() < 1e-3);
    }
}
