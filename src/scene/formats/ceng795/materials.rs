//! `<Materials>` → `MaterialDesc`s and the map from material id to index.
//!
//! Every material has the course's Phong terms (AmbientReflectance, SpecularReflectance,
//! PhongExponent) and a diffuse reflectance (our `albedo`; it may exceed 1). The `type`
//! attribute adds one specular part: `mirror` (MirrorReflectance, no Fresnel), `conductor`
//! (Fresnel from RefractionIndex + i·AbsorptionIndex, times MirrorReflectance) or
//! `dielectric` (RefractionIndex, Beer absorption AbsorptionCoefficient). MirrorReflectance
//! of a material without a type is ignored, as in the course. `Roughness` is the side of the
//! square in which the course perturbs reflected directions. A `BRDF` attribute names one
//! of hw6's `<BRDFs>`: its model and exponent replace the Blinn-Phong highlight and
//! PhongExponent; Torrance-Sparrow's Fresnel takes RefractionIndex and AbsorptionIndex.
//! `degamma="true"` (hw5) raises the four reflectances to the power 2.2 first.

use super::brdfs::{BrdfModel, BrdfSpec};
use super::xml::Xml;
use crate::excerpt::excerpt;
use crate::scene::desc::{CourseBrdf, MaterialDesc, PhongDesc, Specular};
use crate::scene::error::SceneError;
use glam::Vec3;
use roxmltree::Node;
use std::collections::HashMap;

const ALLOWED: [&str; 10] = [
    "AmbientReflectance",
    "DiffuseReflectance",
    "SpecularReflectance",
    "PhongExponent",
    "MirrorReflectance",
    "RefractionIndex",
    "AbsorptionIndex",
    "AbsorptionCoefficient",
    "Roughness",
    "Transparency",
];

/// The materials of every `<Materials>` element, and their ids.
pub(super) struct Materials {
    pub list: Vec<MaterialDesc>,
    pub ids: HashMap<String, u32>,
    /// Materials that may be defined but not used, with why (hw6's `Transparency`, whose
    /// meaning the assignment text does not give).
    pub unusable: HashMap<u32, &'static str>,
}

impl Materials {
    /// The material named by a `<Material>` reference element.
    pub fn lookup(&self, x: &Xml, node: Node) -> Result<u32, SceneError> {
        let id = x.text(node);
        if let Some(why) = self.ids.get(id).and_then(|i| self.unusable.get(i)) {
            return Err(x.error(node, format!("material {} cannot be used: {why}", excerpt(id))));
        }
        self.ids.get(id).copied().ok_or_else(|| SceneError::UnknownMaterial {
            file: x.file.to_path_buf(),
            field: super::xml::describe(node),
            name: id.to_owned(),
            defined: super::xml::id_list(self.ids.keys()),
            line: x.line(node),
        })
    }
}

pub(super) fn materials<'a, 'i: 'a>(
    x: &Xml,
    lists: impl Iterator<Item = Node<'a, 'i>>,
    brdfs: &HashMap<String, BrdfSpec>,
) -> Result<Materials, SceneError> {
    let mut out = Materials { list: Vec::new(), ids: HashMap::new(), unusable: HashMap::new() };
    for list in lists {
        x.check_children(list, &["Material"])?;
        for node in list.children().filter(|n| n.has_tag_name("Material")) {
            let id = node.attribute("id").map(str::trim).unwrap_or("");
            if id.is_empty() {
                return Err(x.error(node, "the material has no id attribute"));
            }
            if out.ids.contains_key(id) {
                return Err(x.error(node, format!("material id \"{id}\" is defined twice")));
            }
            let material = material(x, node, id, brdfs)?;
            if x.child(node, "Transparency")?.is_some() {
                out.unusable.insert(
                    out.list.len() as u32,
                    "its <Transparency> (hw6's glass) is not supported yet",
                );
            }
            out.ids.insert(id.to_owned(), out.list.len() as u32);
            out.list.push(material);
        }
    }
    Ok(out)
}

/// The exponent of `degamma="true"` materials' reflectances.
const DEGAMMA: f32 = 2.2;

