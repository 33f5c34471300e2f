//! `conductor` and `roughconductor`: a measured `material` (embedded), `eta` and `k`, or
//! Mitsuba's default, a perfect mirror.

use super::super::ior::conductor_ior;
use super::super::tree::Element;
use super::super::values::{ColorUse, color, property};
use super::{MICROFACET, Roughness, check_properties, microfacet, reflectance};
use crate::scene::desc::{MaterialDesc, Specular};
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
    let reflectance = reflectance(element, "specular_reflectance")?.unwrap_or(Vec3::ONE);
    let r = if rough { microfacet(element)? } else { Roughness::SMOOTH };
    let none = MaterialDesc {
        distribution: r.distribution,
        roughness: r.alpha,
        roughness_v: r.alpha_v,
        ..none
    };
    let named = property(element, "string", "material");
    let find = |name: &str| element.children.iter().find(|c| c.attr("name") == Some(name));
    let named_none = named.map_or(Ok(true), |m| m.required("value").map(|v| v == "none"))?;
    let (eta, k) = match find("eta") {
        None if named_none => {
            // Mitsuba's default material "none": a perfect mirror.
            return Ok(MaterialDesc { specular: Specular::Mirror { reflectance }, ..none });
        }
        Some(eta) => {
            let k = find("k").map_or(Ok(DVec3::ZERO), |k| color(k, ColorUse::Unbounded))?;
            (color(eta, ColorUse::Unbounded)?, k)
        }
        None => {
            let value = named.map_or(Ok("none"), |m| m.required("value"))?;
            conductor_ior(value).ok_or_else(|| {
                let known: Vec<&str> = super::super::metals::names().collect();
                named.unwrap_or(element).error(format!(
                    "the conductor material '{value}' is not known (known: {}; or give eta and k)",
                    known.join(", ")
                ))
            })?
        }
    };
    let specular = Specular::Conductor { eta: eta.as_vec3(), k: k.as_vec3(), reflectance };
    Ok(MaterialDesc { specular, ..none })
}
