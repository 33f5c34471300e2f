//! The deserialised file (`toml_format`) → a validated `SceneDesc`: materials, objects and
//! lights, each checked with its field path and line (camera and settings: `camera_settings`).

use super::camera_settings::{camera, settings};
use super::desc::{LightDesc, MaterialDesc, ObjectDesc, SceneDesc, ShapeDesc};
use super::error::SceneError;
use super::obj::{self, ObjRef};
use super::shapes::{box_mesh, quad_mesh};
use super::source_map::FieldPath;
use super::toml_format::{
    LightKind, LightToml, MaterialToml, ObjectKind, ObjectToml, SceneFile, TransformEntry, Vec3,
};
use super::transform_list;
use super::validate::Ctx;
use glam::{DAffine3, DVec3};
use std::collections::BTreeMap;
use std::path::Path;

/// Builds the scene; `base_dir` resolves relative OBJ paths, `warnings` collects non-fatal
/// problems (a missing MTL file).
pub(crate) fn scene_desc(
    file: SceneFile,
    ctx: &Ctx,
    base_dir: &Path,
    warnings: &mut Vec<String>,
) -> Result<SceneDesc, SceneError> {
    let camera = camera(&file.camera, ctx)?;
    let settings = settings(file.render.as_ref(), ctx)?;
    let mut builder = Builder {
        ctx,
        base_dir,
        warnings,
        materials: Vec::new(),
        named: BTreeMap::new(),
        default_material: None,
        objects: Vec::new(),
        lights: Vec::new(),
    };
    for (name, material) in &file.materials {
        builder.named_material(name, material)?;
    }
    for (i, object) in file.objects.iter().enumerate() {
        builder.object(i, object)?;
    }
    for (i, light) in file.lights.iter().enumerate() {
        builder.light(i, light)?;
    }
    Ok(SceneDesc {
        source: ctx.file.to_path_buf(),
        camera,
        settings,
        materials: builder.materials,
        objects: builder.objects,
        lights: builder.lights,
    })
}

fn dvec(v: Vec3) -> DVec3 {
    DVec3::from_array(v)
}

struct Builder<'a> {
    ctx: &'a Ctx<'a>,
    base_dir: &'a Path,
    warnings: &'a mut Vec<String>,
    materials: Vec<MaterialDesc>,
    /// The `[materials]` table: name → index.
    named: BTreeMap<String, u32>,
    /// Shared by OBJ models without an MTL material; created on first use.
    default_material: Option<u32>,
    objects: Vec<ObjectDesc>,
    lights: Vec<LightDesc>,
}

