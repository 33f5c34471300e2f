//! OBJ files (through tobj) → meshes, one per OBJ model/material, with where their MTL
//! materials are defined (`mtl` makes them scene materials when a scene uses them).

mod mtl;
mod mtl_mapping;
mod mtl_material;
mod mtl_notes;
#[cfg(test)]
mod mtl_tests;
mod mtl_texture;
mod scan;

pub(crate) use mtl::{ObjMaterial, material_desc};
pub(crate) use mtl_notes::MtlNotes;

use crate::scene::desc::MeshData;
use crate::scene::error::{Line, SceneError};
use crate::scene::formats::obj::scan::{ScanProblem, scan_mtl, scan_obj, without_bom};
use glam::{DVec3, Vec2};
use std::cell::RefCell;
use std::collections::{HashMap, HashSet};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The mesh file (OBJ or PLY) and the scene item that names it, for messages.
pub(crate) struct ObjRef<'a> {
    /// The OBJ path resolved against the scene directory.
    pub obj: PathBuf,
    pub scene: &'a Path,
    /// `objects[3]`.
    pub item: String,
    /// Line of the `file` field in the scene.
    pub line: Line,
    /// Whether the OBJ's material libraries are read (and their absence said): not for a
    /// Mitsuba scene, whose OBJ reader never reads them.
    pub read_mtl: bool,
}

impl ObjRef<'_> {
    fn error(&self, file: &Path, problem: String, line: Line) -> SceneError {
        SceneError::ObjData {
            file: file.to_path_buf(),
            scene: self.scene.to_path_buf(),
            item: self.item.clone(),
            problem,
            line,
        }
    }

    fn scan_error(&self, file: &Path, problem: ScanProblem) -> SceneError {
        self.error(file, problem.message, Line(Some(problem.line)))
    }

    /// Refuses to read the mesh file `file` when `bytes_per_byte` times its length is more
    /// memory than the process may use: checked before it is read whole.
    pub(crate) fn check_length(&self, file: &Path, bytes_per_byte: u64) -> Result<(), SceneError> {
        let length = std::fs::metadata(file).map_or(0, |m| m.len());
        let what = || {
            let (item, scene, line) = (&self.item, self.scene.display(), self.line);
            format!("a file of {length} bytes, named by {item} in '{scene}'{line}")
        };
        crate::scene::reading_budget::check_reading(
            file,
            length.saturating_mul(bytes_per_byte),
            what,
        )
    }
}

pub(crate) struct ObjModel {
    pub name: String,
    pub mesh: MeshData,
    /// Index into `LoadedObj::materials`; `None` for no (or an unknown) MTL material.
    pub material: Option<usize>,
}

pub(crate) struct LoadedObj {
    /// Models with at least one triangle.
    pub models: Vec<ObjModel>,
    /// The MTL materials the models use, not yet read.
    pub materials: Vec<ObjMaterial>,
}

