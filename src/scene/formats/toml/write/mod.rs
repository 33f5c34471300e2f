//! `SceneDesc` → the native TOML format, with meshes as OBJ files in a folder beside it: the
//! inverse of `scene::load` for what the format can express (used by `embray convert`).
//!
//! Placements are written as `matrix` transforms (exact in f64; shutter-close placements as
//! `transform_end`), objects sharing one `Arc<MeshData>` name one OBJ file (so they stay
//! instances), and every camera, render, material and light field has its TOML key. OBJ
//! coordinates are read back through tobj in f32, so mesh vertices round to f32 on the way
//! back (the rest is exact). What the format cannot express is an error naming the item:
//! an albedo or mirror reflectance above 1, a Phong exponent of 0 with a non-zero specular
//! colour, a texture mapped through a non-identity transform.

use crate::scene::desc::IntegratorKind;
use crate::scene::desc::{LensShape, MeshData, SceneDesc, ShapeDesc};
use glam::DAffine3;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;

#[derive(Debug, thiserror::Error)]
pub enum TomlWriteError {
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
    #[error("{item}: {problem}, which the TOML format cannot express")]
    Unsupported { item: String, problem: String },
}

impl TomlWriteError {
    /// The error of a part of `outer` (a material, the scene file): its item says where.
    fn within(self, outer: &str) -> Self {
        match self {
            TomlWriteError::Unsupported { item, problem } if !item.starts_with(outer) => {
                TomlWriteError::Unsupported { item: format!("{outer}: {item}"), problem }
            }
            other => other,
        }
    }
}

/// Writes scenes as TOML, sharing one mesh folder between them.
pub struct TomlWriter {
    mesh_dir: PathBuf,
    /// OBJ file written for each mesh, by `Arc` identity (the `Arc` is kept so that the
    /// address cannot be reused by another mesh).
    meshes: HashMap<*const MeshData, (Arc<MeshData>, PathBuf)>,
    mesh_files: Vec<PathBuf>,
    /// OBJ texts named by the TOML produced so far and not yet written.
    pending_meshes: Vec<(PathBuf, String)>,
}

mod materials;
mod principled;
mod textures;
mod values;

use materials::{material_names, write_material};
use textures::texture_toml;
use values::{c3, f, matrix, quoted, v3};

impl TomlWriter {
    /// Meshes go to `mesh_dir` (created on first use).
    pub fn new(mesh_dir: PathBuf) -> Self {
        TomlWriter {
            mesh_dir,
            meshes: HashMap::new(),
            mesh_files: Vec::new(),
            pending_meshes: Vec::new(),
        }
    }

    /// The OBJ files named so far.
    pub fn mesh_files(&self) -> &[PathBuf] {
        &self.mesh_files
    }

    /// The OBJ files (path, text) that the TOML produced since the last call names and
    /// that are still to be written.
    pub fn take_pending_meshes(&mut self) -> Vec<(PathBuf, String)> {
        std::mem::take(&mut self.pending_meshes)
    }

    /// Writes `scene` to `path` (with `note` as a comment at the top) and any mesh not yet
    /// written, all committed together (`embray convert` checks its paths first instead).
    pub fn write(
        &mut self,
        scene: &SceneDesc,
        path: &Path,
        note: &str,
    ) -> Result<(), TomlWriteError> {
        use crate::output::{OutputPlan, OutputSet};
        let text = self.toml(scene, path, note)?;
        let mut plan = OutputPlan::new();
        let mut files = OutputSet::new();
        let target = plan.output("the TOML file", path, false)?;
        files.write(&target, |w| w.write_all(text.as_bytes()))?;
        for (mesh, obj) in self.take_pending_meshes() {
            let target = plan.output("the OBJ file", &mesh, true)?;
            files.write(&target, |w| w.write_all(obj.as_bytes()))?;
        }
        Ok(files.commit()?)
    }

    /// The TOML text for `scene`, to be written at `path` (mesh paths are relative to it);
    /// what it cannot express is named with the scene's file.
    pub fn toml(
        &mut self,
        scene: &SceneDesc,
        path: &Path,
        note: &str,
    ) -> Result<String, TomlWriteError> {
        let source = scene.source.display().to_string();
        self.toml_text(scene, path, note).map_err(|e| e.within(&source))
    }

