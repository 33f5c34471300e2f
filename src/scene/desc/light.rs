//! Lights: the model lists the kinds (`LightDesc`), each of which is one file in
//! `light::kinds`.

pub use crate::light::EnvironmentMapping;
pub use crate::light::kinds::*;
