//! The METU CENG795 course's XML scene format → one `SceneDesc` per camera.
//!
//! A file holds cameras, lights, materials, a shared vertex list, named transformations and
//! objects (see each file of this module). Every camera renders its own `ImageName`, so
//! `load` returns one scene per camera, in file order, each rendered with the Whitted
//! integrator (`MaxRecursionDepth` bounces, `NumSamples` samples, `BackgroundColor`), in the
//! course's units: radiance in 0–255, written to PNG clamped and truncated
//! (`ToneMap::Clamp255`).
//!
//! `ShadowRayEpsilon` and `IntersectionTestEpsilon` are read and ignored: embray spawns
//! secondary rays with error bounds instead of a fixed offset.

mod attributes;
mod brdfs;
mod camera;
mod inline_mesh;
mod lights;
mod materials;
mod objects;
mod textures;
mod transforms;
mod vertex_data;
mod xml;

use crate::scene::desc::{IntegratorKind, RenderSettings, SceneDesc};
use crate::scene::error::{Line, SceneError};
use glam::Vec3;
use roxmltree::{Document, Node};
use std::io::Write;
use std::path::Path;
use xml::Xml;

/// One camera of a file: the image it renders and the scene as seen by it.
#[derive(Clone, Debug)]
pub struct CameraScene {
    /// The camera's `ImageName` (a PNG file name).
    pub image_name: String,
    pub scene: SceneDesc,
}

/// The recursion depth when a file gives no `MaxRecursionDepth` (the course parser's
/// default: no reflection or refraction).
pub const DEFAULT_MAX_RECURSION_DEPTH: u32 = 0;

/// The path tracer's `max_depth` (surface interactions that gather light) for a
/// path-tracing camera of a file with `MaxRecursionDepth` `depth`. The course's paths are
/// `depth` rays after the camera ray; with next-event estimation the last vertex still
/// samples the lights, which is one interaction more. Measured on the instructor's 100-spp
/// EXRs of hw6's diffuse Cornell box (depth 3): `depth + 1` with NEE is within 0.6 % of
/// diffuse_next_importance.exr (`depth` is 4.5 % darker), `depth` without NEE within 0.1 %
/// of diffuse.exr (`depth + 1` is 3.4 % brighter). With RussianRoulette the course sets no
/// limit, and neither do we (`limits::MAX_DEPTH`).
fn path_depth(depth: u32, next_event: bool) -> u32 {
    if next_event { depth + 1 } else { depth }
}

const SCENE_CHILDREN: [&str; 13] = [
    "BackgroundColor",
    "ShadowRayEpsilon",
    "IntersectionTestEpsilon",
    "MaxRecursionDepth",
    "Cameras",
    "Lights",
    "BRDFs",
    "Materials",
    "Transformations",
    "VertexData",
    "TexCoordData",
    "Textures",
    "Objects",
];

/// True if `path` names a course XML scene (by extension).
pub fn is_ceng795_path(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("xml"))
}

/// Loads the XML scene at `path`, one scene per camera. Notes about approximations (an
/// off-centre image window) and warnings go to stderr.
pub fn load(path: &Path) -> Result<Vec<CameraScene>, SceneError> {
    let (scenes, warnings) = load_with_warnings(path)?;
    for warning in &warnings {
        let _ = writeln!(std::io::stderr(), "warning: {}", crate::excerpt::terminal_safe(warning));
    }
    Ok(scenes)
}

/// As `load`, returning the warnings instead of printing them.
pub fn load_with_warnings(path: &Path) -> Result<(Vec<CameraScene>, Vec<String>), SceneError> {
    load_str_with_warnings(&crate::scene::read_scene_file(path)?, path)
}

