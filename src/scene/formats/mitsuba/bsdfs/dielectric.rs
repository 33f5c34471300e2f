//! `dielectric`, `roughdielectric` and `thindielectric`: glass of index int_ior / ext_ior
//! (numbers or Mitsuba's named indices), two-sided by nature.

use super::super::ior::dielectric_ior;
use super::super::tree::Element;
use super::{MICROFACET, Roughness, check_properties, microfacet, reflectance};
use crate::scene::desc::{MaterialDesc, Specular};
use crate::scene::error::SceneError;
use glam::Vec3;

pub(super) fn dielectric(
    element: &Element,
    kind: &str,
    none: MaterialDesc,
) -> Result<MaterialDesc, SceneError> {
    let rough = kind == "roughdielectric";
    let mut known = vec!["int_ior", "ext_ior", TINTS[0], TINTS[1]];
    if rough {
        known.extend(MICROFACET);
    }
    check_properties(element, &known)?;
    let [reflectance, transmittance] = tints(element)?;
    let r = if rough { microfacet(element)? } else { Roughness::SMOOTH };
    let ior = relative_ior(element, "bk7")?;
    Ok(MaterialDesc {
        specular: Specular::Dielectric { ior, absorption: Vec3::ZERO, reflectance, transmittance },
        distribution: r.distribution,
        roughness: r.alpha,
        roughness_v: r.alpha_v,
        one_sided: false,
        ..none
    })
}

/// A thin sheet: reflection by both faces, the rest straight through, each scaled by a
/// constant `specular_reflectance` or `specular_transmittance` (a texture is refused).
pub(super) fn thin_dielectric(
    element: &Element,
    none: MaterialDesc,
) -> Result<MaterialDesc, SceneError> {
    check_properties(element, &["int_ior", "ext_ior", TINTS[0], TINTS[1]])?;
    let [reflectance, transmittance] = tints(element)?;
    let ior = relative_ior(element, "bk7")?;
    let specular = Specular::ThinDielectric { ior, reflectance, transmittance };
    Ok(MaterialDesc { specular, one_sided: false, ..none })
}

const TINTS: [&str; 2] = ["specular_reflectance", "specular_transmittance"];

/// The constant `specular_reflectance` and `specular_transmittance` (default 1; a texture
/// is refused).
fn tints(element: &Element) -> Result<[Vec3; 2], SceneError> {
    let tint = |name| Ok(reflectance(element, name)?.unwrap_or(Vec3::ONE));
    Ok([tint(TINTS[0])?, tint(TINTS[1])?])
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