    fn toml_text(
        &mut self,
        scene: &SceneDesc,
        path: &Path,
        note: &str,
    ) -> Result<String, TomlWriteError> {
        let mut out = String::new();
        for line in note.lines() {
            let _ = writeln!(out, "# {line}");
        }
        camera_and_render(scene, &mut out)?;
        let names = material_names(&scene.materials);
        for (material, name) in scene.materials.iter().zip(&names) {
            write_material(material, name, &mut out)
                .map_err(|e| e.within(&format!("material '{name}'")))?;
        }
        let toml_dir = path.parent().unwrap_or(Path::new(""));
        for object in &scene.objects {
            out += "\n[[objects]]\n";
            match &object.shape {
                ShapeDesc::Mesh(mesh) => {
                    let file = self.mesh_file(mesh)?;
                    let relative = file.strip_prefix(toml_dir).unwrap_or(&file);
                    let relative = relative.to_string_lossy().replace('\\', "/");
                    let _ = writeln!(out, "type = \"mesh\"\nfile = {}", quoted(&relative));
                }
                ShapeDesc::Sphere { center, radius } => {
                    let _ = writeln!(
                        out,
                        "type = \"sphere\"\ncenter = {}\nradius = {}",
                        v3(*center),
                        f(*radius)
                    );
                }
                ShapeDesc::SdfGrid(_) => {
                    return Err(TomlWriteError::Unsupported {
                        item: object.name.clone(),
                        problem: "a signed distance grid (sdfgrid) has no TOML form".into(),
                    });
                }
            }
            let _ = writeln!(out, "material = {}", quoted(&names[object.material as usize]));
            if object.world_from_object != DAffine3::IDENTITY {
                let _ = writeln!(out, "transform = {}", matrix(&object.world_from_object));
            }
            if let Some(end) = &object.world_from_object_end {
                let _ = writeln!(out, "transform_end = {}", matrix(end));
            }
        }
        for light in &scene.lights {
            out += "\n[[lights]]\n";
            light.write(&mut values::TomlLines(&mut out));
        }
        Ok(out)
    }

    /// The OBJ file of `mesh`, written on first use.
    fn mesh_file(&mut self, mesh: &Arc<MeshData>) -> Result<PathBuf, TomlWriteError> {
        if let Some((_, file)) = self.meshes.get(&Arc::as_ptr(mesh)) {
            return Ok(file.clone());
        }
        let file = self.mesh_dir.join(format!("mesh_{}.obj", self.mesh_files.len()));
        self.pending_meshes.push((file.clone(), obj_text(mesh)));
        self.meshes.insert(Arc::as_ptr(mesh), (Arc::clone(mesh), file.clone()));
        self.mesh_files.push(file.clone());
        Ok(file)
    }
}