fn material(
    x: &Xml,
    node: Node,
    id: &str,
    brdfs: &HashMap<String, BrdfSpec>,
) -> Result<MaterialDesc, SceneError> {
    x.check_children(node, &ALLOWED)?;
    let degamma = x.flag(node, "degamma")?;
    // hw5's degamma: the reflectances are display values, made linear by the inverse of
    // the tone mapper's standard gamma.
    let color = |name: &str| -> Result<Vec3, SceneError> {
        let c = x.child(node, name)?.map_or(Ok(Vec3::ZERO), |n| x.color(n))?;
        Ok(if degamma { c.powf(DEGAMMA) } else { c })
    };
    let scalar = |name: &str, default: Option<f64>| -> Result<f64, SceneError> {
        match x.child(node, name)? {
            Some(n) => {
                let v = x.scalar(n)?;
                if !(v >= 0.0) || !(v as f32).is_finite() {
                    return Err(x.out_of_range(n, v, ">= 0 (and small enough for f32)"));
                }
                Ok(v)
            }
            None => default.ok_or_else(|| x.missing(node, name)),
        }
    };
    let mut phong = PhongDesc {
        ambient: color("AmbientReflectance")?,
        specular: color("SpecularReflectance")?,
        exponent: scalar("PhongExponent", Some(1.0))? as f32,
        brdf: CourseBrdf::default(),
    };
    if let Some(brdf_id) = node.attribute("BRDF").map(str::trim) {
        let Some(spec) = brdfs.get(brdf_id) else {
            let mut defined: Vec<&str> = brdfs.keys().map(String::as_str).collect();
            defined.sort_unstable();
            let defined = if defined.is_empty() { "(none)".to_owned() } else { defined.join(", ") };
            return Err(x.error(
                node,
                format!(
                    "BRDF=\"{}\" names no BRDF of <BRDFs> (defined: {defined})",
                    crate::excerpt::excerpt(brdf_id)
                ),
            ));
        };
        phong.exponent = spec.exponent;
        phong.brdf = match spec.model {
            BrdfModel::OriginalBlinnPhong => CourseBrdf::OriginalBlinnPhong,
            BrdfModel::OriginalPhong => CourseBrdf::OriginalPhong,
            BrdfModel::ModifiedBlinnPhong { normalized } => {
                CourseBrdf::ModifiedBlinnPhong { normalized }
            }
            BrdfModel::ModifiedPhong { normalized } => CourseBrdf::ModifiedPhong { normalized },
            BrdfModel::TorranceSparrow { kd_fresnel } => {
                let eta = scalar("RefractionIndex", None)?;
                if !(eta > 0.0) {
                    let n = x.required(node, "RefractionIndex")?;
                    return Err(x.out_of_range(n, eta, "> 0"));
                }
                CourseBrdf::TorranceSparrow {
                    kd_fresnel,
                    eta: Vec3::splat(eta as f32),
                    k: Vec3::splat(scalar("AbsorptionIndex", Some(0.0))? as f32),
                }
            }
        };
    }
    let kind = node.attribute("type").map(str::trim).unwrap_or("");
    let specular = match kind {
        "" => Specular::None,
        "mirror" => Specular::Mirror { reflectance: color("MirrorReflectance")? },
        "conductor" => {
            let eta = scalar("RefractionIndex", None)?;
            if !(eta > 0.0) {
                let n = x.required(node, "RefractionIndex")?;
                return Err(x.out_of_range(n, eta, "> 0"));
            }
            Specular::Conductor {
                eta: Vec3::splat(eta as f32),
                k: Vec3::splat(scalar("AbsorptionIndex", Some(0.0))? as f32),
                reflectance: color("MirrorReflectance")?,
            }
        }
        "dielectric" => {
            let ior = scalar("RefractionIndex", None)?;
            if !(ior > 0.0) {
                let n = x.required(node, "RefractionIndex")?;
                return Err(x.out_of_range(n, ior, "> 0"));
            }
            Specular::dielectric(ior as f32, color("AbsorptionCoefficient")?)
        }
        other => {
            return Err(x.error(
                node,
                format!(
                    "unsupported material type \"{other}\" (supported: mirror, conductor, \
                     dielectric, or none)"
                ),
            ));
        }
    };
    // Roughness only means something for a reflecting material.
    let roughness = match specular {
        Specular::None => 0.0,
        _ => scalar("Roughness", Some(0.0))? as f32,
    };
    Ok(MaterialDesc {
        name: format!("material_{id}"),
        albedo: color("DiffuseReflectance")?,
        emission: Vec3::ZERO,
        specular,
        roughness,
        texture: None,
        specular_texture: None,
        normal_map: None,
        bump_map: None,
        phong: Some(phong),
        ..MaterialDesc::default()
    })
}
