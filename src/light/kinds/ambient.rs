//! Constant light added to every surface's ambient reflectance (the course's AmbientLight;
//! only the Whitted integrator uses it).

use super::{LightKind, LightParts};
use crate::params::{ParamError, ParamSink, Params, Resources};
use glam::{DAffine3, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub struct Ambient {
    pub radiance: Vec3,
}

impl LightKind for Ambient {
    const NAME: &'static str = "ambient";
    const LABEL: &'static str = "ambient light";
    const FIELDS: &'static [&'static str] = &["radiance"];

    fn read(p: &Params, _: &dyn Resources) -> Result<Self, ParamError> {
        Ok(Ambient { radiance: p.color("radiance")? })
    }

    fn write(&self, out: &mut dyn ParamSink) {
        out.color("radiance", self.radiance);
    }

    fn compile(&self, _: &DAffine3, parts: &mut LightParts) {
        parts.ambient += self.radiance;
    }
}
