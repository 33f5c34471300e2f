//! The TOML reader's state while it builds a scene: materials by name, meshes read once,
//! the objects and lights so far, and the transforms and placements of items.

use super::repeat::Placement;
use super::transform_list::{self};
use crate::scene::desc::{LightDesc, MaterialDesc, ObjectDesc};
use crate::scene::error::SceneError;
use crate::scene::formats::obj::ObjRef;
use crate::scene::formats::toml::format::{ObjectToml, TransformEntry, Vec3};
use crate::scene::formats::toml::source_map::FieldPath;
use crate::scene::formats::toml::validate::Ctx;
use crate::scene::mesh_file::MeshCache;
use glam::{DAffine3, DVec3};
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

pub(super) fn dvec(v: Vec3) -> DVec3 {
    DVec3::from_array(v)
}

/// The mesh file `file` (relative to `base_dir`) named by the item at `path`.
pub(super) fn mesh_ref<'c>(
    ctx: &Ctx<'c>,
    base_dir: &Path,
    path: &FieldPath,
    file: &str,
) -> ObjRef<'c> {
    ObjRef {
        obj: base_dir.join(file),
        scene: ctx.file,
        item: path.to_string(),
        line: ctx.line(&path.key("file")),
        read_mtl: true,
    }
}

pub(super) struct Builder<'a> {
    pub(super) ctx: &'a Ctx<'a>,
    pub(super) base_dir: &'a Path,
    pub(super) warnings: &'a mut Vec<String>,
    pub(super) materials: Vec<MaterialDesc>,
    /// The `[materials]` table: name → index.
    pub(super) named: BTreeMap<String, u32>,
    /// Shared by mesh models without an MTL material; created on first use.
    pub(super) default_material: Option<u32>,
    /// The scene material made for each MTL material, keyed by mesh file and its index
    /// there, so that objects naming one file share them.
    pub(super) mtl_materials: HashMap<(PathBuf, usize), u32>,
    pub(super) meshes: MeshCache,
    pub(super) objects: Vec<ObjectDesc>,
    pub(super) lights: Vec<LightDesc>,
}

impl Builder<'_> {
    pub(super) fn add_material(&mut self, material: MaterialDesc) -> u32 {
        self.materials.push(material);
        (self.materials.len() - 1) as u32
    }

    pub(super) fn lookup_material(&self, path: &FieldPath, name: &str) -> Result<u32, SceneError> {
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

    pub(super) fn default_material(&mut self) -> u32 {
        if let Some(index) = self.default_material {
            return index;
        }
        let index =
            self.add_material(MaterialDesc { name: "default".to_owned(), ..Default::default() });
        self.default_material = Some(index);
        index
    }

    /// An emissive, otherwise black material for a light named `item`.
    pub(super) fn light_material(
        &mut self,
        item: &str,
        emission: glam::Vec3,
        two_sided_emission: bool,
    ) -> u32 {
        self.add_material(MaterialDesc {
            name: item.to_owned(),
            albedo: glam::Vec3::ZERO,
            emission,
            two_sided_emission,
            ..Default::default()
        })
    }

    /// The transform list at `path.key`, composed (identity when absent).
    pub(super) fn transform(
        &self,
        path: &FieldPath,
        key: &str,
        entries: Option<&Vec<TransformEntry>>,
    ) -> Result<DAffine3, SceneError> {
        let list = path.key(key);
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

    /// `transform` and `transform_end`.
    pub(super) fn placement(
        &self,
        path: &FieldPath,
        o: &ObjectToml,
    ) -> Result<Placement, SceneError> {
        let start = self.transform(path, "transform", o.transform.as_ref())?;
        let end = match &o.transform_end {
            Some(entries) => Some(self.transform(path, "transform_end", Some(entries))?),
            None => None,
        };
        if let Some(Err(problem)) = end.map(|end| crate::transform::motion_parts(&start, &end)) {
            let field = path.key("transform_end");
            return Err(SceneError::Transform {
                file: self.ctx.file.to_path_buf(),
                field: field.to_string(),
                problem,
                line: self.ctx.line(&field),
            });
        }
        Ok(Placement { start, end })
    }

    pub(super) fn degenerate(&self, path: &FieldPath, item: &str, problem: String) -> SceneError {
        SceneError::DegenerateShape {
            file: self.ctx.file.to_path_buf(),
            item: item.to_owned(),
            problem,
            line: self.ctx.line(path),
        }
    }
}
