//! Emitters outside shapes: point, directional, constant and envmap, read by embray's light
//! kinds from Mitsuba's parameters (the names agree; `to_world` placements are turned into
//! the position or direction they mean).

use super::Builder;
use super::sensor::property;
use super::transform::transform;
use super::tree::Element;
use super::values::{ColorUse, params};
use crate::light::LightDesc;
use crate::params::{Entry, ParamError, Params, Resources, Value};
use crate::scene::error::SceneError;
use crate::texels::TextureImage;
use glam::DVec3;
use std::sync::Arc;

impl Builder<'_> {
    pub(super) fn emitter(&mut self, element: &Element) -> Result<(), SceneError> {
        let kind = element.required("type")?;
        let mut p = params(element, &[], ColorUse::Emission)?;
        let to_world = match property(element, "transform", "to_world") {
            Some(t) => Some(transform(t)?),
            None => None,
        };
        let set = |p: &mut Params, name: &str, v: DVec3| {
            p.push(Entry {
                name: name.to_owned(),
                value: Value::Numbers(v.to_array().to_vec()),
                field: format!("{} > to_world", element.describe()),
                line: Some(element.line),
                indexed: false,
            })
        };
        let ours = match kind {
            "point" => {
                if let (Some(m), false) = (to_world, p.has("position")) {
                    set(&mut p, "position", m.translation);
                }
                "point"
            }
            "directional" => {
                if let (Some(m), false) = (to_world, p.has("direction")) {
                    set(&mut p, "direction", m.transform_vector3(DVec3::Z));
                }
                "directional"
            }
            "constant" => {
                if !p.has("radiance") {
                    set(&mut p, "radiance", DVec3::ONE);
                }
                "environment"
            }
            "area" => return Err(element.error("an area emitter belongs inside a <shape>")),
            other => {
                return Err(element.error(format!(
                    "the emitter '{other}' is not supported yet (point, directional, constant \
                     and area are)"
                )));
            }
        };
        let light = LightDesc::read(ours, &p, &NoFiles)
            .expect("a kind of light")
            .map_err(|e| SceneError::from_param(&element.file, e))?;
        if light.one_per_scene() && self.lights.iter().any(|l| l.name() == light.name()) {
            return Err(element.error(format!("a scene takes one {} emitter", kind)));
        }
        self.lights.push(light);
        Ok(())
    }
}

struct NoFiles;

impl Resources for NoFiles {
    fn radiance_image(
        &self,
        p: &Params,
        name: &str,
        _: bool,
    ) -> Result<Arc<TextureImage>, ParamError> {
        Err(p.out_of_range(name, "given", "not a parameter of this emitter"))
    }
}
