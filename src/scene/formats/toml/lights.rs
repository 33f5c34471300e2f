//! `[[lights]]` entries: a kind of `light::kinds` reads its own parameters from the entry's
//! table (any `type` it names); quad, sphere and mesh lights are emissive objects.

use super::builder::{Builder, dvec, mesh_ref};
use super::repeat::Placement;
use crate::light::LightDesc;
use crate::params::{Entry, ParamError, Params, Resources, Value};
use crate::scene::desc::ShapeDesc;
use crate::scene::error::SceneError;
use crate::scene::formats::toml::format::{EmissiveShapeKind, EmissiveShapeToml};
use crate::scene::formats::toml::source_map::FieldPath;
use crate::scene::formats::toml::validate::Ctx;
use crate::scene::shapes::quad_mesh;
use crate::scene::texture_image::radiance_param;
use crate::texels::TextureImage;
use std::sync::Arc;

impl Builder<'_> {
    pub(super) fn light(&mut self, i: usize, table: &toml::Table) -> Result<(), SceneError> {
        let ctx = self.ctx;
        let path = FieldPath::root("lights").index(i);
        let name = match table.get("type") {
            Some(toml::Value::String(name)) => name.as_str(),
            Some(other) => return Err(ctx.out_of_range(&path.key("type"), other, "a string")),
            None => return Err(ctx.missing(&path, &path.to_string(), "type")),
        };
        if EmissiveShapeKind::NAMES.contains(&name) {
            let light = toml::Value::Table(table.clone()).try_into().map_err(|e| {
                let message = format!("{path}: {e}{}", ctx.line(&path));
                SceneError::Toml { file: ctx.file.to_path_buf(), message }
            })?;
            return self.emissive_shape(&path, &light);
        }
        let Some(label) = LightDesc::label_of(name) else {
            let kinds = [LightDesc::NAMES, &EmissiveShapeKind::NAMES[..]].concat();
            let requirement = format!("one of {}", kinds.join(", "));
            return Err(ctx.out_of_range(&path.key("type"), format!("{name:?}"), &requirement));
        };
        let params = params(ctx, &path, format!("{path} ({label})"), table);
        let from_param = |e| SceneError::from_param(ctx.file, e);
        let light = LightDesc::read(name, &params, self)
            .expect("a kind with a label")
            .map_err(from_param)?;
        if light.one_per_scene() && self.lights.iter().any(|l| l.name() == name) {
            let requirement = format!("at most one {label} per scene");
            return Err(ctx.out_of_range(&path.key("type"), name, &requirement));
        }
        self.lights.push(light);
        Ok(())
    }

    /// A quad, sphere or mesh light: an object with an emissive material.
    fn emissive_shape(
        &mut self,
        path: &FieldPath,
        l: &EmissiveShapeToml,
    ) -> Result<(), SceneError> {
        let (kind, allowed): (&str, &[&str]) = match l.kind {
            EmissiveShapeKind::Quad => {
                ("quad light", &["type", "corner", "u", "v", "emission", "two_sided", "transform"])
            }
            EmissiveShapeKind::Sphere => (
                "sphere light",
                &["type", "center", "radius", "emission", "two_sided", "transform"],
            ),
            EmissiveShapeKind::Mesh => {
                ("mesh light", &["type", "file", "emission", "two_sided", "transform"])
            }
        };
        let path = path.clone();
        let item = format!("{path} ({kind})");
        let present = [
            ("corner", l.corner.is_some()),
            ("u", l.u.is_some()),
            ("v", l.v.is_some()),
            ("emission", l.emission.is_some()),
            ("two_sided", l.two_sided.is_some()),
            ("center", l.center.is_some()),
            ("radius", l.radius.is_some()),
            ("file", l.file.is_some()),
            ("transform", l.transform.is_some()),
        ];
        let ctx = self.ctx;
        ctx.check_fields(&path, &item, &present, allowed)?;
        let two_sided = l.two_sided.unwrap_or(false);
        let emission = |ctx: &Ctx| -> Result<glam::Vec3, SceneError> {
            let emission = ctx.required(&path, &item, "emission", l.emission)?;
            ctx.color(&path.key("emission"), emission, false)
        };
        match l.kind {
            EmissiveShapeKind::Quad => {
                let corner = ctx.required(&path, &item, "corner", l.corner)?;
                let u = ctx.required(&path, &item, "u", l.u)?;
                let v = ctx.required(&path, &item, "v", l.v)?;
                let emission = emission(ctx)?;
                let world_from_object = self.transform(&path, "transform", l.transform.as_ref())?;
                let mesh = quad_mesh(dvec(corner), dvec(u), dvec(v))
                    .map_err(|p| self.degenerate(&path, &item, p))?;
                let material = self.light_material(&item, emission, two_sided);
                let shape = ShapeDesc::Mesh(Arc::new(mesh));
                self.push(item, shape, material, Placement::fixed(world_from_object), None);
            }
            EmissiveShapeKind::Sphere => {
                let center = ctx.required(&path, &item, "center", l.center)?;
                let radius = ctx.required(&path, &item, "radius", l.radius)?;
                let radius = ctx.positive_radius(&path.key("radius"), radius)?;
                let emission = emission(ctx)?;
                let world_from_object = self.transform(&path, "transform", l.transform.as_ref())?;
                let material = self.light_material(&item, emission, two_sided);
                let shape = ShapeDesc::Sphere { center: dvec(center), radius };
                self.push(item, shape, material, Placement::fixed(world_from_object), None);
            }
            EmissiveShapeKind::Mesh => {
                let file = ctx.required(&path, &item, "file", l.file.as_deref())?;
                let emission = emission(ctx)?;
                let world_from_object = self.transform(&path, "transform", l.transform.as_ref())?;
                let material = self.light_material(&item, emission, two_sided);
                let mesh_ref = mesh_ref(ctx, self.base_dir, &path, file);
                let (_, models) = self.meshes.models(&mesh_ref, None, self.warnings)?;
                for model in models {
                    let name = match &model.name {
                        Some(model_name) => format!("{item} ({file}: {model_name})"),
                        None => format!("{item} ({file})"),
                    };
                    let shape = ShapeDesc::Mesh(model.mesh);
                    self.push(name, shape, material, Placement::fixed(world_from_object), None);
                }
            }
        }
        Ok(())
    }
}

