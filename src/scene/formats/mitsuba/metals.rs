//! Measured complex indices of refraction of conductors (Mitsuba's `ior/` data, embedded so
//! that an installed embray needs no data folder), converted to linear RGB.

use glam::DVec3;

/// The (eta, k) of the conductor `name` in linear RGB, if embray knows it.
pub(super) fn rgb_ior(_name: &str) -> Option<DVec3Pair> {
    None
}

type DVec3Pair = (DVec3, DVec3);
