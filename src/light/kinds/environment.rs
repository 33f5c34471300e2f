//! Radiance from every direction far away: an image (`file`, mapped onto the sphere by
//! `mapping`, see `env_mapping`) or a constant `radiance`, times `scale`. Rays that leave
//! the scene see it in place of the background; a scene takes at most one.

use super::{LightKind, LightParts};
use crate::light::{EnvironmentLight, EnvironmentMapping, TexelLookup};
use crate::params::{ParamError, ParamSink, Params, Resources, show_large_vec};
use crate::texels::TextureImage;
use crate::transform::nearest_rotation;
use glam::{DAffine3, DMat3, Vec3};
use std::sync::Arc;

#[derive(Clone, Debug, PartialEq)]
pub struct Environment {
    pub map: EnvironmentMap,
    pub scale: Vec3,
    pub mapping: EnvironmentMapping,
    /// The map's orientation: a rotation from the map's frame (in which `mapping` holds) to
    /// the world (`to_world`, row by row; identity by default).
    pub world_from_map: DMat3,
    /// How directions read the image (`interpolation`: nearest, or Mitsuba's bilinear).
    pub lookup: TexelLookup,
}

/// What an environment light's radiance comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum EnvironmentMap {
    /// The same radiance from every direction.
    Constant(Vec3),
    /// An image of linear radiances.
    Image(Arc<TextureImage>),
}

const ENCODINGS: [(&str, bool); 2] = [("srgb", true), ("raw", false)];
const LOOKUPS: [(&str, TexelLookup); 2] =
    [("nearest", TexelLookup::Nearest), ("bilinear_poles", TexelLookup::BilinearPoles)];
const MAPPINGS: [(&str, EnvironmentMapping); 2] =
    [("latlong", EnvironmentMapping::LatLong), ("probe", EnvironmentMapping::Probe)];

impl LightKind for Environment {
    const NAME: &'static str = "environment";
    const LABEL: &'static str = "environment light";
    const FIELDS: &'static [&'static str] =
        &["file", "radiance", "scale", "encoding", "mapping", "to_world", "interpolation"];
    const ONE_PER_SCENE: bool = true;

    const SAMPLES_ITS_IMAGE: bool = true;

    fn image(&self) -> Option<&Arc<TextureImage>> {
        match &self.map {
            EnvironmentMap::Image(image) => Some(image),
            EnvironmentMap::Constant(_) => None,
        }
    }

    fn read(p: &Params, resources: &dyn Resources) -> Result<Self, ParamError> {
        let encoding = p.opt_choice("encoding", &ENCODINGS)?;
        let map = match (p.has("file"), p.has("radiance")) {
            (true, true) => return Err(p.conflict("file", "radiance")),
            (false, false) => return Err(p.missing("file (or radiance)")),
            (false, true) => {
                p.require(encoding.is_none(), "encoding", "given", "given only with file")?;
                EnvironmentMap::Constant(p.color("radiance")?)
            }
            (true, false) => {
                let image = resources.radiance_image(p, "file", encoding.unwrap_or(true))?;
                let requirement = "given only for PNG and JPEG files (EXR values are linear)";
                p.require(!(image.hdr && encoding.is_some()), "encoding", "given", requirement)?;
                EnvironmentMap::Image(image)
            }
        };
        let scale = p.opt_color("scale")?.unwrap_or(Vec3::ONE);
        // Scaled past f32's range, a radiance would be dropped as non-finite: the light
        // would vanish without a word.
        let brightest = match &map {
            EnvironmentMap::Constant(radiance) => *radiance,
            EnvironmentMap::Image(image) => image.texels.iter().fold(Vec3::ZERO, |a, t| a.max(*t)),
        };
        // Its importance distribution sums the scaled texels' luminance × solid angle in f32,
        // up to the brightest one's 4π: past f32's range that total becomes infinite and the
        // map's sampling wrong (a 1e38 texel lit a scene 20× less than a 1e37 one).
        let sphere = 4.0 * std::f32::consts::PI;
        let finite = (brightest * scale * sphere).is_finite();
        let requirement =
            "small enough that 4π × scale × radiance stays within f32's range (3.4e38)";
        // Named where the size comes from: the scale, or else the radiance or image itself.
        let (field, value) = match &map {
            _ if scale.max_element() > 1.0 => ("scale", show_large_vec(scale)),
            EnvironmentMap::Constant(_) => ("radiance", show_large_vec(brightest)),
            EnvironmentMap::Image(_) => {
                let brightest = show_large_vec(brightest);
                ("file", format!("an image whose brightest texel is {brightest}"))
            }
        };
        p.require(finite, field, value, requirement)?;
        let mapping = p.opt_choice("mapping", &MAPPINGS)?;
        p.require(mapping.is_none() || p.has("file"), "mapping", "given", "given only with file")?;
        let world_from_map = match p.numbers::<9>("to_world")? {
            Some(rows) => {
                let rotation = nearest_rotation(DMat3::from_cols_array(&rows).transpose());
                p.require(
                    rotation.is_some(),
                    "to_world",
                    format!("{rows:?}"),
                    "a rotation (9 numbers, row by row; no scale, shear or mirror)",
                )?;
                rotation.unwrap_or(DMat3::IDENTITY)
            }
            None => DMat3::IDENTITY,
        };
        let lookup = p.opt_choice("interpolation", &LOOKUPS)?.unwrap_or_default();
        let mapping = mapping.unwrap_or_default();
        Ok(Environment { map, scale, mapping, world_from_map, lookup })
    }

    fn write(&self, out: &mut dyn ParamSink) {
        match &self.map {
            EnvironmentMap::Constant(radiance) => out.color("radiance", *radiance),
            EnvironmentMap::Image(image) => {
                out.path("file", &image.file);
                if !image.hdr {
                    out.text("encoding", if image.srgb_decoded { "srgb" } else { "raw" });
                }
                out.text("mapping", &self.mapping.to_string());
            }
        }
        out.color("scale", self.scale);
        if self.lookup != TexelLookup::Nearest {
            let name = LOOKUPS.iter().find(|(_, l)| *l == self.lookup).map_or("nearest", |l| l.0);
            out.text("interpolation", name);
        }
        if self.world_from_map != DMat3::IDENTITY {
            out.numbers("to_world", &self.world_from_map.transpose().to_cols_array());
        }
    }

    fn compile(&self, render_from_world: &DAffine3, parts: &mut LightParts) {
        // Directions are looked up in the map's frame: render space only rotates back to
        // the world, and the map's orientation is a rotation from there.
        let world_from_render = render_from_world.matrix3.inverse();
        let world_from_render = (self.world_from_map.transpose() * world_from_render).as_mat3();
        parts.environment = Some(match &self.map {
            EnvironmentMap::Constant(radiance) => EnvironmentLight::new(
                1,
                1,
                &[*radiance],
                self.scale,
                EnvironmentMapping::LatLong,
                world_from_render,
            ),
            EnvironmentMap::Image(image) => EnvironmentLight::new(
                image.width as usize,
                image.height as usize,
                &image.texels,
                self.scale,
                self.mapping,
                world_from_render,
            )
            .with_lookup(self.lookup),
        });
    }
}
