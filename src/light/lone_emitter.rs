//! A scene's one flat emitter (a triangle or a parallelogram), sampled by area in select
//! form: the numbers `LightSet::sample_emitter` gives where it samples by area (far from
//! the emitter), computed by the same operations in the same order, but written so that
//! the loop over the Lambertian lanes vectorises it. The emitter sample is then made for
//! many paths at once instead of one chain of dependent operations per path.

use super::emitter::NearSphere;
use super::shape_sample::solid_angle_density;
use super::{EmitterShape, LightSet, NO_GEOMETRY};
use crate::float_error::{TrianglePlane, triangle_point};
use crate::lane_select::{select, select3};
use crate::sampling::uniform_triangle;
use glam::{Vec2, Vec3};

/// The emitter: a copy of what deciding how a point is sampled, and sampling it by area,
/// need.
#[derive(Clone, Debug)]
pub struct LoneEmitter {
    pub sampler: AreaSampler,
}

/// What sampling the lone emitter by area needs, copied out of the light set: small and
/// `Copy`, so that the lanes' loop gets it as its own argument (loads from it then alias
/// none of the loop's stores, which it vectorises only if it can tell).
#[derive(Clone, Copy, Debug)]
pub struct AreaSampler {
    /// Whether the emitter is a parallelogram (else a triangle).
    quad: bool,
    /// The triangles a point is computed on: the triangle's, or the parallelogram's two
    /// (`EmitterShape::Quad`).
    triangles: [[Vec3; 3]; 2],
    planes: [TrianglePlane; 2],
    inverse_area: f32,
    /// The chance that the light set picks it (1, unless it emits nothing).
    probability: f32,
    pub emission: Vec3,
    pub visible: bool,
    pub two_sided: bool,
    /// The shape's `NearSphere`, within which `sample_emitter` samples by solid angle.
    near: NearSphere,
}

/// A point sampled by area on the emitter: its error bound, and the density per unit
/// solid angle (light choice included) at the shading point; 0 where `sample_emitter`
/// finds none.
#[derive(Clone, Copy, Debug)]
pub struct AreaSample {
    pub point: Vec3,
    pub error: Vec3,
    pub normal: Vec3,
    pub pdf: f32,
}

impl LightSet {
    /// The scene's emitter, if it has exactly one and it is flat and emits.
    pub fn lone_emitter(&self) -> Option<LoneEmitter> {
        // The lanes take one radiance for all of an emitter: a textured one is sampled by
        // `sample_emitter`, which looks its texture up.
        let [emitter] = &self.emitters[..] else { return None };
        if emitter.emission_map.is_some() {
            return None;
        }
        let probability = self.emitter_probability(0);
        if !(probability > 0.0 && emitter.area > 0.0) {
            return None;
        }
        let (quad, triangles, planes, near) = match &emitter.shape {
            EmitterShape::Triangle { vertices, plane, near, .. } => {
                (false, [*vertices; 2], [*plane; 2], *near)
            }
            EmitterShape::Quad { vertices: [v0, v1, v2, v3], planes, near, .. } => {
                (true, [[*v0, *v1, *v3], [*v2, *v3, *v1]], *planes, *near)
            }
            EmitterShape::Sphere(_) | EmitterShape::Ellipsoid(_) => return None,
        };
        let sampler = AreaSampler {
            quad,
            triangles,
            planes,
            inverse_area: 1.0 / emitter.shape.area(),
            probability,
            emission: emitter.emission,
            visible: emitter.geom_id != NO_GEOMETRY,
            two_sided: emitter.two_sided,
            near,
        };
        Some(LoneEmitter { sampler })
    }
}

impl AreaSampler {
    /// Whether `sample_emitter` samples a point from `reference` by area (rather than by
    /// solid angle, or not at all behind a one-sided emitter).
    #[inline(always)]
    pub fn by_area(&self, reference: Vec3) -> bool {
        !self.behind(reference) && !self.is_near(reference)
    }

    /// Whether `reference` is behind the emitter, one-sided, so that `sample_emitter` finds
    /// no light for it (the emitter is the light set's only one, and emits): the same
    /// operations as `EmitterShape::is_behind` (both shapes' first triangle starts at their
    /// first vertex and has their normal).
    #[inline(always)]
    pub fn behind(&self, reference: Vec3) -> bool {
        !self.two_sided && !((reference - self.triangles[0][0]).dot(self.planes[0].normal) > 0.0)
    }

    /// `EmitterShape::is_near`.
    #[inline(always)]
    pub fn is_near(&self, reference: Vec3) -> bool {
        self.near.contains(reference)
    }

    /// The point `sample_emitter(reference, _, u)` samples where `by_area(reference)`.
    #[inline(always)]
    pub fn sample_by_area(&self, reference: Vec3, u: Vec2) -> AreaSample {
        let second = self.quad && u.x + u.y > 1.0;
        // A parallelogram's point is computed on the triangle that holds it; a triangle's
        // barycentrics come from Heitz's low-distortion map.
        let b = if self.quad { u } else { uniform_triangle(u) };
        let (s, t) = (select(second, 1.0 - b.x, b.x), select(second, 1.0 - b.y, b.y));
        let [first_triangle, second_triangle] = &self.triangles;
        let triangle: [Vec3; 3] =
            std::array::from_fn(|i| select3(second, second_triangle[i], first_triangle[i]));
        let [first_plane, second_plane] = &self.planes;
        let plane = TrianglePlane {
            e1: select3(second, second_plane.e1, first_plane.e1),
            e2: select3(second, second_plane.e2, first_plane.e2),
            normal: select3(second, second_plane.normal, first_plane.normal),
            tilt: select(second, second_plane.tilt, first_plane.tilt),
            edge_tilt: select(second, second_plane.edge_tilt, first_plane.edge_tilt),
        };
        let (point, error) = triangle_point(&triangle, &plane, s, t);
        let normal = first_plane.normal;
        let shape_pdf = solid_angle_density(self.inverse_area, reference, point, normal);
        let pdf = self.probability * shape_pdf;
        let found = shape_pdf > 0.0 && pdf > 0.0 && pdf.is_finite();
        AreaSample { point, error, normal, pdf: select(found, pdf, 0.0) }
    }
}

#[cfg(test)]
#[path = "lone_emitter_tests.rs"]
mod tests;