fn camera_and_render(scene: &SceneDesc, out: &mut String) -> Result<(), TomlWriteError> {
    let c = &scene.camera;
    let _ = writeln!(
        out,
        "\n[camera]\nlookfrom = {}\nlookat = {}\nup = {}\nvfov = {}\nresolution = [{}, {}]",
        v3(c.lookfrom),
        v3(c.lookat),
        v3(c.up),
        f(c.vfov_deg),
        c.width,
        c.height
    );
    if c.aperture > 0.0 {
        let _ = writeln!(out, "aperture = {}", f(c.aperture));
    }
    if c.lens_shape == LensShape::Square {
        out.push_str("lens = \"square\"\n");
    }
    if let Some(d) = c.focus_distance {
        let _ = writeln!(out, "focus_distance = {}", f(d));
    }
    if c.shift != glam::DVec2::ZERO {
        let _ = writeln!(out, "shift = [{}, {}]", f(c.shift.x), f(c.shift.y));
    }
    if c.pixel_aspect != 1.0 {
        let _ = writeln!(out, "pixel_aspect = {}", f(c.pixel_aspect));
    }
    if c.mirrored {
        out.push_str("mirrored = true\n");
    }
    let (near, far) = c.clip;
    if near > 0.0 || far.is_finite() {
        let _ = writeln!(out, "clip = [{}, {}]", f(near), f(far));
    }
    if c.ortho_half_height.is_some() {
        return Err(TomlWriteError::Unsupported {
            item: "the camera".to_owned(),
            problem: "it is orthographic".to_owned(),
        });
    }
    let s = &scene.settings;
    if let Some(aovs) = s.aovs {
        // The TOML format has no AOV setting: without this, the converted scene would
        // render other channels than its source, unsaid.
        return Err(TomlWriteError::Unsupported {
            item: "the render settings".to_owned(),
            problem: format!(
                "the scene asks for the AOVs '{aovs}' (Mitsuba's aov integrator; `render \
                 --aovs {aovs}` gives them)"
            ),
        });
    }
    let integrator = match s.integrator {
        IntegratorKind::Path => "path",
        IntegratorKind::Whitted => "whitted",
    };
    let _ = writeln!(
        out,
        "\n[render]\nspp = {}\nmax_depth = {}\nbackground = {}\nlight_samples = {}\nintegrator = \"{integrator}\"",
        s.spp,
        s.max_depth,
        c3(s.background),
        s.light_samples
    );
    match s.filter {
        crate::sampling::filter::PixelFilter::Box => {}
        crate::sampling::filter::PixelFilter::Gaussian { stddev } => {
            let _ = writeln!(out, "filter = {{ type = \"gaussian\", stddev = {stddev:?} }}");
        }
        crate::sampling::filter::PixelFilter::Tent { radius } => {
            let _ = writeln!(out, "filter = {{ type = \"tent\", radius = {radius:?} }}");
        }
        crate::sampling::filter::PixelFilter::Mitchell { b, c } => {
            let _ = writeln!(out, "filter = {{ type = \"mitchell\", b = {b:?}, c = {c:?} }}");
        }
        crate::sampling::filter::PixelFilter::Lanczos { lobes } => {
            let _ = writeln!(out, "filter = {{ type = \"lanczos\", lobes = {lobes:?} }}");
        }
    }
    if let Some(t) = s.crop {
        let _ = writeln!(out, "crop = [{}, {}, {}, {}]", t.x0, t.y0, t.x1, t.y1);
    }
    if s.rr_depth != crate::scene::DEFAULT_RR_DEPTH {
        let _ = writeln!(out, "rr_depth = {}", s.rr_depth);
    }
    if s.seed != 0 {
        let _ = writeln!(out, "seed = {}", s.seed);
    }
    if !s.jitter {
        let _ = writeln!(out, "jitter = false");
    }
    if s.hide_emitters {
        let _ = writeln!(out, "hide_emitters = true");
    }
    if s.sides == crate::scene::Sides::Shading {
        let _ = writeln!(out, "sides = \"shading\"");
    }
    if let Some(t) = &s.background_texture {
        let _ = writeln!(out, "background_texture = {}", texture_toml(t, false)?);
    }
    if let Some(t) = &s.tonemap {
        let _ = writeln!(
            out,
            "tonemap = {{ operator = \"photographic\", key = {}, burn_out = {}, saturation = {}, gamma = {} }}",
            f(f64::from(t.key)),
            f(f64::from(t.burn_out)),
            f(f64::from(t.saturation)),
            f(f64::from(t.gamma))
        );
    }
    Ok(())
}

fn obj_text(mesh: &MeshData) -> String {
    let mut out = String::with_capacity(mesh.positions.len() * 40 + mesh.indices.len() * 24);
    for p in &mesh.positions {
        let _ = writeln!(out, "v {} {} {}", f(p.x), f(p.y), f(p.z));
    }
    if let Some(normals) = &mesh.normals {
        for n in normals {
            let _ = writeln!(out, "vn {} {} {}", f(n.x), f(n.y), f(n.z));
        }
    }
    if let Some(uvs) = &mesh.uvs {
        for t in uvs {
            let _ = writeln!(out, "vt {:?} {:?}", t.x, t.y);
        }
    }
    let (n, t) = (mesh.normals.is_some(), mesh.uvs.is_some());
    for tri in &mesh.indices {
        out.push('f');
        for &i in tri {
            let i = i + 1;
            let _ = match (t, n) {
                (false, false) => write!(out, " {i}"),
                (true, false) => write!(out, " {i}/{i}"),
                (false, true) => write!(out, " {i}//{i}"),
                (true, true) => write!(out, " {i}/{i}/{i}"),
            };
        }
        out.push('\n');
    }
    out
}
