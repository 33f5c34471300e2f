//! Colour helpers shared by light selection, BSDF lobe choice and reports.

use glam::Vec3;

/// Relative luminance of linear Rec. 709 RGB.
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}