/// Loads the OBJ file; a missing MTL file adds a warning and leaves its materials undefined.
/// Without `read_mtl`, no MTL file is opened and the models have no material.
pub(crate) fn load(obj_ref: &ObjRef, warnings: &mut Vec<String>) -> Result<LoadedObj, SceneError> {
    let obj = obj_ref.obj.as_path();
    obj_ref.check_length(obj, crate::limits::BYTES_PER_OBJ_BYTE)?;
    let text = crate::input_file::read_text(obj).map(without_bom).map_err(|error| {
        SceneError::ObjRead {
            obj: obj.to_path_buf(),
            scene: obj_ref.scene.to_path_buf(),
            item: obj_ref.item.clone(),
            error,
            line: obj_ref.line,
        }
    })?;
    let scan = scan_obj(&text).map_err(|p| obj_ref.scan_error(obj, p))?;
    for warning in &scan.warnings {
        warnings.push(format!("{}: {} (line {})", obj.display(), warning.message, warning.line));
    }

    let obj_dir = obj.parent().unwrap_or(Path::new("")).to_path_buf();
    let mtl_error: RefCell<Option<SceneError>> = RefCell::new(None);
    let missing_mtl: RefCell<Vec<String>> = RefCell::new(Vec::new());
    let mtl_warnings: RefCell<Vec<String>> = RefCell::new(Vec::new());
    // Parallel to tobj's list of materials (every library's, in the order it reads them).
    let sources: RefCell<Vec<ObjMaterial>> = RefCell::new(Vec::new());
    let material_loader = |mtl_name: &Path| -> tobj::MTLLoadResult {
        if !obj_ref.read_mtl {
            return Ok((Vec::new(), Default::default()));
        }
        let mtl = obj_dir.join(mtl_name);
        let mtl_text = match crate::input_file::read_text(&mtl).map(without_bom) {
            Ok(text) => text,
            // A missing library is a warning (exporters often name one they do not ship);
            // one that exists but cannot be read (a device, too large) is an error.
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                let problem = format!("material library '{}' cannot be read: {e}", mtl.display());
                *mtl_error.borrow_mut() = Some(obj_ref.error(obj, problem, Line(None)));
                return Err(tobj::LoadError::OpenFileFailed);
            }
            Err(e) => {
                missing_mtl.borrow_mut().push(format!(
                    "{}: material library '{}' cannot be read ({e}); its materials fall back \
                     to the default",
                    obj.display(),
                    mtl.display()
                ));
                return Err(tobj::LoadError::OpenFileFailed);
            }
        };
        match scan_mtl(&mtl_text) {
            Ok(found) => mtl_warnings.borrow_mut().extend(
                found
                    .into_iter()
                    .map(|w| format!("{}: {} (line {})", mtl.display(), w.message, w.line)),
            ),
            Err(problem) => {
                *mtl_error.borrow_mut() = Some(obj_ref.scan_error(&mtl, problem));
                return Err(tobj::LoadError::MaterialParseError);
            }
        }
        let loaded = tobj::load_mtl_buf(&mut mtl_text.as_bytes());
        match &loaded {
            Ok((materials, _)) => {
                let lines = mtl::newmtl_lines(&mtl_text);
                if lines.len() != materials.len() {
                    let problem = format!(
                        "{} materials found but {} newmtl statements",
                        materials.len(),
                        lines.len()
                    );
                    *mtl_error.borrow_mut() = Some(obj_ref.error(&mtl, problem, Line(None)));
                    return Err(tobj::LoadError::MaterialParseError);
                }
                let text: Arc<str> = Arc::from(mtl_text);
                for (m, (line, offset)) in materials.iter().zip(lines) {
                    sources.borrow_mut().push(ObjMaterial {
                        name: m.name.clone(),
                        mtl: mtl.clone(),
                        text: Arc::clone(&text),
                        line,
                        offset,
                    });
                }
            }
            // What the scan does not foresee still names the MTL file, not the OBJ.
            Err(e) => {
                let problem = format!("invalid MTL file: {e}");
                *mtl_error.borrow_mut() = Some(obj_ref.error(&mtl, problem, Line(None)));
            }
        }
        loaded
    };
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    // tobj has panicked on malformed input before; a scene file must never crash the loader.
    let result = catch_unwind(AssertUnwindSafe(|| {
        tobj::load_obj_buf(&mut text.as_bytes(), &options, material_loader)
    }))
    .map_err(|_| {
        obj_ref.error(obj, "the OBJ parser (tobj) panicked on this file".to_owned(), Line(None))
    })?;
    if let Some(error) = mtl_error.into_inner() {
        return Err(error);
    }
    let missing_mtl = missing_mtl.into_inner();
    let (models, materials) =
        result.map_err(|e| obj_ref.error(obj, format!("invalid OBJ: {e}"), Line(None)))?;
    let materials = match materials {
        Ok(materials) => materials,
        Err(tobj::LoadError::OpenFileFailed) if !missing_mtl.is_empty() => Vec::new(),
        Err(e) => return Err(obj_ref.error(obj, format!("invalid MTL file: {e}"), Line(None))),
    };
    // An undefined material would silently fall back to the default; say so (unless the
    // whole library is missing, which is already said).
    if missing_mtl.is_empty() && obj_ref.read_mtl {
        // A set: a search of the list per `usemtl` made n materials cost n².
        let defined: HashSet<&str> = materials.iter().map(|m| m.name.as_str()).collect();
        warn_undefined(obj, &scan.usemtl, &defined, warnings);
    }
    warnings.extend(missing_mtl);
    warnings.extend(mtl_warnings.into_inner());

    let sources = sources.into_inner();
    if sources.len() != materials.len() {
        let problem = "the MTL materials could not be matched to their statements".to_owned();
        return Err(obj_ref.error(obj, problem, Line(None)));
    }
    let mut used: HashMap<usize, usize> = HashMap::new();
    let mut loaded = LoadedObj { models: Vec::new(), materials: Vec::new() };
    for model in models {
        let name = model.name.clone();
        // Where some faces give normals (or texture coordinates) and some do not, tobj's
        // arrays do not match the vertices and `mesh_data` uses none of them: said here.
        let vertices = model.mesh.positions.len() / 3;
        let partial = [
            ("normals", model.mesh.normals.len(), 3),
            ("texture coordinates", model.mesh.texcoords.len(), 2),
        ];
        for (what, given, per_vertex) in partial {
            if given > 0 && given != per_vertex * vertices {
                warnings.push(format!(
                    "{}: model '{}': some faces give {what} and some do not, so none are used",
                    obj.display(),
                    crate::excerpt::excerpt(&name)
                ));
            }
        }
        let Some(mesh) = mesh_data(&model.mesh)
            .map_err(|p| obj_ref.error(obj, format!("model '{name}': {p}"), Line(None)))?
        else {
            continue;
        };
        let material = model.mesh.material_id.and_then(|id| sources.get(id).map(|m| (id, m)));
        let material = material.map(|(id, m)| {
            *used.entry(id).or_insert_with(|| {
                loaded.materials.push(m.clone());
                loaded.materials.len() - 1
            })
        });
        loaded.models.push(ObjModel { name, mesh, material });
    }
    if loaded.models.is_empty() {
        return Err(obj_ref.error(obj, "the OBJ file has no triangles".to_owned(), Line(None)));
    }
    Ok(loaded)
}

