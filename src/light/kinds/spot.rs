//! A point light that sends its light into a cone around `direction` (unit, from the light
//! into the scene): the course's SpotLight. Full `intensity` within half the
//! `falloff_degrees` of the axis, none beyond half the `coverage_degrees`, and in between
//! `intensity` times ((cos α − cos(coverage/2)) / (cos(falloff/2) − cos(coverage/2)))⁴.
//! (hw5.tex prints cos(falloff/2) as the first term, which makes the light drop to 0 just
//! outside the falloff cone and jump back to full at the coverage edge, against its own
//! description: "diminish non-linearly" from the first to the second. The pack has no
//! SpotLight reference to settle it.)
//!
//! With `profile = "linear"` the light falls off as Mitsuba's `spot` does instead: linearly
//! in the angle, from full at half the falloff angle to none at half the coverage angle.
//! A `texture` (an image) is projected through the cone as Mitsuba projects it: the point
//! (u, v) = ½ + ½ (x, y) / (z tan(coverage/2)) of the image in the light's frame, x
//! along `up × direction` and y along `direction × x`.

use super::{LightKind, LightParts, distance};
use crate::light::PointLight;
use crate::params::{ParamError, ParamSink, Params, Resources};
use crate::texels::TextureImage;
use glam::{DAffine3, DVec3, Vec2, Vec3};
use std::sync::Arc;

/// How the light falls off between the falloff and coverage cones.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SpotProfile {
    /// The course's: the fourth power of the normalised cosine.
    #[default]
    Course,
    /// Mitsuba's: linear in the angle.
    Linear,
}

const PROFILES: [(&str, SpotProfile); 2] =
    [("course", SpotProfile::Course), ("linear", SpotProfile::Linear)];

#[derive(Clone, Debug, PartialEq)]
pub struct Spot {
    pub position: DVec3,
    pub direction: DVec3,
    pub intensity: Vec3,
    pub coverage_degrees: f64,
    pub falloff_degrees: f64,
    pub profile: SpotProfile,
    /// An image projected through the cone, and the `up` that orients it.
    pub texture: Option<(Arc<TextureImage>, DVec3)>,
}

impl LightKind for Spot {
    const NAME: &'static str = "spot";
    const LABEL: &'static str = "spot light";
    const FIELDS: &'static [&'static str] = &[
        "position",
        "direction",
        "intensity",
        "coverage_angle",
        "falloff_angle",
        "profile",
        "texture",
        "up",
    ];
    const ONLY_SAMPLED: bool = true;

    fn image(&self) -> Option<&Arc<TextureImage>> {
        self.texture.as_ref().map(|(image, _)| image)
    }

    fn read(p: &Params, resources: &dyn Resources) -> Result<Self, ParamError> {
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
        let profile = p.opt_choice("profile", &PROFILES)?.unwrap_or_default();
        let texture = match p.has("texture") {
            false => None,
            true => {
                let ok = coverage < 180.0;
                p.require(ok, "coverage_angle", coverage, "< 180 for a projected texture")?;
                let up = match p.opt_vec3("up")? {
                    Some(_) => p.direction("up")?,
                    None => DVec3::Y,
                };
                let across = up.cross(direction).length();
                p.require(across > 1e-9, "up", "parallel to the direction", "not parallel")?;
                Some((resources.radiance_image(p, "texture", true)?, up))
            }
        };
        Ok(Spot {
            position,
            direction,
            intensity,
            coverage_degrees: coverage,
            falloff_degrees: falloff,
            profile,
            texture,
        })
    }

    fn write(&self, out: &mut dyn ParamSink) {
        out.vec3("position", self.position);
        out.vec3("direction", self.direction);
        out.color("intensity", self.intensity);
        out.number("coverage_angle", self.coverage_degrees);
        out.number("falloff_angle", self.falloff_degrees);
        if self.profile != SpotProfile::Course {
            out.text("profile", "linear");
        }
        if let Some((image, up)) = &self.texture {
            out.path("texture", &image.file);
            out.vec3("up", *up);
        }
    }

    fn translate(&mut self, offset: DVec3) {
        self.position += offset;
    }

    fn reach(&self, origin: DVec3) -> f64 {
        distance(self.position, origin)
    }

    fn compile(&self, render_from_world: &DAffine3, parts: &mut LightParts) {
        let half = |degrees: f64| (0.5 * degrees).to_radians();
        let axis = render_from_world.transform_vector3(self.direction).normalize();
        let texture = self.texture.as_ref().map(|(image, up)| {
            let up = render_from_world.transform_vector3(*up);
            let x = up.cross(axis).normalize();
            let y = axis.cross(x);
            let tan = half(self.coverage_degrees).tan() as f32;
            SpotTexture { image: image.clone(), x: x.as_vec3(), y: y.as_vec3(), tan_coverage: tan }
        });
        parts.points.push(PointLight {
            position: render_from_world.transform_point3(self.position).as_vec3(),
            intensity: self.intensity,
            spot: Some(SpotCone {
                axis: axis.as_vec3(),
                cos_falloff: half(self.falloff_degrees).cos() as f32,
                cos_coverage: half(self.coverage_degrees).cos() as f32,
                profile: self.profile,
                angles: (half(self.falloff_degrees) as f32, half(self.coverage_degrees) as f32),
                texture,
            }),
            projection: None,
        });
    }
}

