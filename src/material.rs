//! Surface materials as the integrator sees them.

use glam::Vec3;

/// A Lambertian reflector that may also emit (emission is two-sided, so an area light
/// works whichever way its quad is wound).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Material {
    pub albedo: Vec3,
    pub emission: Vec3,
}

impl Material {
    pub fn is_emissive(&self) -> bool {
        self.emission.max_element() > 0.0
    }
}