/// Parses XML text read from `source` (used in messages and to resolve PLY paths).
pub fn load_str_with_warnings(
    text: &str,
    source: &Path,
) -> Result<(Vec<CameraScene>, Vec<String>), SceneError> {
    let reading_bytes = (text.len() as u64).saturating_mul(crate::limits::BYTES_PER_XML_BYTE);
    let what = || format!("{} bytes of XML", text.len());
    crate::scene::reading_budget::check_reading(source, reading_bytes, what)?;
    let doc = Document::parse(text).map_err(|e| SceneError::Xml {
        file: source.to_path_buf(),
        element: "the XML document".to_owned(),
        problem: format!("malformed XML: {e}"),
        line: Line(Some(e.pos().row as usize)),
    })?;
    let x = Xml { file: source, doc: &doc };
    let root = doc.root_element();
    if !root.has_tag_name("Scene") {
        return Err(x.error(root, "the root element must be <Scene>"));
    }
    x.check_children(root, &SCENE_CHILDREN)?;
    attributes::check_attributes(&x, root)?;
    let all = |name: &'static str| root.children().filter(move |n| n.has_tag_name(name));
    let mut warnings = Vec::new();

    let mut settings = RenderSettings {
        spp: 1,
        max_depth: DEFAULT_MAX_RECURSION_DEPTH,
        background: Vec3::ZERO,
        light_samples: 1,
        integrator: IntegratorKind::Whitted,
        tonemap: None,
        background_texture: None,
        filter: Default::default(),
        hide_emitters: false,
        aovs: None,
        rr_depth: crate::scene::DEFAULT_RR_DEPTH,
        ..RenderSettings::default()
    };
    if let Some(node) = x.child(root, "BackgroundColor")? {
        settings.background = x.color(node)?;
    }
    if let Some(node) = x.child(root, "MaxRecursionDepth")? {
        let depth = x.count(node)?;
        let max = crate::limits::MAX_DEPTH;
        if depth > u64::from(max) {
            return Err(x.out_of_range(node, depth, &format!("at most {max}")));
        }
        settings.max_depth = depth as u32;
    }
    for name in ["ShadowRayEpsilon", "IntersectionTestEpsilon"] {
        if let Some(node) = x.child(root, name)? {
            x.scalar(node)?; // read (so that a bad value is reported) and ignored
        }
    }

    let brdfs = brdfs::brdfs(&x, all("BRDFs"))?;
    let materials = materials::materials(&x, all("Materials"), &brdfs)?;
    let transforms = transforms::transforms(&x, all("Transformations"))?;
    // One list each: a second would shift every index after the first silently.
    let vertices = vertex_data::vertex_data(&x, x.child(root, "VertexData")?.into_iter())?;
    let texcoords = vertex_data::texcoord_data(&x, x.child(root, "TexCoordData")?.into_iter())?;
    let base_dir = source.parent().unwrap_or(Path::new(""));
    let textures = textures::texture_maps(&x, base_dir, all("Textures"))?;
    let lights = lights::lights(&x, all("Lights"), &textures)?;
    // hw4.tex: with a background texture, BackgroundColor is ignored.
    settings.background_texture = textures.background.clone();
    let refs = objects::Refs {
        base_dir,
        materials: &materials,
        transforms: &transforms,
        vertices: &vertices,
        texcoords: &texcoords,
        textures: &textures,
    };
    let objects::Objects { objects, extra_materials } =
        objects::objects(&x, &refs, all("Objects"), &mut warnings)?;
    let mut material_list = materials.list.clone();
    material_list.extend(extra_materials);

    let mut cameras = Vec::new();
    // Two cameras writing one file would silently overwrite each other's image.
    let mut outputs = std::collections::HashMap::new();
    for list in all("Cameras") {
        x.check_children(list, &["Camera"])?;
        for node in list.children().filter(Node::is_element) {
            let camera = camera::camera(&x, node)?;
            let key = crate::output::image_name_key(&camera.image_name);
            if let Some(first) = outputs.insert(key, x.line(node)) {
                return Err(x.error(
                    node,
                    format!(
                        "ImageName '{}' names the same output files as the camera{first}; \
                         every camera needs its own ImageName",
                        crate::excerpt::excerpt(&camera.image_name)
                    ),
                ));
            }
            cameras.push(camera);
        }
    }
    if cameras.is_empty() {
        return Err(x.missing(root, "Cameras > Camera"));
    }
    let scenes = cameras
        .into_iter()
        .map(|spec| {
            warnings.extend(spec.notes);
            CameraScene {
                image_name: spec.image_name,
                scene: SceneDesc {
                    source: source.to_path_buf(),
                    reading_bytes,
                    camera: spec.camera,
                    settings: RenderSettings {
                        spp: spec.spp,
                        tonemap: spec.tonemap,
                        integrator: if spec.path_tracing.is_some() {
                            IntegratorKind::Path
                        } else {
                            IntegratorKind::Whitted
                        },
                        max_depth: match spec.path_tracing {
                            Some(mode) if mode.roulette => crate::limits::MAX_DEPTH,
                            Some(mode) => path_depth(settings.max_depth, mode.next_event),
                            None => settings.max_depth,
                        },
                        ..settings.clone()
                    },
                    materials: material_list.clone(),
                    objects: objects.clone(),
                    lights: match spec.path_tracing {
                        // No path can hit a point or area light: without next-event
                        // estimation they light nothing.
                        Some(mode) if !mode.next_event => {
                            lights.iter().filter(|l| !l.only_sampled()).cloned().collect()
                        }
                        _ => lights.clone(),
                    },
                },
            }
        })
        .collect();
    Ok((scenes, warnings))
}
