//! embray's TOML scene format → a validated `SceneDesc`. The stages: TOML syntax with the
//! line of every key (`source_map`), a scan rejecting every NaN/inf, serde into `format`
//! (unknown keys are errors), then the model, each item checked with its field path and
//! line: camera and settings (`camera`), materials (`materials`), objects with motion and
//! repeat grids (`objects`), lights (`lights`). `write` is the inverse, for `embray convert`.

mod builder;
pub(crate) mod camera;
pub(crate) mod format;
mod lights;
pub(crate) mod materials;
mod objects;
mod repeat;
pub(crate) mod source_map;
pub(crate) mod transform_list;
pub(crate) mod validate;
mod whitted;
pub mod write;

use crate::excerpt::excerpt;
use crate::scene::desc::SceneDesc;
use crate::scene::error::SceneError;
use crate::scene::formats::toml::camera::{camera, settings};
use crate::scene::formats::toml::format::SceneFile;
use crate::scene::formats::toml::source_map::FieldPath;
use crate::scene::formats::toml::validate::Ctx;
use crate::scene::mesh_file::MeshCache;
use builder::Builder;
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// Parses TOML scene text read from `source` (messages name it; relative paths resolve from
/// its folder) into the model, with the warnings.
pub(crate) fn load_str_with_warnings(
    text: &str,
    source: &Path,
) -> Result<(SceneDesc, Vec<String>), SceneError> {
    let parsing = (text.len() as u64).saturating_mul(crate::limits::BYTES_PER_TOML_BYTE);
    let what = || format!("{} bytes of TOML", text.len());
    crate::scene::reading_budget::check_reading(source, parsing, what)?;
    let map = source_map::SourceMap::new(text);
    let file: SceneFile = map.read(source)?;
    let materials = file.materials.len() as u64;
    let needed = parsing.saturating_add(materials * crate::limits::BYTES_PER_MATERIAL);
    let what = || format!("{} bytes of TOML, {materials} materials", text.len());
    crate::scene::reading_budget::check_reading(source, needed, what)?;
    let ctx = Ctx { file: source, map };
    let base_dir = source.parent().unwrap_or(Path::new(""));
    let mut warnings = Vec::new();
    let mut scene = scene_desc(file, &ctx, base_dir, &mut warnings)?;
    scene.reading_bytes = (text.len() as u64).saturating_mul(crate::limits::BYTES_PER_TEXT_BYTE);
    Ok((scene, warnings))
}

pub use objects::MAX_REPEAT_COPIES;

/// Builds the scene; `base_dir` resolves relative mesh paths, `warnings` collects non-fatal
/// problems (a missing MTL file).
pub(crate) fn scene_desc<'a>(
    file: SceneFile,
    ctx: &'a Ctx<'a>,
    base_dir: &'a Path,
    warnings: &'a mut Vec<String>,
) -> Result<SceneDesc, SceneError> {
    let camera = camera(&file.camera, ctx)?;
    let mut settings = settings(file.render.as_ref(), &camera, ctx)?;
    if let Some(t) = file.render.as_ref().and_then(|r| r.background_texture.as_ref()) {
        settings.background_texture = Some(materials::background_texture(t, ctx, base_dir)?);
    }
    let mut builder = Builder {
        ctx,
        base_dir,
        warnings,
        // Exactly as many as the file has (and the default material): a vector doubling to
        // 100,000 materials would hold twice their size while it moves them.
        materials: Vec::with_capacity(file.materials.len() + 1),
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
    materials::resolve_blends(&file.materials, &mut builder)?;
    let mut bounds = crate::scene::budget::MeshBounds::default();
    for (i, object) in file.objects.iter().enumerate() {
        let first = builder.objects.len();
        builder.object(i, object)?;
        // Beyond the supported range now, with the line: measured from the camera, as the
        // default render space (cameraworld) measures it, which no --offset changes. The
        // render checks again in its render space (world space measures from the origin).
        let path = FieldPath::root("objects").index(i);
        if settings.integrator == crate::scene::desc::IntegratorKind::Whitted {
            let placed = &builder.objects[first..];
            whitted::check_objects(ctx, i, placed, &builder.materials, &builder.named)?;
        }
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
        reading_bytes: 0,
        camera,
        settings,
        materials: builder.materials,
        objects: builder.objects,
        lights: builder.lights,
    })
}