/// One tobj mesh → `MeshData` in f64, or `None` if it has no triangles. Checks every index
/// and every number.
fn mesh_data(mesh: &tobj::Mesh) -> Result<Option<MeshData>, String> {
    if mesh.indices.is_empty() {
        return Ok(None);
    }
    let count = mesh.positions.len() / 3;
    if !mesh.indices.len().is_multiple_of(3) {
        return Err(format!("{} indices is not a whole number of triangles", mesh.indices.len()));
    }
    if let Some(&bad) = mesh.indices.iter().find(|&&i| i as usize >= count) {
        return Err(format!("vertex index {bad} is out of range ({count} vertices)"));
    }
    let positions: Vec<DVec3> = mesh
        .positions
        .chunks_exact(3)
        .map(|p| DVec3::new(p[0].into(), p[1].into(), p[2].into()))
        .collect();
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(format!("vertex {} has a non-finite coordinate", i + 1));
    }
    let normals = (mesh.normals.len() == 3 * count).then(|| {
        mesh.normals
            .chunks_exact(3)
            .map(|n| DVec3::new(n[0].into(), n[1].into(), n[2].into()))
            .collect::<Vec<_>>()
    });
    if normals.as_ref().is_some_and(|n| n.iter().any(|n| !n.is_finite())) {
        return Err("a normal has a non-finite coordinate".to_owned());
    }
    let uvs = (mesh.texcoords.len() == 2 * count)
        .then(|| mesh.texcoords.chunks_exact(2).map(|t| Vec2::new(t[0], t[1])).collect::<Vec<_>>());
    if uvs.as_ref().is_some_and(|t| t.iter().any(|t| !t.is_finite())) {
        return Err("a texture coordinate is not finite".to_owned());
    }
    let indices = mesh.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
    Ok(Some(MeshData { positions, indices, normals, uvs, attributes: Vec::new() }))
}

/// A warning for each name of `usemtl` (name, line) that `defined` lacks, said once, the
/// first eight by name, the rest in one (an OBJ of 100,000 groups printed 100,000 lines).
fn warn_undefined(
    obj: &Path,
    usemtl: &[(String, usize)],
    defined: &HashSet<&str>,
    warnings: &mut Vec<String>,
) {
    const NAMED: usize = 8;
    let mut undefined = HashSet::new();
    let first_uses = usemtl
        .iter()
        .filter(|(name, _)| !defined.contains(name.as_str()) && undefined.insert(name.as_str()));
    let first_uses: Vec<&(String, usize)> = first_uses.collect();
    let obj = obj.display();
    for (name, line) in first_uses.iter().take(NAMED) {
        warnings.push(format!(
            "{obj}: usemtl '{}' names no material of its material libraries; the default is \
             used (line {line})",
            crate::excerpt::excerpt(name)
        ));
    }
    if let Some((name, line)) = first_uses.get(NAMED) {
        let more = first_uses.len() - NAMED;
        warnings.push(format!(
            "{obj}: {more} more usemtl names match no material of its material libraries, the \
             first '{}' (line {line}); the default is used",
            crate::excerpt::excerpt(name)
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn undefined_material_names_are_said_once_and_gathered_past_eight() {
        let mut usemtl: Vec<(String, usize)> = (0..100).map(|i| (format!("x{i}"), i + 1)).collect();
        usemtl.push(("x0".to_owned(), 500));
        usemtl.push(("known".to_owned(), 501));
        let defined = HashSet::from(["known"]);
        let mut warnings = Vec::new();
        warn_undefined(Path::new("m.obj"), &usemtl, &defined, &mut warnings);
        assert_eq!(warnings.len(), 9, "{warnings:?}");
        assert!(warnings[0].contains("'x0'") && warnings[0].contains("(line 1)"));
        assert!(
            warnings[8].contains("92 more usemtl names") && warnings[8].contains("'x8' (line 9)")
        );
    }

    #[test]
    fn mesh_indices_are_checked() {
        let mesh =
            tobj::Mesh { positions: vec![0.0; 9], indices: vec![0, 1, 3], ..Default::default() };
        assert!(mesh_data(&mesh).unwrap_err().contains("vertex index 3 is out of range"));
    }
}
