//! Lights in render space: point and directional lights (one shadow ray each) and emissive
//! primitives, chosen in proportion to their emitted power and sampled from the shading
//! point (see `emitter`). Emitters without geometry (the course's area lights) are sampled
//! the same way but never hit.

mod ellipsoid;
mod emission_map;
mod emitter;
mod env_mapping;
mod environment;
pub mod kinds;
mod lone_emitter;
mod shape_sample;
mod sphere_shape;
#[cfg(test)]
mod tests;

pub use ellipsoid::Ellipsoid;
pub use emission_map::{EmissionMap, UvSource};
pub use emitter::EmitterShape;
pub use env_mapping::EnvironmentMapping;
pub use environment::{EnvironmentLight, EnvironmentSample, TexelLookup};
pub use kinds::{LightDesc, LightKind, LightParts, SpotCone};
pub use lone_emitter::{AreaSample, AreaSampler, LoneEmitter};
pub use shape_sample::ShapeSample;
pub use sphere_shape::SphereShape;

use crate::color::luminance;
use crate::sampling::alias::AliasTable;
use glam::{Vec2, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub struct PointLight {
    pub position: Vec3,
    /// Radiant intensity (W/sr) per channel (on the axis, for a spot light).
    pub intensity: Vec3,
    /// The cone a spot light shines into; `None` for an isotropic point light.
    pub spot: Option<SpotCone>,
    /// The image and frustum of a projector.
    pub projection: Option<kinds::Projection>,
}

impl PointLight {
    /// Whether its intensity is the same every way (no cone, no projected image).
    pub fn is_isotropic(&self) -> bool {
        self.spot.is_none() && self.projection.is_none()
    }

    /// Radiant intensity towards the unit direction `w` (from the light).
    pub fn intensity_towards(&self, w: Vec3) -> Vec3 {
        let intensity = match &self.spot {
            Some(cone) => {
                let factor = cone.factor(w);
                if factor > 0.0 { self.intensity * factor * cone.tint(w) } else { Vec3::ZERO }
            }
            None => self.intensity,
        };
        match &self.projection {
            Some(projection) => intensity * projection.factor(w),
            None => intensity,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Unit direction the light travels in.
    pub direction: Vec3,
    /// Irradiance on a surface facing the light.
    pub irradiance: Vec3,
}

/// `Emitter::geom_id` of an emitter that is no scene geometry (rays never hit it).
pub const NO_GEOMETRY: u32 = u32::MAX;

#[derive(Clone, Debug)]
pub struct Emitter {
    pub geom_id: u32,
    pub shape: EmitterShape,
    pub emission: Vec3,
    pub area: f32,
    /// Emits on both sides (the course's area lights), not only where its normal points.
    pub two_sided: bool,
    /// The texture `emission` is multiplied by, and where on the emitter it is looked up.
    pub emission_map: Option<Box<EmissionMap>>,
}

impl Emitter {
    pub fn new(geom_id: u32, shape: EmitterShape, emission: Vec3, two_sided: bool) -> Self {
        Emitter { geom_id, area: shape.area(), shape, emission, two_sided, emission_map: None }
    }

    /// This emitter with its emission textured by `map`.
    pub fn textured(self, map: Option<EmissionMap>) -> Self {
        Emitter { emission_map: map.map(Box::new), ..self }
    }

    /// The radiance it emits at `point`, a point on it.
    pub fn emission_at(&self, point: Vec3) -> Vec3 {
        match &self.emission_map {
            None => self.emission,
            Some(map) => map.radiance(self.emission, point),
        }
    }

    /// Its emission averaged over its texture's coordinates (for choosing among emitters).
    fn mean_emission(&self) -> Vec3 {
        self.emission * self.emission_map.as_ref().map_or(Vec3::ONE, |m| m.mean)
    }
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
    /// Probability density of choosing this point's direction, per unit solid angle at the
    /// shading point (includes the choice of emitter).
    pub pdf: f32,
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

/// Marks an instance without sampled emitters in `LightSet::first_prim`.
const NOT_SAMPLED: u32 = u32::MAX;

#[derive(Clone, Debug, Default)]
pub struct LightSet {
    pub points: Vec<PointLight>,
    pub directional: Vec<DirectionalLight>,
    /// Ambient radiance (used by the Whitted integrator only).
    pub ambient: Vec3,
    /// Light from every direction far away; rays that leave the scene see it.
    pub environment: Option<EnvironmentLight>,
    pub emitters: Vec<Emitter>,
    /// Picks emitters in proportion to their power.
    selection: Option<AliasTable>,
    /// Per instance: where its primitives start in `emitter_of_prim` (or `NOT_SAMPLED`).
    first_prim: Vec<u32>,
    /// The emitter that samples each primitive of the emissive instances.
    emitter_of_prim: Vec<u32>,
}

/// The emitters of the scene's instances: `emitters`, and for every instance whose
/// primitives are all sampled, the index in `emitters` of each primitive's emitter.
#[derive(Clone, Debug, Default)]
pub struct InstanceEmitters {
    pub emitters: Vec<Emitter>,
    pub by_instance: Vec<Option<Vec<u32>>>,
}

impl LightSet {
    /// Point, directional, instance emitters and emitters without geometry.
    pub fn new(
        points: Vec<PointLight>,
        directional: Vec<DirectionalLight>,
        instance_emitters: InstanceEmitters,
        unattached: Vec<Emitter>,
    ) -> Self {
        let InstanceEmitters { mut emitters, by_instance } = instance_emitters;
        emitters.extend(unattached);
        let mut first_prim = Vec::with_capacity(by_instance.len());
        let mut emitter_of_prim = Vec::new();
        for prims in by_instance {
            match prims {
                Some(prims) => {
                    first_prim.push(emitter_of_prim.len() as u32);
                    emitter_of_prim.extend(prims);
                }
                None => first_prim.push(NOT_SAMPLED),
            }
        }
        let mut set = LightSet {
            points,
            directional,
            ambient: Vec3::ZERO,
            environment: None,
            emitters,
            selection: None,
            first_prim,
            emitter_of_prim,
        };
        set.build_selection();
        set
    }

    /// The table that picks emitters by power; drops them all if none emits.
    fn build_selection(&mut self) {
        let powers = self.emitters.iter().map(|e| {
            let sides = if e.two_sided { 2.0 } else { 1.0 };
            sides * e.area as f64 * luminance(e.mean_emission()) as f64
        });
        self.selection = AliasTable::new(powers);
        if self.selection.is_none() {
            self.emitters.clear();
            self.emitter_of_prim.clear();
            self.first_prim.iter_mut().for_each(|f| *f = NOT_SAMPLED);
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

    /// The emitter that samples primitive `prim` of instance `geom_id`, if any.
    fn emitter_of(&self, geom_id: u32, prim: u32) -> Option<usize> {
        let first = *self.first_prim.get(geom_id as usize)?;
        if first == NOT_SAMPLED {
            return None;
        }
        let index = *self.emitter_of_prim.get(first as usize + prim as usize)? as usize;
        (self.emitters.get(index)?.geom_id == geom_id).then_some(index)
    }

    /// Density per unit solid angle at `reference` with which `sample_emitter` picks `point`
    /// (normal `normal`) on primitive `prim` of instance `geom_id`; `None` if that primitive
    /// is not sampled (its emission must be counted in full wherever a ray hits it).
    pub fn pdf(
        &self,
        reference: Vec3,
        geom_id: u32,
        prim: u32,
        point: Vec3,
        normal: Vec3,
    ) -> Option<f32> {
        let index = self.emitter_of(geom_id, prim)?;
        let emitter = &self.emitters[index];
        (emitter.area > 0.0).then(|| {
            self.emitter_probability(index) * emitter.shape.pdf_from(reference, point, normal)
        })
    }

    /// Picks an emitter in proportion to its power (with the two numbers of `pick`, see
    /// `AliasTable::sample`) and a point on it as seen from `reference` (with `on_surface`).
    pub fn sample_emitter(
        &self,
        reference: Vec3,
        pick: Vec2,
        on_surface: Vec2,
    ) -> Option<EmitterSample> {
        let index = self.selection.as_ref()?.sample(pick.to_array());
        let emitter = &self.emitters[index];
        let probability = self.emitter_probability(index);
        if probability <= 0.0 || emitter.area <= 0.0 {
            return None;
        }
        // Behind a one-sided emitter nothing arrives: skip the sampling work.
        if emitter.shape.is_behind(emitter.two_sided, reference) {
            return None;
        }
        let sample = emitter.shape.sample_from(reference, on_surface)?;
        let pdf = probability * sample.pdf;
        if !(pdf > 0.0) || !pdf.is_finite() {
            return None;
        }
        Some(EmitterSample {
            point: sample.point,
            error: sample.error,
            normal: sample.normal,
            emission: emitter.emission_at(sample.point),
            pdf,
            geom_id: emitter.geom_id,
            visible: emitter.geom_id != NO_GEOMETRY,
            two_sided: emitter.two_sided,
        })
    }
}
