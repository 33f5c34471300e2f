//! `conductor` and `roughconductor`: a measured `material` (embedded), `eta` and `k`, or
//! Mitsuba's default, a perfect mirror.

use super::super::ior::conductor_ior;
use super::super::tree::Element;
use super::super::values::{ColorUse, color, string};
use super::{MICROFACET, Roughness, check_properties, microfacet, reflectance};
use crate::scene::desc::{MaterialDesc, Shadowing, Specular};
use crate::scene::error::SceneError;
use glam::{DVec3, Vec3};

pub(super) fn conductor(
    element: &Element,
    kind: &str,
    none: MaterialDesc,
) -> Result<MaterialDesc, SceneError> {
    let rough = kind == "roughconductor";
    let mut known = vec!["material", "eta", "k", "specular_reflectance"];
    if rough {
        known.extend(MICROFACET);
    }
    check_properties(element, &known)?;
    // A textured tint is refused by `reflectance`: embray's conductors take a constant one.
    let reflectance = reflectance(element, "specular_reflectance")?.unwrap_or(Vec3::ONE);
    let r = if rough { microfacet(element)? } else { Roughness::SMOOTH };
    let none = MaterialDesc {
        distribution: r.distribution,
        roughness: r.alpha,
        roughness_v: r.alpha_v,
        // Mitsuba's microfacet G is G₁(ωi)·G₁(ωo) (`MicrofacetDistribution::G`).
        shadowing: Shadowing::Separable,
        ..none
    };
    let named = string(element, "material")?;
    let find = |name: &str| element.children.iter().find(|c| c.attr("name") == Some(name));
    let material = named.map_or(Ok("none"), |m| m.required("value"))?;
    let (eta, k) = if find("eta").is_some() || material == "none" {
        // Mitsuba's defaults: η = 0 and k = 1, a perfect mirror (as is any k with η = 0).
        if material != "none" {
            let both = find("eta").or(find("k")).unwrap_or(element);
            return Err(both.error("give either (eta, k) or material, not both (as Mitsuba)"));
        }
        let k = find("k").map_or(Ok(DVec3::ONE), |k| color(k, ColorUse::Unbounded))?;
        match find("eta") {
            None => return Ok(MaterialDesc { specular: Specular::Mirror { reflectance }, ..none }),
            Some(eta) => (color(eta, ColorUse::Unbounded)?, k),
        }
    } else {
        if let Some(k) = find("k") {
            // Mitsuba reads k only beside eta: with a material it is left unread, an error.
            return Err(k.error("give either (eta, k) or material, not both (as Mitsuba)"));
        }
        conductor_ior(material).ok_or_else(|| {
            let known: Vec<&str> = super::super::metals::names().collect();
            named.unwrap_or(element).error(format!(
                "the conductor material '{material}' is not known (known: {}; or give eta and k)",
                known.join(", ")
            ))
        })?
    };
    let specular = Specular::Conductor { eta: eta.as_vec3(), k: k.as_vec3(), reflectance };
    Ok(MaterialDesc { specular, ..none })
}
