//! Named indices of refraction: Mitsuba's table of dielectrics, and the measured complex
//! indices of conductors (`material="Au"`).

use glam::DVec3;

/// Mitsuba's named dielectric indices (its `ior.h`).
const DIELECTRICS: [(&str, f64); 23] = [
    ("vacuum", 1.0),
    ("helium", 1.00004),
    ("hydrogen", 1.00013),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.3330),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.5750),
    ("diamond", 2.419),
];

/// The index of a named dielectric (or a number written as text).
pub(super) fn dielectric_ior(name: &str) -> Option<f64> {
    let name = name.trim();
    DIELECTRICS
        .iter()
        .find(|(known, _)| known.eq_ignore_ascii_case(name))
        .map(|(_, ior)| *ior)
        .or_else(|| name.parse().ok().filter(|v: &f64| v.is_finite()))
}

/// The (eta, k) of a named conductor in linear RGB.
pub(super) fn conductor_ior(name: &str) -> Option<(DVec3, DVec3)> {
    super::metals::rgb_ior(name.trim())
}
