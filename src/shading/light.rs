//! Lights in render space: point and directional lights (one shadow ray each) and emissive
//! primitives, which are sampled by area in proportion to their emitted power. Emitters
//! without geometry (the course's area lights) are sampled the same way but never hit.

use crate::color::luminance;
use crate::float_error::{TrianglePlane, gamma, triangle_point};
use crate::sampling::alias::AliasTable;
use crate::sampling::uniform_triangle;
use glam::{Vec2, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub struct PointLight {
    pub position: Vec3,
    /// Radiant intensity (W/sr) per channel.
    pub intensity: Vec3,
}

#[derive(Clone, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Unit direction the light travels in.
    pub direction: Vec3,
    /// Irradiance on a surface facing the light.
    pub irradiance: Vec3,
}

/// One emitting primitive, in render space.
#[derive(Clone, Debug, PartialEq)]
pub enum EmitterShape {
    Triangle([Vec3; 3]),
    Sphere {
        center: Vec3,
        radius: f32,
    },
    /// A geometry-less square (the course's area light): `center ± edge_u ± edge_v`, with
    /// `edge_u`, `edge_v` half an edge long and perpendicular to `normal` (unit length).
    /// It emits on both sides.
    Square {
        center: Vec3,
        edge_u: Vec3,
        edge_v: Vec3,
        normal: Vec3,
    },
}

/// `Emitter::geom_id` of an emitter that is no scene geometry (rays never hit it).
pub const NO_GEOMETRY: u32 = u32::MAX;

#[derive(Clone, Debug, PartialEq)]
pub struct Emitter {
    pub geom_id: u32,
    pub shape: EmitterShape,
    pub emission: Vec3,
    pub area: f32,
}

/// A point sampled on an emitter.
#[derive(Clone, Copy, Debug)]
pub struct EmitterSample {
    pub point: Vec3,
    /// Rounding-error bound of `point`, so shadow rays can stop safely short of it.
    pub error: Vec3,
    /// Unit surface normal at `point`.
    pub normal: Vec3,
    pub emission: Vec3,
    /// Probability density of choosing this point, per unit area (includes the choice of
    /// emitter).
    pub pdf_area: f32,
    pub geom_id: u32,
    /// Whether rays can hit the emitter. An invisible one (`NO_GEOMETRY`) is only ever
    /// found by light sampling, which then gets full weight.
    pub visible: bool,
    /// Emits on both sides (the course's area lights), not only where `normal` points.
    pub two_sided: bool,
}

impl EmitterSample {
    /// The cosine at which light leaves the emitter towards `towards` (a unit direction
    /// from the sampled point): negative where a one-sided emitter sends nothing.
    pub fn emitted_cosine(&self, towards: Vec3) -> f32 {
        let cos = self.normal.dot(towards);
        if self.two_sided { cos.abs() } else { cos }
    }
}

#[derive(Clone, Debug, Default)]
pub struct LightSet {
    pub points: Vec<PointLight>,
    pub directional: Vec<DirectionalLight>,
    /// Ambient radiance (used by the Whitted integrator only).
    pub ambient: Vec3,
    pub emitters: Vec<Emitter>,
    /// Picks emitters in proportion to their power.
    selection: Option<AliasTable>,
    /// Per instance: index of its first emitter (emitter of primitive p = first + p).
    first_emitter: Vec<Option<u32>>,
}

impl LightSet {
    /// Point, directional and emitting-primitive lights; `first_emitter[i]` is the index of
    /// instance i's first emitter (its primitive p is emitter first + p).
    pub fn new(
        points: Vec<PointLight>,
        directional: Vec<DirectionalLight>,
        emitters: Vec<Emitter>,
        first_emitter: Vec<Option<u32>>,
    ) -> Self {
        let mut set = LightSet {
            points,
            directional,
            ambient: Vec3::ZERO,
            emitters,
            selection: None,
            first_emitter,
        };
        set.build_selection();
        set
    }

    /// The table that picks emitters by power; drops them all if none emits.
    fn build_selection(&mut self) {
        let powers = self.emitters.iter().map(|e| {
            let sides = if matches!(e.shape, EmitterShape::Square { .. }) { 2.0 } else { 1.0 };
            sides * e.area as f64 * luminance(e.emission) as f64
        });
        self.selection = AliasTable::new(powers);
        if self.selection.is_none() {
            self.emitters.clear();
            self.first_emitter.iter_mut().for_each(|f| *f = None);
        }
    }

    pub fn has_emitters(&self) -> bool {
        !self.emitters.is_empty()
    }

    pub fn has_delta_lights(&self) -> bool {
        !self.points.is_empty() || !self.directional.is_empty()
    }

    fn emitter_probability(&self, index: usize) -> f32 {
        self.selection.as_ref().map_or(0.0, |t| t.pmf(index) as f32)
    }

    /// Density per unit area with which `sample_emitter` picks a point on primitive `prim`
    /// of instance `geom_id`; `None` if that primitive is not sampled (its emission must be
    /// counted in full wherever a ray hits it).
    pub fn pdf_area(&self, geom_id: u32, prim: u32) -> Option<f32> {
        let first = (*self.first_emitter.get(geom_id as usize)?)?;
        let index = (first + prim) as usize;
        let emitter = self.emitters.get(index)?;
        (emitter.geom_id == geom_id && emitter.area > 0.0)
            .then(|| self.emitter_probability(index) / emitter.area)
    }

    /// Picks an emitter in proportion to its power (with the two numbers of `pick`, see
    /// `AliasTable::sample`) and a point on it uniformly by area (with `on_surface`).
    pub fn sample_emitter(&self, pick: Vec2, on_surface: Vec2) -> Option<EmitterSample> {
        let index = self.selection.as_ref()?.sample(pick.to_array());
        let emitter = &self.emitters[index];
        let probability = self.emitter_probability(index);
        if probability <= 0.0 || emitter.area <= 0.0 {
            return None;
        }
        let (point, error, normal) = match emitter.shape {
            EmitterShape::Triangle(tri) => {
                let b = uniform_triangle(on_surface);
                let plane = TrianglePlane::new(&tri);
                let (point, error) = triangle_point(&tri, &plane, b.x, b.y);
                (point, error, plane.normal)
            }
            EmitterShape::Sphere { center, radius } => {
                let z = 1.0 - 2.0 * on_surface.x;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = 2.0 * std::f32::consts::PI * on_surface.y;
                let n = Vec3::new(r * phi.cos(), r * phi.sin(), z);
                let local = radius * n;
                let error = local.abs() * gamma(5)
                    + (center.abs() + local.abs()) * gamma(1)
                    + Vec3::splat(radius * gamma(8));
                (center + local, error, n)
            }
            EmitterShape::Square { center, edge_u, edge_v, normal } => {
                let (a, b) = (2.0 * on_surface.x - 1.0, 2.0 * on_surface.y - 1.0);
                let (du, dv) = (edge_u * a, edge_v * b);
                let point = center + du + dv;
                let error = (center.abs() + du.abs() + dv.abs()) * gamma(3);
                (point, error, normal)
            }
        };
        Some(EmitterSample {
            point,
            error,
            normal,
            emission: emitter.emission,
            pdf_area: probability / emitter.area,
            geom_id: emitter.geom_id,
            visible: emitter.geom_id != NO_GEOMETRY,
            two_sided: matches!(emitter.shape, EmitterShape::Square { .. }),
        })
    }
}