impl Builder<'_> {
    fn add_material(&mut self, material: MaterialDesc) -> u32 {
        self.materials.push(material);
        (self.materials.len() - 1) as u32
    }

    fn named_material(&mut self, name: &str, m: &MaterialToml) -> Result<(), SceneError> {
        let path = FieldPath::root("materials").key(name);
        let albedo = self.ctx.color(&path.key("albedo"), m.albedo.unwrap_or([0.8; 3]), true)?;
        let emission =
            self.ctx.color(&path.key("emission"), m.emission.unwrap_or([0.0; 3]), false)?;
        let index = self.add_material(MaterialDesc { name: name.to_owned(), albedo, emission, ..Default::default() });
        self.named.insert(name.to_owned(), index);
        Ok(())
    }

    fn lookup_material(&self, path: &FieldPath, name: &str) -> Result<u32, SceneError> {
        self.named.get(name).copied().ok_or_else(|| {
            let defined: Vec<&str> = self.named.keys().map(String::as_str).collect();
            SceneError::UnknownMaterial {
                file: self.ctx.file.to_path_buf(),
                field: path.to_string(),
                name: name.to_owned(),
                defined: if defined.is_empty() { "(none)".to_owned() } else { defined.join(", ") },
                line: self.ctx.line(path),
            }
        })
    }

    fn default_material(&mut self) -> u32 {
        if let Some(index) = self.default_material {
            return index;
        }
        let index = self.add_material(MaterialDesc {
            name: "default".to_owned(),
            albedo: glam::Vec3::splat(0.8),
            emission: glam::Vec3::ZERO,
            ..Default::default()
        });
        self.default_material = Some(index);
        index
    }

    /// Rejects fields the type does not take; `present` lists every optional field.
    fn check_fields(
        &self,
        path: &FieldPath,
        item: &str,
        present: &[(&str, bool)],
        allowed: &[&str],
    ) -> Result<(), SceneError> {
        let Some((field, _)) = present.iter().find(|(name, set)| *set && !allowed.contains(name))
        else {
            return Ok(());
        };
        Err(SceneError::FieldNotAllowed {
            file: self.ctx.file.to_path_buf(),
            item: item.to_owned(),
            field: (*field).to_owned(),
            allowed: allowed.join(", "),
            line: self.ctx.line(&path.key(field)),
        })
    }

    fn required<T: Copy>(
        &self,
        path: &FieldPath,
        item: &str,
        field: &str,
        value: Option<T>,
    ) -> Result<T, SceneError> {
        value.ok_or_else(|| SceneError::MissingField {
            file: self.ctx.file.to_path_buf(),
            item: item.to_owned(),
            field: field.to_owned(),
            line: self.ctx.line(path),
        })
    }

    fn transform(
        &self,
        path: &FieldPath,
        entries: Option<&Vec<TransformEntry>>,
    ) -> Result<DAffine3, SceneError> {
        let list = path.key("transform");
        let mut ops = Vec::new();
        for (i, entry) in entries.map_or(&[][..], Vec::as_slice).iter().enumerate() {
            let op = entry.op().map_err(|keys| {
                let field = list.index(i);
                SceneError::TransformEntry {
                    file: self.ctx.file.to_path_buf(),
                    field: field.to_string(),
                    found: if keys.is_empty() { "none".to_owned() } else { keys.join(", ") },
                    line: self.ctx.line(&field),
                }
            })?;
            ops.push(op);
        }
        transform_list::world_from_object(&ops).map_err(|problem| {
            let field = problem.entry.map_or(list.clone(), |i| list.index(i));
            SceneError::Transform {
                file: self.ctx.file.to_path_buf(),
                field: field.to_string(),
                problem: problem.message,
                line: self.ctx.line(&field),
            }
        })
    }

    fn degenerate(&self, path: &FieldPath, item: &str, problem: String) -> SceneError {
        SceneError::DegenerateShape {
            file: self.ctx.file.to_path_buf(),
            item: item.to_owned(),
            problem,
            line: self.ctx.line(path),
        }
    }

    fn object(&mut self, i: usize, o: &ObjectToml) -> Result<(), SceneError> {
        let path = FieldPath::root("objects").index(i);
        let (kind, allowed): (&str, &[&str]) = match o.kind {
            ObjectKind::Quad => ("quad", &["type", "material", "corner", "u", "v", "transform"]),
            ObjectKind::Sphere => {
                ("sphere", &["type", "material", "center", "radius", "transform"])
            }
            ObjectKind::Box => ("box", &["type", "material", "min", "max", "transform"]),
            ObjectKind::Mesh => ("mesh", &["type", "material", "file", "transform"]),
        };
        let item = format!("{path} ({kind})");
        let present = [
            ("corner", o.corner.is_some()),
            ("u", o.u.is_some()),
            ("v", o.v.is_some()),
            ("center", o.center.is_some()),
            ("radius", o.radius.is_some()),
            ("min", o.min.is_some()),
            ("max", o.max.is_some()),
            ("file", o.file.is_some()),
        ];
        self.check_fields(&path, &item, &present, allowed)?;
        let world_from_object = self.transform(&path, o.transform.as_ref())?;
        let material = o
            .material
            .as_deref()
            .map(|name| self.lookup_material(&path.key("material"), name))
            .transpose()?;
        let shape = match o.kind {
            ObjectKind::Mesh => {
                let file = self.required(&path, &item, "file", o.file.as_deref())?;
                return self.mesh_objects(&path, file, material, world_from_object);
            }
            ObjectKind::Quad => {
                let corner = self.required(&path, &item, "corner", o.corner)?;
                let u = self.required(&path, &item, "u", o.u)?;
                let v = self.required(&path, &item, "v", o.v)?;
                let mesh = quad_mesh(dvec(corner), dvec(u), dvec(v))
                    .map_err(|p| self.degenerate(&path, &item, p))?;
                ShapeDesc::Mesh(std::sync::Arc::new(mesh))
            }
            ObjectKind::Sphere => {
                let center = self.required(&path, &item, "center", o.center)?;
                let radius = self.required(&path, &item, "radius", o.radius)?;
                let radius = self.ctx.positive(&path.key("radius"), radius)?;
                if crate::transform::uniform_scale(&world_from_object).is_none() {
                    let field = path.key("transform");
                    return Err(SceneError::Transform {
                        file: self.ctx.file.to_path_buf(),
                        field: field.to_string(),
                        problem: "a sphere's transform must keep it round: no non-uniform \
                                  scale or shear"
                            .to_owned(),
                        line: self.ctx.line(&field),
                    });
                }
                ShapeDesc::Sphere { center: dvec(center), radius }
            }
            ObjectKind::Box => {
                let min = self.required(&path, &item, "min", o.min)?;
                let max = self.required(&path, &item, "max", o.max)?;
                let mesh =
                    box_mesh(dvec(min), dvec(max)).map_err(|p| self.degenerate(&path, &item, p))?;
                ShapeDesc::Mesh(std::sync::Arc::new(mesh))
            }
        };
        let material = self.required(&path, &item, "material", material)?;
        self.objects.push(ObjectDesc { name: item, shape, material, world_from_object, world_from_object_end: None });
        Ok(())
    }

    /// One object per OBJ model (tobj splits models at each material change).
    fn mesh_objects(
        &mut self,
        path: &FieldPath,
        file: &str,
        material: Option<u32>,
        world_from_object: DAffine3,
    ) -> Result<(), SceneError> {
        let obj_ref = ObjRef {
            obj: self.base_dir.join(file),
            scene: self.ctx.file,
            item: path.to_string(),
            line: self.ctx.line(&path.key("file")),
        };
        let loaded = obj::load(&obj_ref, self.warnings)?;
        let mut mtl_indices: Vec<Option<u32>> = vec![None; loaded.materials.len()];
        for model in loaded.models {
            let index = match (material, model.material) {
                (Some(index), _) => index,
                (None, Some(m)) => match mtl_indices[m] {
                    Some(index) => index,
                    None => {
                        let mtl = &loaded.materials[m];
                        let index = self.add_material(MaterialDesc {
                            name: format!("{file}: {}", mtl.name),
                            albedo: mtl.albedo,
                            emission: mtl.emission,
                            ..Default::default()
                        });
                        mtl_indices[m] = Some(index);
                        index
                    }
                },
                (None, None) => self.default_material(),
            };
            self.objects.push(ObjectDesc {
                name: format!("{path} ({file}: {})", model.name),
                shape: ShapeDesc::Mesh(std::sync::Arc::new(model.mesh)),
                material: index,
                world_from_object,
                world_from_object_end: None,
            });
        }
        Ok(())
    }

    fn light(&mut self, i: usize, l: &LightToml) -> Result<(), SceneError> {
        let path = FieldPath::root("lights").index(i);
        let (kind, allowed): (&str, &[&str]) = match l.kind {
            LightKind::Point => ("point light", &["type", "position", "intensity"]),
            LightKind::Quad => {
                ("quad light", &["type", "corner", "u", "v", "emission", "transform"])
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
            ("transform", l.transform.is_some()),
        ];
        self.check_fields(&path, &item, &present, allowed)?;
        match l.kind {
            LightKind::Point => {
                let position = self.required(&path, &item, "position", l.position)?;
                let intensity = self.required(&path, &item, "intensity", l.intensity)?;
                let intensity = self.ctx.color(&path.key("intensity"), intensity, false)?;
                self.lights.push(LightDesc::Point { position: dvec(position), intensity });
            }
            LightKind::Quad => {
                let corner = self.required(&path, &item, "corner", l.corner)?;
                let u = self.required(&path, &item, "u", l.u)?;
                let v = self.required(&path, &item, "v", l.v)?;
                let emission = self.required(&path, &item, "emission", l.emission)?;
                let emission = self.ctx.color(&path.key("emission"), emission, false)?;
                let world_from_object = self.transform(&path, l.transform.as_ref())?;
                let mesh = quad_mesh(dvec(corner), dvec(u), dvec(v))
                    .map_err(|p| self.degenerate(&path, &item, p))?;
                let material = self.add_material(MaterialDesc {
                    name: item.clone(),
                    albedo: glam::Vec3::ZERO,
                    emission,
                    ..Default::default()
                });
                self.objects.push(ObjectDesc {
                    name: item,
                    shape: ShapeDesc::Mesh(std::sync::Arc::new(mesh)),
                    material,
                    world_from_object,
                    world_from_object_end: None,
                });
            }
        }
        Ok(())
    }
}
