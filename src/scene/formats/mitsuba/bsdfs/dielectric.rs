//! `dielectric` and `roughdielectric`: glass of index int_ior / ext_ior (numbers or
//! Mitsuba's named indices), two-sided by nature.

use super::super::ior::dielectric_ior;
use super::super::tree::Element;
use super::{MICROFACET, Roughness, check_properties, microfacet, unit_only};
use crate::scene::desc::{MaterialDesc, Specular};
use crate::scene::error::SceneError;
use glam::Vec3;

pub(super) fn dielectric(
    element: &Element,
    kind: &str,
    none: MaterialDesc,
) -> Result<MaterialDesc, SceneError> {
    let rough = kind == "roughdielectric";
    let mut known = vec!["int_ior", "ext_ior", "specular_reflectance", "specular_transmittance"];
    if rough {
        known.extend(MICROFACET);
    }
    check_properties(element, &known)?;
    unit_only(element, &["specular_reflectance", "specular_transmittance"])?;
    let r = if rough { microfacet(element)? } else { Roughness::SMOOTH };
    let ior = relative_ior(element, "bk7")?;
    Ok(MaterialDesc {
        specular: Specular::Dielectric { ior, absorption: Vec3::ZERO },
        distribution: r.distribution,
        roughness: r.alpha,
        roughness_v: r.alpha_v,
        one_sided: false,
        ..none
    })
}

/// int_ior / ext_ior, each a number or a named index (defaults: `interior`, air).
pub(super) fn relative_ior(element: &Element, interior: &str) -> Result<f32, SceneError> {
    let ior = |name: &str, default: &str| -> Result<f64, SceneError> {
        let named = |p: &Element, value: &str| {
            dielectric_ior(value)
                .ok_or_else(|| p.error(format!("'{value}' is not a known index of refraction")))
        };
        match element.children.iter().find(|c| c.attr("name") == Some(name)) {
            None => named(element, default),
            Some(p) if matches!(p.tag.as_str(), "float" | "integer") => {
                super::super::values::number_attr(p, "value")
            }
            Some(p) if p.tag == "string" => named(p, p.required("value")?),
            // Mitsuba reads an index as a number or a name only (a texture is not read).
            Some(p) => Err(p.error(format!("`{name}` must be a <float> or a <string>"))),
        }
    };
    let (inside, outside) = (ior("int_ior", interior)?, ior("ext_ior", "air")?);
    if !(inside > 0.0 && outside > 0.0) {
        return Err(element.error("int_ior and ext_ior must be > 0"));
    }
    Ok((inside / outside) as f32)
}
