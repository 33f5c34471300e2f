//! `[[lights]]` entries into `LightDesc`s (and emissive objects for quad, sphere and mesh
//! lights).

use super::builder::{Builder, dvec, mesh_ref};
use super::repeat::Placement;
use crate::scene::desc::{EnvironmentMap, EnvironmentMapping, LightDesc, Spot, Point, Environment, Directional, Area, Ambient, ShapeDesc};
use crate::scene::error::SceneError;
use crate::scene::formats::toml::format::{
    EnvironmentMappingToml, ImageEncodingToml, LightKind, LightToml,
};
use crate::scene::formats::toml::source_map::FieldPath;
use crate::scene::formats::toml::transform_list::fmt_vec;
use crate::scene::formats::toml::validate::Ctx;
use crate::scene::shapes::quad_mesh;
use crate::scene::texture_image::{ImageRef, load_radiance};
use std::sync::Arc;

impl Builder<'_> {
    pub(super) fn light(&mut self, i: usize, l: &LightToml) -> Result<(), SceneError> {
        let path = FieldPath::root("lights").index(i);
        let (kind, allowed): (&str, &[&str]) = match l.kind {
            LightKind::Point => ("point light", &["type", "position", "intensity"]),
            LightKind::Spot => (
                "spot light",
                &["type", "position", "direction", "intensity", "coverage_angle", "falloff_angle"],
            ),
            LightKind::Quad => {
                ("quad light", &["type", "corner", "u", "v", "emission", "transform"])
            }
            LightKind::Directional => ("directional light", &["type", "direction", "irradiance"]),
            LightKind::Ambient => ("ambient light", &["type", "radiance"]),
            LightKind::Sphere => {
                ("sphere light", &["type", "center", "radius", "emission", "transform"])
            }
            LightKind::Mesh => ("mesh light", &["type", "file", "emission", "transform"]),
            LightKind::Area => ("area light", &["type", "center", "normal", "size", "radiance"]),
            LightKind::Environment => {
                ("environment light", &["type", "file", "radiance", "scale", "encoding", "mapping"])
            }
        };
        let item = format!("{path} ({kind})");
        let present = [
            ("position", l.position.is_some()),
            ("intensity", l.intensity.is_some()),
            ("corner", l.corner.is_some()),
            ("u", l.u.is_some()),
            ("v", l.v.is_some()),
            ("emission", l.emission.is_some()),
            ("direction", l.direction.is_some()),
            ("irradiance", l.irradiance.is_some()),
            ("radiance", l.radiance.is_some()),
            ("center", l.center.is_some()),
            ("radius", l.radius.is_some()),
            ("file", l.file.is_some()),
            ("transform", l.transform.is_some()),
            ("normal", l.normal.is_some()),
            ("size", l.size.is_some()),
            ("coverage_angle", l.coverage_angle.is_some()),
            ("falloff_angle", l.falloff_angle.is_some()),
            ("scale", l.scale.is_some()),
            ("encoding", l.encoding.is_some()),
            ("mapping", l.mapping.is_some()),
        ];
        let ctx = self.ctx;
        ctx.check_fields(&path, &item, &present, allowed)?;
        let emission = |ctx: &Ctx| -> Result<glam::Vec3, SceneError> {
            let emission = ctx.required(&path, &item, "emission", l.emission)?;
            ctx.color(&path.key("emission"), emission, false)
        };
        match l.kind {
            LightKind::Point => {
                let position = ctx.required(&path, &item, "position", l.position)?;
                let intensity = ctx.required(&path, &item, "intensity", l.intensity)?;
                let intensity = ctx.color(&path.key("intensity"), intensity, false)?;
                self.lights.push(LightDesc::Point(Point { position: dvec(position), intensity }));
            }
            LightKind::Spot => {
                let position = ctx.required(&path, &item, "position", l.position)?;
                let intensity = ctx.required(&path, &item, "intensity", l.intensity)?;
                let intensity = ctx.color(&path.key("intensity"), intensity, false)?;
                let direction = ctx.required(&path, &item, "direction", l.direction)?;
                let field = path.key("direction");
                let direction = dvec(direction).try_normalize().ok_or_else(|| {
                    ctx.out_of_range(&field, fmt_vec(&direction), "a non-zero vector")
                })?;
                let coverage = ctx.required(&path, &item, "coverage_angle", l.coverage_angle)?;
                let falloff = ctx.required(&path, &item, "falloff_angle", l.falloff_angle)?;
                let coverage_field = path.key("coverage_angle");
                ctx.require(
                    coverage > 0.0 && coverage <= 360.0,
                    &coverage_field,
                    coverage,
                    "an angle in degrees, > 0 and <= 360",
                )?;
                ctx.require(
                    falloff >= 0.0 && falloff <= coverage,
                    &path.key("falloff_angle"),
                    falloff,
                    "an angle in degrees, >= 0 and <= coverage_angle",
                )?;
                self.lights.push(LightDesc::Spot(Spot {
                    position: dvec(position),
                    direction,
                    intensity,
                    coverage_degrees: coverage,
                    falloff_degrees: falloff,
                }));
            }
            LightKind::Directional => {
                let direction = ctx.required(&path, &item, "direction", l.direction)?;
                let field = path.key("direction");
                let unit = dvec(direction).try_normalize().ok_or_else(|| {
                    ctx.out_of_range(&field, fmt_vec(&direction), "a non-zero vector")
                })?;
                let irradiance = ctx.required(&path, &item, "irradiance", l.irradiance)?;
                let irradiance = ctx.color(&path.key("irradiance"), irradiance, false)?;
                self.lights.push(LightDesc::Directional(Directional { direction: unit, irradiance }));
            }
            LightKind::Ambient => {
                let radiance = ctx.required(&path, &item, "radiance", l.radiance)?;
                let radiance = ctx.color(&path.key("radiance"), radiance, false)?;
                self.lights.push(LightDesc::Ambient(Ambient { radiance }));
            }
            LightKind::Area => {
                let center = ctx.required(&path, &item, "center", l.center)?;
                let normal = ctx.required(&path, &item, "normal", l.normal)?;
                let field = path.key("normal");
                let normal = dvec(normal).try_normalize().ok_or_else(|| {
                    ctx.out_of_range(&field, fmt_vec(&normal), "a non-zero vector")
                })?;
                let size = ctx.required(&path, &item, "size", l.size)?;
                let size = ctx.positive(&path.key("size"), size)?;
                let radiance = ctx.required(&path, &item, "radiance", l.radiance)?;
                let radiance = ctx.color(&path.key("radiance"), radiance, false)?;
                self.lights.push(LightDesc::Area(Area { center: dvec(center), normal, size, radiance }));
            }
            LightKind::Environment => {
                let map = self.environment_map(&path, &item, l)?;
                let scale = match l.scale {
                    Some(scale) => ctx.color(&path.key("scale"), scale, false)?,
                    None => glam::Vec3::ONE,
                };
                if self.lights.iter().any(|l| matches!(l, LightDesc::Environment(_))) {
                    let requirement = "at most one environment light per scene";
                    return Err(ctx.out_of_range(&path.key("type"), "environment", requirement));
                }
                let mapping = match l.mapping {
                    None | Some(EnvironmentMappingToml::Latlong) => EnvironmentMapping::LatLong,
                    Some(EnvironmentMappingToml::Probe) => EnvironmentMapping::Probe,
                };
                if l.mapping.is_some() && l.file.is_none() {
                    let requirement = "given only with file";
                    return Err(ctx.out_of_range(&path.key("mapping"), "given", requirement));
                }
                self.lights.push(LightDesc::Environment(Environment { map, scale, mapping }));
            }
            LightKind::Quad => {
                let corner = ctx.required(&path, &item, "corner", l.corner)?;
                let u = ctx.required(&path, &item, "u", l.u)?;
                let v = ctx.required(&path, &item, "v", l.v)?;
                let emission = emission(ctx)?;
                let world_from_object = self.transform(&path, "transform", l.transform.as_ref())?;
                let mesh = quad_mesh(dvec(corner), dvec(u), dvec(v))
                    .map_err(|p| self.degenerate(&path, &item, p))?;
                let material = self.light_material(&item, emission);
                let shape = ShapeDesc::Mesh(Arc::new(mesh));
                self.push(item, shape, material, Placement::fixed(world_from_object), None);
            }
            LightKind::Sphere => {
                let center = ctx.required(&path, &item, "center", l.center)?;
                let radius = ctx.required(&path, &item, "radius", l.radius)?;
                let radius = ctx.positive(&path.key("radius"), radius)?;
                let emission = emission(ctx)?;
                let world_from_object = self.transform(&path, "transform", l.transform.as_ref())?;
                let material = self.light_material(&item, emission);
                let shape = ShapeDesc::Sphere { center: dvec(center), radius };
                self.push(item, shape, material, Placement::fixed(world_from_object), None);
            }
            LightKind::Mesh => {
                let file = ctx.required(&path, &item, "file", l.file.as_deref())?;
                let emission = emission(ctx)?;
                let world_from_object = self.transform(&path, "transform", l.transform.as_ref())?;
                let material = self.light_material(&item, emission);
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

    /// An environment light's `file` or `radiance` (exactly one of them).
    fn environment_map(
        &self,
        path: &FieldPath,
        item: &str,
        l: &LightToml,
    ) -> Result<EnvironmentMap, SceneError> {
        let ctx = self.ctx;
        match (&l.file, l.radiance) {
            (Some(_), Some(_)) => Err(ctx.conflict(path, item, "file", "radiance")),
            (None, None) => Err(ctx.missing(path, item, "file (or radiance)")),
            (None, Some(radiance)) => {
                if l.encoding.is_some() {
                    let requirement = "given only with file";
                    return Err(ctx.out_of_range(&path.key("encoding"), "given", requirement));
                }
                Ok(EnvironmentMap::Constant(ctx.color(&path.key("radiance"), radiance, false)?))
            }
            (Some(file), None) => {
                let at = ImageRef {
                    image: self.base_dir.join(file),
                    scene: ctx.file,
                    item: path.key("file").to_string(),
                    line: ctx.line(&path.key("file")),
                };
                let srgb = l.encoding.unwrap_or(ImageEncodingToml::Srgb) == ImageEncodingToml::Srgb;
                let image = load_radiance(&at, srgb)?;
                if image.hdr && l.encoding.is_some() {
                    let requirement = "given only for PNG and JPEG files (EXR values are linear)";
                    return Err(ctx.out_of_range(&path.key("encoding"), "given", requirement));
                }
                Ok(EnvironmentMap::Image(image))
            }
        }
    }
}
