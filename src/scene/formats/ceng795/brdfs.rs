//! `<BRDFs>` (Fall 2022 hw6): the reflectance models materials name with their `BRDF`
//! attribute. OriginalBlinnPhong, OriginalPhong, ModifiedBlinnPhong and ModifiedPhong (both
//! with an optional `normalized="true"`) and TorranceSparrow (with `kdfresnel`), each with an
//! `<Exponent>`; `shading::course_brdf` defines them.

use super::xml::Xml;
use crate::scene::error::SceneError;
use roxmltree::Node;
use std::collections::HashMap;

/// A BRDF element: its model (Torrance-Sparrow's Fresnel indices come from the material)
/// and exponent.
#[derive(Clone, Copy, Debug)]
pub(super) struct BrdfSpec {
    pub model: BrdfModel,
    pub exponent: f32,
}

#[derive(Clone, Copy, Debug)]
pub(super) enum BrdfModel {
    OriginalBlinnPhong,
    OriginalPhong,
    ModifiedBlinnPhong { normalized: bool },
    ModifiedPhong { normalized: bool },
    TorranceSparrow { kd_fresnel: bool },
}

const MODELS: [&str; 5] = [
    "OriginalBlinnPhong",
    "OriginalPhong",
    "ModifiedBlinnPhong",
    "ModifiedPhong",
    "TorranceSparrow",
];

/// Every BRDF of every `<BRDFs>` element, by id.
pub(super) fn brdfs<'a, 'i: 'a>(
    x: &Xml,
    lists: impl Iterator<Item = Node<'a, 'i>>,
) -> Result<HashMap<String, BrdfSpec>, SceneError> {
    let mut out = HashMap::new();
    for list in lists {
        x.check_children(list, &MODELS)?;
        for node in list.children().filter(Node::is_element) {
            let id = node.attribute("id").map(str::trim).unwrap_or("");
            if id.is_empty() {
                return Err(x.error(node, "the BRDF has no id attribute"));
            }
            if out.contains_key(id) {
                return Err(x.error(node, format!("BRDF id \"{id}\" is defined twice")));
            }
            out.insert(id.to_owned(), brdf(x, node)?);
        }
    }
    Ok(out)
}

fn brdf(x: &Xml, node: Node) -> Result<BrdfSpec, SceneError> {
    x.check_children(node, &["Exponent"])?;
    let flag = |name: &str| x.flag(node, name);
    let model = match node.tag_name().name() {
        "OriginalBlinnPhong" => BrdfModel::OriginalBlinnPhong,
        "OriginalPhong" => BrdfModel::OriginalPhong,
        "ModifiedBlinnPhong" => BrdfModel::ModifiedBlinnPhong { normalized: flag("normalized")? },
        "ModifiedPhong" => BrdfModel::ModifiedPhong { normalized: flag("normalized")? },
        _ => BrdfModel::TorranceSparrow { kd_fresnel: flag("kdfresnel")? },
    };
    let exponent_node = x.required(node, "Exponent")?;
    let exponent = x.scalar(exponent_node)?;
    if !(exponent > 0.0) || !(exponent as f32).is_finite() {
        return Err(x.out_of_range(exponent_node, exponent, "> 0 (and small enough for f32)"));
    }
    Ok(BrdfSpec { model, exponent: exponent as f32 })
}