/// An image projected through a spot light's cone, in render space.
#[derive(Clone, Debug, PartialEq)]
pub struct SpotTexture {
    image: Arc<TextureImage>,
    /// The light's frame across the axis: image u grows along `x`, v along `y`.
    x: Vec3,
    y: Vec3,
    tan_coverage: f32,
}

/// A spot light's cone in render space.
#[derive(Clone, Debug, PartialEq)]
pub struct SpotCone {
    /// Unit axis, from the light into the scene.
    pub axis: Vec3,
    /// cos(falloff / 2): full intensity within.
    pub cos_falloff: f32,
    /// cos(coverage / 2): no light beyond.
    pub cos_coverage: f32,
    pub profile: SpotProfile,
    /// Half the falloff and coverage angles, in radians (the linear profile's ends).
    pub angles: (f32, f32),
    pub texture: Option<SpotTexture>,
}

impl SpotCone {
    /// A cone of the course's profile, without a texture.
    pub fn course(axis: Vec3, cos_falloff: f32, cos_coverage: f32) -> Self {
        SpotCone {
            axis,
            cos_falloff,
            cos_coverage,
            profile: SpotProfile::Course,
            angles: (cos_falloff.clamp(-1.0, 1.0).acos(), cos_coverage.clamp(-1.0, 1.0).acos()),
            texture: None,
        }
    }

    /// The fraction of the axis intensity sent along the unit direction `w` (from the light).
    pub fn factor(&self, w: Vec3) -> f32 {
        let cos = self.axis.dot(w);
        if cos >= self.cos_falloff {
            1.0
        } else if cos > self.cos_coverage {
            match self.profile {
                SpotProfile::Course => {
                    ((cos - self.cos_coverage) / (self.cos_falloff - self.cos_coverage)).powi(4)
                }
                SpotProfile::Linear => {
                    let (falloff, coverage) = self.angles;
                    (coverage - cos.clamp(-1.0, 1.0).acos()) / (coverage - falloff)
                }
            }
        } else {
            0.0
        }
    }

    /// The projected image's colour along `w` (white without one).
    pub fn tint(&self, w: Vec3) -> Vec3 {
        let Some(t) = &self.texture else { return Vec3::ONE };
        let z = self.axis.dot(w);
        if z <= 0.0 {
            return Vec3::ZERO;
        }
        let scale = 0.5 / (z * t.tan_coverage);
        let uv = Vec2::new(0.5 + t.x.dot(w) * scale, 0.5 + t.y.dot(w) * scale);
        t.image.centred_bilinear(uv)
    }
}
