//! Mesh files (OBJ or PLY, chosen by extension) for mesh objects and mesh lights. Each file
//! is loaded once per scene load, keyed by its resolved path, so that every object naming it
//! gets the same `Arc<MeshData>` and becomes an instance of one prototype. The `smooth`
//! variant of a model (normals computed, or dropped) is also made once.

use crate::scene::desc::MeshData;
use crate::scene::error::SceneError;
use crate::scene::formats::obj::{self, ObjMaterial, ObjRef};
use crate::scene::formats::ply;
use crate::scene::vertex_normals::VertexNormals;
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;

/// One model of a mesh file, with the data an object needs.
pub(crate) struct Model {
    /// The OBJ model name; `None` for a PLY file (one model).
    pub name: Option<String>,
    pub mesh: Arc<MeshData>,
    /// The MTL material: its index in the file (to share the scene material made from it)
    /// and where it is defined.
    pub material: Option<(usize, ObjMaterial)>,
}

struct CachedModel {
    name: Option<String>,
    material: Option<usize>,
    /// As in the file.
    mesh: Arc<MeshData>,
    /// With the shading normals toggled: computed when the file has none, dropped when it
    /// has some. Made on first use.
    toggled: Option<Arc<MeshData>>,
}

impl CachedModel {
    /// `smooth`: `None` keeps what the file has, `Some(true)` gives normals (the file's, or
    /// ones computed as `computed` says), `Some(false)` none (flat shading).
    fn mesh(&mut self, smooth: Option<bool>, computed: VertexNormals) -> Arc<MeshData> {
        let has_normals = self.mesh.normals.is_some();
        if smooth.is_none_or(|smooth| smooth == has_normals) {
            return Arc::clone(&self.mesh);
        }
        let toggled = self.toggled.get_or_insert_with(|| {
            let mut mesh = MeshData::clone(&self.mesh);
            mesh.normals =
                if has_normals { None } else { Some(computed.of(&mesh.positions, &mesh.indices)) };
            Arc::new(mesh)
        });
        Arc::clone(toggled)
    }
}

struct CachedFile {
    models: Vec<CachedModel>,
    materials: Vec<ObjMaterial>,
}

/// The mesh files loaded so far in one scene load.
#[derive(Default)]
pub(crate) struct MeshCache {
    files: HashMap<PathBuf, CachedFile>,
    /// How the normals of a smooth mesh without any are computed (one way per format).
    computed: VertexNormals,
}

impl MeshCache {
    pub(crate) fn new(computed: VertexNormals) -> Self {
        MeshCache { files: HashMap::new(), computed }
    }

    /// The models of the file `mesh_ref` names, loading it on first use. Also returns the
    /// cache key (the canonical path), which identifies the file's MTL materials.
    pub(crate) fn models(
        &mut self,
        mesh_ref: &ObjRef,
        smooth: Option<bool>,
        warnings: &mut Vec<String>,
    ) -> Result<(PathBuf, Vec<Model>), SceneError> {
        let key = std::fs::canonicalize(&mesh_ref.obj).unwrap_or_else(|_| mesh_ref.obj.clone());
        let file = match self.files.entry(key.clone()) {
            std::collections::hash_map::Entry::Occupied(entry) => entry.into_mut(),
            std::collections::hash_map::Entry::Vacant(entry) => {
                entry.insert(load_file(mesh_ref, warnings)?)
            }
        };
        let computed = self.computed;
        let models = file
            .models
            .iter_mut()
            .map(|model| Model {
                name: model.name.clone(),
                mesh: model.mesh(smooth, computed),
                material: model.material.map(|m| (m, file.materials[m].clone())),
            })
            .collect();
        Ok((key, models))
    }
}

fn load_file(mesh_ref: &ObjRef, warnings: &mut Vec<String>) -> Result<CachedFile, SceneError> {
    let path = &mesh_ref.obj;
    let extension = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("obj") => {
            let loaded = obj::load(mesh_ref, warnings)?;
            let models = loaded
                .models
                .into_iter()
                .map(|model| CachedModel {
                    name: Some(model.name),
                    material: model.material,
                    mesh: Arc::new(model.mesh),
                    toggled: None,
                })
                .collect();
            Ok(CachedFile { models, materials: loaded.materials })
        }
        Some("ply") => {
            // Its length checked first, the mesh it declares as it is read (`ply::parse`).
            mesh_ref.check_length(path, 1)?;
            let bytes =
                crate::input_file::read_bytes(path).map_err(|error| SceneError::PlyRead {
                    ply: path.clone(),
                    scene: mesh_ref.scene.to_path_buf(),
                    item: mesh_ref.item.clone(),
                    error,
                    line: mesh_ref.line,
                })?;
            let mesh_memory = crate::limits::memory_available()
                .map(|available| available.saturating_sub(bytes.len() as u64));
            let (mesh, warning) =
                ply::parse(&bytes, mesh_memory).map_err(|problem| SceneError::PlyData {
                    ply: path.clone().into_boxed_path(),
                    ply_line: crate::scene::error::Line(problem.line),
                    scene: mesh_ref.scene.to_path_buf().into_boxed_path(),
                    item: mesh_ref.item.clone(),
                    problem: problem.message,
                    line: mesh_ref.line,
                })?;
            if let Some(warning) = warning {
                let line = warning.line.map_or(String::new(), |line| format!(" (line {line})"));
                warnings.push(format!("{}: {}{line}", path.display(), warning.message));
            }
            let model =
                CachedModel { name: None, material: None, mesh: Arc::new(mesh), toggled: None };
            Ok(CachedFile { models: vec![model], materials: Vec::new() })
        }
        _ => Err(SceneError::OutOfRange {
            file: mesh_ref.scene.to_path_buf(),
            field: format!("{}.file", mesh_ref.item),
            value: format!("'{}'", path.display()),
            requirement: "an OBJ (.obj) or PLY (.ply) file".to_owned(),
            line: mesh_ref.line,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes::box_mesh;
    use glam::DVec3;

    #[test]
    fn smooth_variants_are_made_once() {
        let mut model = CachedModel {
            name: None,
            material: None,
            mesh: Arc::new(box_mesh(DVec3::ZERO, DVec3::ONE).unwrap()),
            toggled: None,
        };
        let area = VertexNormals::AreaWeighted;
        let file = model.mesh(None, area);
        assert!(Arc::ptr_eq(&file, &model.mesh(Some(false), area)));
        let smooth = model.mesh(Some(true), area);
        assert!(smooth.normals.is_some());
        assert!(Arc::ptr_eq(&smooth, &model.mesh(Some(true), area)));
        assert!(!Arc::ptr_eq(&smooth, &file));
    }
}
