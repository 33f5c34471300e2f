//! An isotropic point light: `intensity` is radiant intensity (W/sr per channel).

use super::{LightKind, LightParts, distance};
use crate::light::PointLight;
use crate::params::{ParamError, ParamSink, Params, Resources};
use glam::{DAffine3, DVec3, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    pub position: DVec3,
    pub intensity: Vec3,
}

impl LightKind for Point {
    const NAME: &'static str = "point";
    const LABEL: &'static str = "point light";
    const FIELDS: &'static [&'static str] = &["position", "intensity"];
    const ONLY_SAMPLED: bool = true;

    fn read(p: &Params, _: &dyn Resources) -> Result<Self, ParamError> {
        Ok(Point { position: p.vec3("position")?, intensity: p.color("intensity")? })
    }

    fn write(&self, out: &mut dyn ParamSink) {
        out.vec3("position", self.position);
        out.color("intensity", self.intensity);
    }

    fn translate(&mut self, offset: DVec3) {
        self.position += offset;
    }

    fn reach(&self, origin: DVec3) -> f64 {
        distance(self.position, origin)
    }

    fn compile(&self, render_from_world: &DAffine3, parts: &mut LightParts) {
        parts.points.push(PointLight {
            position: render_from_world.transform_point3(self.position).as_vec3(),
            intensity: self.intensity,
            spot: None,
            projection: None,
        });
    }
}
