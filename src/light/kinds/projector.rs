//! A slide projector: a point light that sends an image into the scene through a pinhole,
//! as Mitsuba's `projector`. `fov` is the image's horizontal angle (its height follows the
//! image's aspect), `up` orients it, and `scale` the irradiance it casts: `scale` times the
//! image on a plane facing the projector at distance 1, so its intensity along a direction
//! at θ from the axis is scale · image(u, v) / cos³θ. Without an image it projects a
//! square of `scale`.

use super::{LightKind, LightParts, distance};
use crate::light::PointLight;
use crate::params::{ParamError, ParamSink, Params, Resources};
use crate::texels::TextureImage;
use glam::{DAffine3, DVec3, Vec2, Vec3};
use std::sync::Arc;

#[derive(Clone, Debug, PartialEq)]
pub struct Projector {
    pub position: DVec3,
    pub direction: DVec3,
    pub up: DVec3,
    pub fov_degrees: f64,
    pub image: Option<Arc<TextureImage>>,
    pub scale: Vec3,
}

impl LightKind for Projector {
    const NAME: &'static str = "projector";
    const LABEL: &'static str = "projector";
    const FIELDS: &'static [&'static str] =
        &["position", "direction", "up", "fov", "image", "scale"];
    const ONLY_SAMPLED: bool = true;

    fn image(&self) -> Option<&Arc<TextureImage>> {
        self.image.as_ref()
    }

    fn read(p: &Params, resources: &dyn Resources) -> Result<Self, ParamError> {
        let position = p.vec3("position")?;
        let direction = p.direction("direction")?;
        let up = match p.opt_vec3("up")? {
            Some(_) => p.direction("up")?,
            None => DVec3::Y,
        };
        p.require(
            up.cross(direction).length() > 1e-9,
            "up",
            "parallel",
            "not parallel to direction",
        )?;
        let fov = p.number("fov")?;
        p.require(fov > 0.0 && fov < 180.0, "fov", fov, "an angle in degrees, > 0 and < 180")?;
        let image = match p.has("image") {
            true => Some(resources.radiance_image(p, "image", true)?),
            false => None,
        };
        let scale = p.opt_color("scale")?.unwrap_or(Vec3::ONE);
        Ok(Projector { position, direction, up, fov_degrees: fov, image, scale })
    }

    fn write(&self, out: &mut dyn ParamSink) {
        out.vec3("position", self.position);
        out.vec3("direction", self.direction);
        out.vec3("up", self.up);
        out.number("fov", self.fov_degrees);
        if let Some(image) = &self.image {
            out.path("image", &image.file);
        }
        out.color("scale", self.scale);
    }

    fn translate(&mut self, offset: DVec3) {
        self.position += offset;
    }

    fn reach(&self, origin: DVec3) -> f64 {
        distance(self.position, origin)
    }

    fn compile(&self, render_from_world: &DAffine3, parts: &mut LightParts) {
        let axis = render_from_world.transform_vector3(self.direction).normalize();
        let up = render_from_world.transform_vector3(self.up);
        let left = up.cross(axis).normalize();
        let tan_x = (0.5 * self.fov_degrees).to_radians().tan() as f32;
        let aspect = self.image.as_ref().map_or(1.0, |i| i.width as f32 / i.height as f32);
        parts.points.push(PointLight {
            position: render_from_world.transform_point3(self.position).as_vec3(),
            intensity: self.scale,
            spot: None,
            projection: Some(Projection {
                image: self.image.clone(),
                axis: axis.as_vec3(),
                left: left.as_vec3(),
                up: axis.cross(left).as_vec3(),
                tan_x,
                tan_y: tan_x / aspect,
            }),
        });
    }
}

/// A projector's image and frustum in render space.
#[derive(Clone, Debug, PartialEq)]
pub struct Projection {
    image: Option<Arc<TextureImage>>,
    axis: Vec3,
    left: Vec3,
    up: Vec3,
    /// Tangents of half the horizontal and vertical angles.
    tan_x: f32,
    tan_y: f32,
}

impl Projection {
    /// The factor on the light's intensity along the unit direction `w`: the image there
    /// over cos³θ (an irradiance that is the image's on the plane at distance 1), or 0
    /// outside the frustum.
    pub fn factor(&self, w: Vec3) -> Vec3 {
        let z = self.axis.dot(w);
        if z <= 0.0 {
            return Vec3::ZERO;
        }
        let u = 0.5 - 0.5 * self.left.dot(w) / (z * self.tan_x);
        let v = 0.5 - 0.5 * self.up.dot(w) / (z * self.tan_y);
        if !((0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v)) {
            return Vec3::ZERO;
        }
        let texel = self.image.as_ref().map_or(Vec3::ONE, |i| i.centred_bilinear(Vec2::new(u, v)));
        texel / (z * z * z)
    }
}
