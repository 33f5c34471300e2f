//! The deserialised file (`toml_format`) → a validated `SceneDesc`: objects (with motion and
//! repeat grids) and lights, each checked with its field path and line (camera and settings:
//! `camera_settings`; materials: `materials`).

pub(crate) mod camera;
pub(crate) mod format;
mod lights;
pub(crate) mod materials;
mod repeat;
pub(crate) mod source_map;
pub(crate) mod transform_list;
pub(crate) mod validate;
pub mod write;

use crate::excerpt::excerpt;
use crate::scene::desc::{LightDesc, MaterialDesc, ObjectDesc, SceneDesc, ShapeDesc};
use crate::scene::error::SceneError;
use crate::scene::formats::obj::ObjRef;
use crate::scene::formats::toml::camera::{camera, settings};
use crate::scene::formats::toml::format::{
    ObjectKind, ObjectToml, RepeatToml, SceneFile, TransformEntry, Vec3,
};
use crate::scene::formats::toml::source_map::FieldPath;
use crate::scene::formats::toml::validate::Ctx;
use crate::scene::mesh_file::MeshCache;
use crate::scene::shapes::{box_mesh, quad_mesh};
use glam::{DAffine3, DVec3};
use repeat::{Grid, Placement};
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use transform_list::fmt_vec;

/// The most copies one `repeat` may make (each costs about `limits::BYTES_PER_OBJECT`).
pub const MAX_REPEAT_COPIES: u64 = 1_000_000;

/// Copies of a `repeat` grid up to this many are named `... copy (i,j,k)`; those of larger
/// grids are all named `... copy`.
const NAMED_COPIES: usize = 1_000_000;

/// Parses TOML scene text read from `source` (messages name it; relative paths resolve from
/// its folder) into the model, with the warnings.
pub(crate) fn load_str_with_warnings(
    text: &str,
    source: &Path,
) -> Result<(SceneDesc, Vec<String>), SceneError> {
    let map = source_map::SourceMap::parse(text, source)?;
    map.check_finite(source)?;
    let file: SceneFile = ::toml::from_str(text).map_err(|e| source_map::toml_error(source, &e))?;
    let ctx = Ctx { file: source, map };
    let base_dir = source.parent().unwrap_or(Path::new(""));
    let mut warnings = Vec::new();
    let scene = scene_desc(file, &ctx, base_dir, &mut warnings)?;
    Ok((scene, warnings))
}

