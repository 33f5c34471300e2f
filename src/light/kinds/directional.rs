//! Light from infinitely far away arriving along `direction` (unit, from the light into the
//! scene); `irradiance` on a surface facing it.

use super::{LightKind, LightParts};
use crate::light::DirectionalLight;
use crate::params::{ParamError, ParamSink, Params, Resources};
use glam::{DAffine3, DVec3, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub struct Directional {
    pub direction: DVec3,
    pub irradiance: Vec3,
}

impl LightKind for Directional {
    const NAME: &'static str = "directional";
    const LABEL: &'static str = "directional light";
    const FIELDS: &'static [&'static str] = &["direction", "irradiance"];

    fn read(p: &Params, _: &dyn Resources) -> Result<Self, ParamError> {
        Ok(Directional { direction: p.direction("direction")?, irradiance: p.color("irradiance")? })
    }

    fn write(&self, out: &mut dyn ParamSink) {
        out.vec3("direction", self.direction);
        out.color("irradiance", self.irradiance);
    }

    fn compile(&self, render_from_world: &DAffine3, parts: &mut LightParts) {
        parts.directional.push(DirectionalLight {
            direction: render_from_world.transform_vector3(self.direction).normalize().as_vec3(),
            irradiance: self.irradiance,
        });
    }
}
