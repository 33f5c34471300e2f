//! A point light that sends its light into a cone around `direction` (unit, from the light
//! into the scene): the course's SpotLight. Full `intensity` within half the
//! `falloff_degrees` of the axis, none beyond half the `coverage_degrees`, and in between
//! `intensity` times ((cos α − cos(coverage/2)) / (cos(falloff/2) − cos(coverage/2)))⁴.
//! (hw5.tex prints cos(falloff/2) as the first term, which makes the light drop to 0 just
//! outside the falloff cone and jump back to full at the coverage edge, against its own
//! description: "diminish non-linearly" from the first to the second. The pack has no
//! SpotLight reference to settle it.)

use super::{LightKind, LightParts, distance};
use crate::light::PointLight;
use crate::params::{ParamError, ParamSink, Params, Resources};
use glam::{DAffine3, DVec3, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub struct Spot {
    pub position: DVec3,
    pub direction: DVec3,
    pub intensity: Vec3,
    pub coverage_degrees: f64,
    pub falloff_degrees: f64,
}

impl LightKind for Spot {
    const NAME: &'static str = "spot";
    const LABEL: &'static str = "spot light";
    const FIELDS: &'static [&'static str] =
        &["position", "direction", "intensity", "coverage_angle", "falloff_angle"];
    const ONLY_SAMPLED: bool = true;

    fn read(p: &Params, _: &dyn Resources) -> Result<Self, ParamError> {
        let position = p.vec3("position")?;
        let intensity = p.color("intensity")?;
        let direction = p.direction("direction")?;
        let coverage = p.number("coverage_angle")?;
        let falloff = p.number("falloff_angle")?;
        let ok = coverage > 0.0 && coverage <= 360.0;
        p.require(ok, "coverage_angle", coverage, "an angle in degrees, > 0 and <= 360")?;
        let requirement =
            format!("an angle in degrees, >= 0 and <= {}", p.spelling("coverage_angle"));
        p.require(falloff >= 0.0 && falloff <= coverage, "falloff_angle", falloff, &requirement)?;
        Ok(Spot {
            position,
            direction,
            intensity,
            coverage_degrees: coverage,
            falloff_degrees: falloff,
        })
    }

    fn write(&self, out: &mut dyn ParamSink) {
        out.vec3("position", self.position);
        out.vec3("direction", self.direction);
        out.color("intensity", self.intensity);
        out.number("coverage_angle", self.coverage_degrees);
        out.number("falloff_angle", self.falloff_degrees);
    }

    fn translate(&mut self, offset: DVec3) {
        self.position += offset;
    }

    fn reach(&self, origin: DVec3) -> f64 {
        distance(self.position, origin)
    }

    fn compile(&self, render_from_world: &DAffine3, parts: &mut LightParts) {
        let half_cos = |degrees: f64| (0.5 * degrees).to_radians().cos() as f32;
        parts.points.push(PointLight {
            position: render_from_world.transform_point3(self.position).as_vec3(),
            intensity: self.intensity,
            spot: Some(SpotCone {
                axis: render_from_world.transform_vector3(self.direction).normalize().as_vec3(),
                cos_falloff: half_cos(self.falloff_degrees),
                cos_coverage: half_cos(self.coverage_degrees),
            }),
        });
    }
}

/// A spot light's cone in render space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotCone {
    /// Unit axis, from the light into the scene.
    pub axis: Vec3,
    /// cos(falloff / 2): full intensity within.
    pub cos_falloff: f32,
    /// cos(coverage / 2): no light beyond.
    pub cos_coverage: f32,
}

impl SpotCone {
    /// The fraction of the axis intensity sent along the unit direction `w` (from the light).
    pub fn factor(&self, w: Vec3) -> f32 {
        let cos = self.axis.dot(w);
        if cos >= self.cos_falloff {
            1.0
        } else if cos > self.cos_coverage {
            ((cos - self.cos_coverage) / (self.cos_falloff - self.cos_coverage)).powi(4)
        } else {
            0.0
        }
    }
}
