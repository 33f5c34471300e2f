//! Lights: the model lists the kinds, each of which is one file in `light::kinds`.

pub use crate::light::EnvironmentMapping;
pub use crate::light::kinds::{
    Ambient, Area, Directional, Environment, EnvironmentMap, LightDesc, Point, Spot,
};
