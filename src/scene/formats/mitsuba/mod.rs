//! Mitsuba 3 scenes (`<scene version="3.0.0">`): the XML format of the research renderer
//! users compare with, read into the model with Mitsuba's parameter names, defaults and
//! conventions. What embray cannot render as Mitsuba would is refused with the plugin type,
//! file and line, never silently replaced.

mod attributes;
mod bsdfs;
mod cie;
mod emitters;
mod film;
mod integrator;
mod ior;
mod metals;
mod params;
mod sampler;
mod scalars;
mod sensor;
mod shapes;
mod spd;
mod spectrum;
mod transform;
mod tree;
mod values;

use crate::excerpt::excerpt;
use crate::scene::desc::{LightDesc, MaterialDesc, ObjectDesc, RenderSettings, SceneDesc};
use crate::scene::error::SceneError;
use crate::scene::mesh_file::MeshCache;
use std::cell::Cell;
use std::collections::HashMap;
use std::path::Path;
pub(super) use tree::define_error;
use tree::{Element, FileResolver};

/// Whether `text` is a Mitsuba scene: its root element is `<scene>` (lower case; the
/// course's is `<Scene>`). Declarations, comments and a DOCTYPE before it are skipped.
pub fn is_mitsuba(text: &str) -> bool {
    let mut rest = text;
    loop {
        let Some(at) = rest.find('<') else { return false };
        rest = &rest[at..];
        let skip_to = |end: &str| rest.find(end).map(|i| i + end.len());
        let skipped = if rest.starts_with("<?") {
            skip_to("?>")
        } else if rest.starts_with("<!--") {
            skip_to("-->")
        } else if rest.starts_with("<!") {
            skip_to(">")
        } else {
            let name: String =
                rest[1..].chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            return name == "scene";
        };
        match skipped {
            Some(end) => rest = &rest[end..],
            None => return false,
        }
    }
}

/// Objects with an `id`, for `<ref>`.
pub(super) struct Ids {
    by_id: HashMap<String, Element>,
    /// BSDFs being read inside one another (`nested`).
    nesting: Cell<usize>,
}

impl Ids {
    /// `read` (the BSDFs inside `element`) one level deeper: refused past
    /// `MAX_BSDF_NESTING`.
    fn nested<T>(
        &self,
        element: &Element,
        read: impl FnOnce() -> Result<T, SceneError>,
    ) -> Result<T, SceneError> {
        let level = self.nesting.get();
        if level >= crate::limits::MAX_BSDF_NESTING {
            return Err(element.error(format!(
                "BSDFs nest deeper than {} (does a <ref> lead back to a BSDF that holds it?)",
                crate::limits::MAX_BSDF_NESTING
            )));
        }
        self.nesting.set(level + 1);
        let read = read();
        self.nesting.set(level);
        read
    }

    /// The BSDF `element` is or refers to.
    fn bsdf<'a>(&'a self, element: &'a Element) -> Result<&'a Element, SceneError> {
        let found = self.resolve(element)?;
        if found.tag != "bsdf" {
            return Err(element.error(format!(
                "'{}' is a <{}>, not a <bsdf>",
                found.describe(),
                found.tag
            )));
        }
        Ok(found)
    }

    /// The object `element` is, or the one it refers to (`<ref id=…>`).
    fn resolve<'a>(&'a self, element: &'a Element) -> Result<&'a Element, SceneError> {
        if element.tag != "ref" {
            return Ok(element);
        }
        let id = element.required("id")?;
        match self.by_id.get(id) {
            Some(found) => Ok(found),
            None => {
                let mut known: Vec<&str> = self.by_id.keys().map(String::as_str).collect();
                known.sort();
                let mut listed: Vec<String> = known.iter().take(10).map(|k| excerpt(k)).collect();
                if known.len() > 10 {
                    listed.push(format!("and {} more", known.len() - 10));
                }
                let known = if listed.is_empty() { "none".to_owned() } else { listed.join(", ") };
                Err(element
                    .error(format!("no object has the id '{}' (known: {known})", excerpt(id))))
            }
        }
    }
}

struct Builder<'a> {
    files: &'a FileResolver,
    ids: Ids,
    meshes: MeshCache,
    /// Each mesh file's model as Mitsuba reads it (`shapes::winding::Prepared`), made once
    /// however many shapes name it, so that they share it.
    prepared: shapes::Prepared,
    warnings: &'a mut Vec<String>,
    materials: Vec<MaterialDesc>,
    /// The material made for each BSDF id, for shapes that share it.
    shared_materials: HashMap<String, u32>,
    objects: Vec<ObjectDesc>,
    lights: Vec<LightDesc>,
    /// The objects of each shapegroup by id, in the group's space.
    groups: HashMap<String, Vec<ObjectDesc>>,
}