/// The entry's table as a kind's parameters, each with its field path and line.
fn params(ctx: &Ctx, path: &FieldPath, item: String, table: &toml::Table) -> Params {
    let entries = table
        .iter()
        .map(|(name, value)| {
            let field = path.key(name);
            Entry {
                name: name.clone(),
                value: param_value(value),
                line: ctx.line(&field).0,
                field: field.to_string(),
                indexed: true,
            }
        })
        .collect();
    Params::new(item, ctx.line(path).0, entries)
}

fn param_value(value: &toml::Value) -> Value {
    let number = |v: &toml::Value| match v {
        toml::Value::Integer(i) => Some(*i as f64),
        toml::Value::Float(x) => Some(*x),
        _ => None,
    };
    match value {
        toml::Value::String(text) => Value::Text(text.clone()),
        toml::Value::Boolean(b) => Value::Bool(*b),
        toml::Value::Array(items) => match items.iter().map(number).collect::<Option<Vec<_>>>() {
            Some(numbers) => Value::Numbers(numbers),
            None => Value::Other(value.to_string()),
        },
        v => number(v).map_or_else(|| Value::Other(v.to_string()), Value::Number),
    }
}

impl Resources for Builder<'_> {
    fn radiance_image(
        &self,
        params: &Params,
        name: &str,
        srgb: bool,
    ) -> Result<Arc<TextureImage>, ParamError> {
        radiance_param(params, name, self.ctx.file, |file| self.base_dir.join(file), srgb)
    }
}
