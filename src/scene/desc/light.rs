//! Lights and environment maps.

use super::shape::TextureImage;
use glam::{DVec3, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub enum LightDesc {
    /// Isotropic point light; `intensity` is radiant intensity (W/sr per channel).
    Point { position: DVec3, intensity: Vec3 },
    /// A point light that sends its light into a cone around `direction` (unit, from the
    /// light into the scene): the course's SpotLight. Full `intensity` within half the
    /// `falloff_degrees` of the axis, none beyond half the `coverage_degrees`, and in
    /// between `intensity` times ((cos α − cos(coverage/2)) / (cos(falloff/2) −
    /// cos(coverage/2)))⁴. (hw5.tex prints cos(falloff/2) as the first term, which makes
    /// the light drop to 0 just outside the falloff cone and jump back to full at the
    /// coverage edge, against its own description: "diminish non-linearly" from the first to
    /// the second. The pack has no SpotLight reference to settle it.)
    Spot {
        position: DVec3,
        direction: DVec3,
        intensity: Vec3,
        coverage_degrees: f64,
        falloff_degrees: f64,
    },
    /// Light from infinitely far away arriving along `direction` (pointing from the light
    /// into the scene); `irradiance` on a surface facing it.
    Directional { direction: DVec3, irradiance: Vec3 },
    /// Constant light added to every surface's ambient reflectance (the course's
    /// AmbientLight; only the Whitted integrator uses it).
    Ambient { radiance: Vec3 },
    /// The course's AreaLight: a square of side `size` centred at `center`, facing `normal`
    /// (unit length), emitting `radiance` (two-sided). It lights the scene (sampled by area)
    /// but has no geometry: rays never hit it, so the camera does not see it.
    Area { center: DVec3, normal: DVec3, size: f64, radiance: Vec3 },
    /// Radiance from every direction far away: a latitude-longitude map (the course's
    /// SphericalDirectionalLight; see `shading::light::EnvironmentLight` for the mapping)
    /// times `scale`. Rays that leave the scene see it in place of the background.
    Environment { map: EnvironmentMap, scale: Vec3, mapping: EnvironmentMapping },
}

pub use crate::light::EnvironmentMapping;

/// What an environment light's radiance comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum EnvironmentMap {
    /// The same radiance from every direction.
    Constant(Vec3),
    /// A latitude-longitude image of linear radiances.
    Image(std::sync::Arc<TextureImage>),
}