/// The Mitsuba scene in `text` (read from `path`), with `-D name=value` parameters.
pub fn load(
    path: &Path,
    text: &str,
    defines: &[(String, String)],
) -> Result<(SceneDesc, Vec<String>), SceneError> {
    // Mitsuba sorts its parameters by name length with an unstable sort: which of two
    // values of one name it substitutes is not defined.
    for (at, define) in defines.iter().enumerate() {
        if let Some(first) = defines[..at].iter().find(|(name, _)| *name == define.0) {
            let problem = format!(
                "`{}` is given twice (first as {}): Mitsuba leaves which value it uses \
                 undefined; give it once",
                crate::excerpt::excerpt(&define.0),
                crate::excerpt::excerpt(&first.1)
            );
            return Err(define_error(path, define, problem));
        }
    }
    let (root, files, reading_bytes) = tree::read(path, text, defines)?;
    let mut warnings = Vec::new();
    transform::axis_warnings(&root, &mut warnings);
    let mut by_id = HashMap::new();
    for child in &root.children {
        if let Some(id) = child.attr("id") {
            if by_id.insert(id.to_owned(), child.clone()).is_some() {
                return Err(child.error(format!("the id '{id}' is given twice")));
            }
        }
    }
    let mut settings = RenderSettings { max_depth: crate::limits::MAX_DEPTH, ..Default::default() };
    let mut sensor = None;
    values::refuse_second(&root, "integrator", "a scene")?;
    let mut builder = Builder {
        files: &files,
        ids: Ids { by_id, nesting: Cell::new(0) },
        // Mitsuba's `recompute_vertex_normals`.
        meshes: MeshCache::new(crate::scene::VertexNormals::AngleWeighted),
        prepared: shapes::Prepared::default(),
        warnings: &mut warnings,
        materials: Vec::new(),
        shared_materials: HashMap::new(),
        objects: Vec::new(),
        lights: Vec::new(),
        groups: HashMap::new(),
    };
    for child in &root.children {
        match child.tag.as_str() {
            "integrator" => integrator::integrator(child, &mut settings, builder.warnings)?,
            "sensor" => {
                if sensor.is_some() {
                    return Err(child.error("embray renders one sensor per scene"));
                }
                sensor = Some(sensor::sensor(child, builder.warnings)?);
            }
            "shape" => builder.shape(child)?,
            // An area emitter with an id is one a shape refers to.
            "emitter" if child.attr("type") == Some("area") && child.attr("id").is_some() => {}
            "emitter" => builder.emitter(child)?,
            // Read where they are used (by reference).
            "bsdf" | "texture" => {}
            other => {
                let kind = child.attr("type").map(|t| format!(" '{t}'")).unwrap_or_default();
                return Err(child.error(format!(
                    "<{other}>{kind} is not supported (media, polarisation and spectral-only \
                     features are not)"
                )));
            }
        }
    }
    let sensor = sensor.ok_or_else(|| root.error("the scene has no <sensor>"))?;
    // Mitsuba's default sampler: independent, 4 samples, seed 0.
    let sampler = sensor.sampler.unwrap_or_default();
    settings.spp = sampler.sample_count;
    settings.seed = sampler.seed;
    settings.jitter = sampler.jitter;
    settings.filter = sensor.filter;
    settings.sides = crate::scene::Sides::Shading;
    settings.crop = sensor.crop;
    let Builder { materials, objects, lights, .. } = builder;
    let scene = SceneDesc {
        source: path.to_path_buf(),
        reading_bytes,
        camera: sensor.camera,
        settings,
        materials,
        objects,
        lights,
    };
    Ok((scene, warnings))
}

#[cfg(test)]
mod tests {
    use super::is_mitsuba;

    #[test]
    fn the_root_element_tells_the_formats_apart() {
        assert!(is_mitsuba(
            "<?xml version=\"1.0\"?>\n<!-- a <Scene> -->\n<scene version=\"3.0.0\"/>"
        ));
        assert!(is_mitsuba("<scene version='2.0.0'>"));
        assert!(!is_mitsuba("<!-- <scene version=\"3.0.0\"> -->\n<Scene>"));
        assert!(!is_mitsuba("<Scene><!-- <scene> --></Scene>"));
        assert!(!is_mitsuba("<scenes/>"));
        assert!(!is_mitsuba("no XML here"));
    }
}