/// Builds the scene; `base_dir` resolves relative mesh paths, `warnings` collects non-fatal
/// problems (a missing MTL file).
pub(crate) fn scene_desc(
    file: SceneFile,
    ctx: &Ctx,
    base_dir: &Path,
    warnings: &mut Vec<String>,
) -> Result<SceneDesc, SceneError> {
    let camera = camera(&file.camera, ctx)?;
    let mut settings = settings(file.render.as_ref(), ctx)?;
    if let Some(t) = file.render.as_ref().and_then(|r| r.background_texture.as_ref()) {
        settings.background_texture = Some(materials::background_texture(t, ctx, base_dir)?);
    }
    let mut builder = Builder {
        ctx,
        base_dir,
        warnings,
        materials: Vec::new(),
        named: BTreeMap::new(),
        default_material: None,
        mtl_materials: HashMap::new(),
        meshes: MeshCache::default(),
        objects: Vec::new(),
        lights: Vec::new(),
    };
    for (name, material) in &file.materials {
        let material = materials::material(name, material, ctx, base_dir)?;
        let index = builder.add_material(material);
        builder.named.insert(name.clone(), index);
    }
    let mut bounds = crate::scene::budget::MeshBounds::default();
    for (i, object) in file.objects.iter().enumerate() {
        let first = builder.objects.len();
        builder.object(i, object)?;
        // Beyond the supported range now, with the line: measured from the camera, as the
        // default render space (cameraworld) measures it, which no --offset changes. The
        // render checks again in its render space (world space measures from the origin).
        let path = FieldPath::root("objects").index(i);
        for placed in &builder.objects[first..] {
            let from_camera =
                crate::scene::budget::object_reach_from(placed, &mut bounds, camera.lookfrom);
            let reach = crate::scene::budget::object_reach(placed, &mut bounds);
            let (max, world_max) =
                (crate::limits::MAX_COORDINATE, crate::limits::MAX_WORLD_COORDINATE);
            // A `repeat` copy is named by its grid index and a mesh by its file (and model),
            // so that the message names the file whose vertices are out of range; a plain
            // object is named by `path` alone. The name goes into the requirement, which is
            // not shortened as the value is.
            let which = match placed.name == path.to_string() {
                true => String::new(),
                false => format!(" (at the farthest corner of {})", excerpt(&placed.name)),
            };
            let requirement =
                format!("within the supported coordinate range ±{max:e} of the camera{which}");
            let value = format!("{from_camera:e} from the camera");
            ctx.require(from_camera <= max, &path, value, &requirement)?;
            let requirement =
                format!("within the supported world coordinate range ±{world_max:e}{which}");
            let value = format!("{reach:e} from the origin");
            ctx.require(reach <= world_max, &path, value, &requirement)?;
        }
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
    pub(super) fn light_material(&mut self, item: &str, emission: glam::Vec3) -> u32 {
        self.add_material(MaterialDesc {
            name: item.to_owned(),
            albedo: glam::Vec3::ZERO,
            emission,
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
        Ok(Placement { start, end })
    }

    /// Validates `repeat`: counts >= 1, at most `MAX_REPEAT_COPIES` in all, and the farthest
    /// copy still at a finite position.
    pub(super) fn grid(
        &self,
        path: &FieldPath,
        repeat: Option<&RepeatToml>,
        placement: &Placement,
    ) -> Result<Option<Grid>, SceneError> {
        let Some(repeat) = repeat else { return Ok(None) };
        let count_path = path.key("repeat").key("count");
        for (i, &n) in repeat.count.iter().enumerate() {
            self.ctx.require(n >= 1, &count_path.index(i), n, ">= 1")?;
        }
        let total: u64 = repeat.count.iter().map(|&n| u64::from(n)).product();
        let [nx, ny, nz] = repeat.count;
        self.ctx.require(
            total <= MAX_REPEAT_COPIES,
            &count_path,
            format!("{nx} × {ny} × {nz} = {total} copies"),
            &format!("at most {MAX_REPEAT_COPIES} copies"),
        )?;
        let grid = Grid { count: repeat.count, spacing: dvec(repeat.spacing) };
        let farthest = (DVec3::new(nx as f64, ny as f64, nz as f64) - 1.0) * grid.spacing;
        let far = placement.shifted(farthest);
        if !farthest.is_finite()
            || !far.start.translation.is_finite()
            || far.end.is_some_and(|end| !end.translation.is_finite())
        {
            let field = path.key("repeat").key("spacing");
            return Err(SceneError::Transform {
                file: self.ctx.file.to_path_buf(),
                field: field.to_string(),
                problem: format!(
                    "the farthest copy's position overflows (spacing {} × count {})",
                    fmt_vec(&repeat.spacing),
                    fmt_vec(&repeat.count.map(f64::from))
                ),
                line: self.ctx.line(&field),
            });
        }
        Ok(Some(grid))
    }

    /// Adds the object, or one per copy of `grid`, all sharing `shape`.
    pub(super) fn push(
        &mut self,
        name: String,
        shape: ShapeDesc,
        material: u32,
        placement: Placement,
        grid: Option<Grid>,
    ) {
        let object = |name: String, shape: ShapeDesc, placement: Placement| ObjectDesc {
            name,
            shape,
            material,
            world_from_object: placement.start,
            world_from_object_end: placement.end,
        };
        match grid {
            None => self.objects.push(object(name, shape, placement)),
            Some(grid) => {
                self.objects.reserve(grid.total());
                // Formatting a name per copy costs more than the rest of the copy; beyond
                // `NAMED_COPIES` the copies share one name.
                let named = grid.total() <= NAMED_COPIES;
                let shared_name = format!("{name} copy");
                for ([i, j, k], offset) in grid.offsets() {
                    let name = if named {
                        format!("{name} copy ({i},{j},{k})")
                    } else {
                        shared_name.clone()
                    };
                    self.objects.push(object(name, shape.clone(), placement.shifted(offset)));
                }
            }
        }
    }

    pub(super) fn degenerate(&self, path: &FieldPath, item: &str, problem: String) -> SceneError {
        SceneError::DegenerateShape {
            file: self.ctx.file.to_path_buf(),
            item: item.to_owned(),
            problem,
            line: self.ctx.line(path),
        }
    }

    pub(super) fn object(&mut self, i: usize, o: &ObjectToml) -> Result<(), SceneError> {
        let path = FieldPath::root("objects").index(i);
        const PLACED: [&str; 4] = ["type", "transform", "transform_end", "repeat"];
        let (kind, own): (&str, &[&str]) = match o.kind {
            ObjectKind::Quad => ("quad", &["material", "corner", "u", "v"]),
            ObjectKind::Sphere => ("sphere", &["material", "center", "radius"]),
            ObjectKind::Box => ("box", &["material", "min", "max"]),
            ObjectKind::Mesh => ("mesh", &["material", "file", "smooth"]),
        };
        let allowed: Vec<&str> = PLACED.iter().chain(own).copied().collect();
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
            ("smooth", o.smooth.is_some()),
        ];
        let ctx = self.ctx;
        ctx.check_fields(&path, &item, &present, &allowed)?;
        let placement = self.placement(&path, o)?;
        let grid = self.grid(&path, o.repeat.as_ref(), &placement)?;
        let material = o
            .material
            .as_deref()
            .map(|name| self.lookup_material(&path.key("material"), name))
            .transpose()?;
        let shape = match o.kind {
            ObjectKind::Mesh => {
                let file = ctx.required(&path, &item, "file", o.file.as_deref())?;
                return self.mesh_objects(&path, file, o.smooth, material, placement, grid);
            }
            ObjectKind::Quad => {
                let corner = ctx.required(&path, &item, "corner", o.corner)?;
                let u = ctx.required(&path, &item, "u", o.u)?;
                let v = ctx.required(&path, &item, "v", o.v)?;
                let mesh = quad_mesh(dvec(corner), dvec(u), dvec(v))
                    .map_err(|p| self.degenerate(&path, &item, p))?;
                ShapeDesc::Mesh(Arc::new(mesh))
            }
            ObjectKind::Sphere => {
                // Any non-singular transform is allowed: the renderer instances a unit sphere
                // for ellipsoids.
                let center = ctx.required(&path, &item, "center", o.center)?;
                let radius = ctx.required(&path, &item, "radius", o.radius)?;
                let radius = ctx.positive(&path.key("radius"), radius)?;
                ShapeDesc::Sphere { center: dvec(center), radius }
            }
            ObjectKind::Box => {
                let min = ctx.required(&path, &item, "min", o.min)?;
                let max = ctx.required(&path, &item, "max", o.max)?;
                let mesh =
                    box_mesh(dvec(min), dvec(max)).map_err(|p| self.degenerate(&path, &item, p))?;
                ShapeDesc::Mesh(Arc::new(mesh))
            }
        };
        let material = ctx.required(&path, &item, "material", material)?;
        self.push(item, shape, material, placement, grid);
        Ok(())
    }

    /// One object per model of the mesh file (an OBJ file has one per material), times the
    /// copies of `grid`. `material` overrides the MTL materials.
    pub(super) fn mesh_objects(
        &mut self,
        path: &FieldPath,
        file: &str,
        smooth: Option<bool>,
        material: Option<u32>,
        placement: Placement,
        grid: Option<Grid>,
    ) -> Result<(), SceneError> {
        let mesh_ref = mesh_ref(self.ctx, self.base_dir, path, file);
        let (key, models) = self.meshes.models(&mesh_ref, smooth, self.warnings)?;
        for model in models {
            let index = match (material, model.material) {
                (Some(index), _) => index,
                (None, Some((m, mtl))) => match self.mtl_materials.get(&(key.clone(), m)) {
                    Some(&index) => index,
                    None => {
                        let index = self.add_material(MaterialDesc {
                            name: format!("{file}: {}", mtl.name),
                            albedo: mtl.albedo,
                            emission: mtl.emission,
                            ..Default::default()
                        });
                        self.mtl_materials.insert((key.clone(), m), index);
                        index
                    }
                },
                (None, None) => self.default_material(),
            };
            let name = match &model.name {
                Some(model_name) => format!("{path} ({file}: {model_name})"),
                None => format!("{path} ({file})"),
            };
            self.push(name, ShapeDesc::Mesh(model.mesh), index, placement, grid);
        }
        Ok(())
    }
}
