//! `plastic` and `roughplastic`: a dielectric coating (default polypropylene) over a
//! diffuse base, linear or `nonlinear`.

use super::super::tree::{Element, FileResolver};
use super::super::values::boolean;
use super::dielectric::relative_ior;
use super::{
    MICROFACET, Roughness, check_properties, microfacet, reflectance, reflectance_texture,
    unit_only,
};
use crate::scene::desc::{MaterialDesc, Specular};
use crate::scene::error::SceneError;
use glam::Vec3;

pub(super) fn plastic(
    element: &Element,
    kind: &str,
    none: MaterialDesc,
    ids: &super::super::Ids,
    files: &FileResolver,
) -> Result<MaterialDesc, SceneError> {
    let rough = kind == "roughplastic";
    let mut known =
        vec!["int_ior", "ext_ior", "diffuse_reflectance", "specular_reflectance", "nonlinear"];
    if rough {
        known.extend(MICROFACET);
    }
    check_properties(element, &known)?;
    unit_only(element, &["specular_reflectance"])?;
    let r = if rough { microfacet(element)? } else { Roughness::SMOOTH };
    if super::roughness_textures(element, ids, files)?.is_some() {
        return Err(element.error("a textured alpha on a plastic is not supported"));
    }
    if r.alpha_v.is_some() {
        return Err(element.error("roughplastic takes one alpha (alpha_u = alpha_v)"));
    }
    let (distribution, roughness) = (r.distribution, r.alpha);
    let ior = relative_ior(element, "polypropylene")?;
    if ior == 1.0 {
        return Err(element.error("int_ior and ext_ior must differ (a coating must be seen)"));
    }
    let nonlinear = boolean(element, "nonlinear")?.unwrap_or(false);
    let mut material = MaterialDesc {
        albedo: Vec3::splat(0.5),
        specular: Specular::Plastic { ior, nonlinear },
        distribution,
        roughness,
        ..none
    };
    if let Some(texture) = reflectance_texture(element, "diffuse_reflectance", ids, files)? {
        material.texture = Some(texture);
    } else if let Some(rgb) = reflectance(element, "diffuse_reflectance")? {
        material.albedo = rgb;
    }
    Ok(material)
}
