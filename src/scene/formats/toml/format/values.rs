//! Plain values of the TOML format.

pub(crate) type Vec3 = [f64; 3];
