//! The course's AreaLight: a square of side `size` centred at `center`, facing `normal`
//! (unit), emitting `radiance` on both sides. It lights the scene (sampled by area) but has
//! no geometry: rays never hit it, so the camera does not see it.

use super::{LightKind, LightParts, distance};
use crate::light::{Emitter, EmitterShape, NO_GEOMETRY};
use crate::params::{ParamError, ParamSink, Params, Resources};
use crate::transform::course_square_axes;
use glam::{DAffine3, DVec3, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub struct Area {
    pub center: DVec3,
    pub normal: DVec3,
    pub size: f64,
    pub radiance: Vec3,
}

impl LightKind for Area {
    const NAME: &'static str = "area";
    const LABEL: &'static str = "area light";
    const FIELDS: &'static [&'static str] = &["center", "normal", "size", "radiance"];
    const ONLY_SAMPLED: bool = true;

    fn read(p: &Params, _: &dyn Resources) -> Result<Self, ParamError> {
        Ok(Area {
            center: p.vec3("center")?,
            normal: p.direction("normal")?,
            size: p.positive("size")?,
            radiance: p.color("radiance")?,
        })
    }

    fn write(&self, out: &mut dyn ParamSink) {
        out.vec3("center", self.center);
        out.vec3("normal", self.normal);
        out.number("size", self.size);
        out.color("radiance", self.radiance);
    }

    fn translate(&mut self, offset: DVec3) {
        self.center += offset;
    }

    fn reach(&self, origin: DVec3) -> f64 {
        distance(self.center, origin) + self.size
    }

    fn compile(&self, render_from_world: &DAffine3, parts: &mut LightParts) {
        let (u, v) = course_square_axes(self.normal);
        let half = 0.5 * self.size;
        let corner = |a: f64, b: f64| {
            let world = self.center + (a * u + b * v) * half;
            render_from_world.transform_point3(world).as_vec3()
        };
        let vertices = [corner(-1.0, -1.0), corner(1.0, -1.0), corner(1.0, 1.0), corner(-1.0, 1.0)];
        // A square whose corners round to a non-parallelogram (far from the origin) is
        // sampled as two triangles.
        match EmitterShape::quad(vertices) {
            Some(shape) => {
                parts.invisible.push(Emitter::new(NO_GEOMETRY, shape, self.radiance, true))
            }
            None => {
                let [v0, v1, v2, v3] = vertices;
                for tri in [[v0, v1, v3], [v2, v3, v1]] {
                    let shape = EmitterShape::triangle(tri);
                    parts.invisible.push(Emitter::new(NO_GEOMETRY, shape, self.radiance, true));
                }
            }
        }
    }
}
