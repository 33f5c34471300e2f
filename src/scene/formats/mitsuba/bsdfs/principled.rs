//! `principled` and `principledthin`: Mitsuba's names, defaults and conversions (`specular`
//! to η; η = 1 and specular = 0 nudged where light is transmitted), every weight a number
//! or a texture's mean channel. Numbers outside the model's range are refused.

use super::super::tree::{Element, FileResolver};
use super::super::values::float;
use super::range::{NON_NEGATIVE, POSITIVE, Range, UNIT};
use super::texture::float_texture;
use super::{check_properties, reflectance, reflectance_texture};
use crate::scene::desc::{MaterialDesc, ParamDesc, PrincipledDesc};
use crate::scene::error::SceneError;
use glam::Vec3;

/// The weights both models take, each in [0, 1].
const WEIGHTS: [&str; 7] =
    ["roughness", "anisotropic", "spec_tint", "sheen", "sheen_tint", "spec_trans", "flatness"];

/// Only in `principled`, each in [0, 1].
const SOLID_WEIGHTS: [&str; 3] = ["metallic", "clearcoat", "clearcoat_gloss"];

const SOLID_RATES: [&str; 3] =
    ["main_specular_sampling_rate", "clearcoat_sampling_rate", "diffuse_reflectance_sampling_rate"];

const THIN_RATES: [&str; 4] = [
    "specular_reflectance_sampling_rate",
    "specular_transmittance_sampling_rate",
    "diffuse_transmittance_sampling_rate",
    "diffuse_reflectance_sampling_rate",
];

pub(super) fn principled(
    element: &Element,
    kind: &str,
    none: MaterialDesc,
    ids: &super::super::Ids,
    files: &FileResolver,
) -> Result<MaterialDesc, SceneError> {
    let thin = kind == "principledthin";
    let mut known = vec!["base_color", "eta"];
    known.extend(WEIGHTS);
    if thin {
        known.push("diff_trans");
        known.extend(THIN_RATES);
    } else {
        known.push("specular");
        known.extend(SOLID_WEIGHTS);
        known.extend(SOLID_RATES);
    }
    check_properties(element, &known)?;

    let mut desc = PrincipledDesc::new(thin);
    let weight = |name: &str, default: f32| param(element, name, default, UNIT, ids, files);
    desc.roughness = weight("roughness", 0.5)?;
    desc.anisotropic = weight("anisotropic", 0.0)?;
    desc.spec_tint = weight("spec_tint", 0.0)?;
    desc.sheen = weight("sheen", 0.0)?;
    desc.sheen_tint = weight("sheen_tint", 0.0)?;
    desc.spec_trans = weight("spec_trans", 0.0)?;
    desc.flatness = weight("flatness", 0.0)?;
    let transmits = !desc.spec_trans.is_zero();
    let rate = |name: &str| -> Result<f32, SceneError> {
        Ok(number(element, name, NON_NEGATIVE)?.unwrap_or(1.0))
    };
    if thin {
        let two = Range { end: 2.0, ..UNIT };
        desc.diff_trans = param(element, "diff_trans", 0.0, two, ids, files)?;
        desc.eta = param(element, "eta", 1.5, POSITIVE, ids, files)?;
        let rates = &mut desc.sampling_rates;
        rates.specular_reflectance = rate("specular_reflectance_sampling_rate")?;
        rates.specular_transmittance = rate("specular_transmittance_sampling_rate")?;
        rates.diffuse_transmittance = rate("diffuse_transmittance_sampling_rate")?;
        rates.diffuse_reflectance = rate("diffuse_reflectance_sampling_rate")?;
    } else {
        desc.metallic = weight("metallic", 0.0)?;
        desc.clearcoat = weight("clearcoat", 0.0)?;
        desc.clearcoat_gloss = weight("clearcoat_gloss", 0.0)?;
        desc.eta = ParamDesc::Constant(solid_eta(element, transmits)?);
        let rates = &mut desc.sampling_rates;
        let main = rate("main_specular_sampling_rate")?;
        (rates.specular_reflectance, rates.specular_transmittance) = (main, main);
        rates.clearcoat = rate("clearcoat_sampling_rate")?;
        rates.diffuse_reflectance = rate("diffuse_reflectance_sampling_rate")?;
    }
    if desc.sampling_rates.samples_nothing(thin) {
        return Err(element.error(
            "every *_sampling_rate is 0: at least one lobe must be sampled (the image would \
             be dark without a word)",
        ));
    }

    let mut material = MaterialDesc { albedo: Vec3::splat(0.5), ..none };
    if let Some(texture) = reflectance_texture(element, "base_color", ids, files)? {
        material.texture = Some(texture);
    } else if let Some(rgb) = reflectance(element, "base_color")? {
        material.albedo = rgb;
    }
    Ok(MaterialDesc { principled: Some(Box::new(desc)), ..material })
}

/// `principled`'s η, from `eta` or `specular`.
fn solid_eta(element: &Element, transmits: bool) -> Result<f32, SceneError> {
    if super::texture_child(element, "eta").is_some() {
        return Err(
            element.error("principled's eta is a <float> (a texture only in principledthin)")
        );
    }
    let eta = number(element, "eta", POSITIVE)?;
    let specular = number(element, "specular", UNIT)?;
    crate::scene::desc::solid_eta(eta, specular, transmits)
        .ok_or_else(|| element.error("give either eta or specular, not both"))
}

/// The `<float>` `name` (refused outside `range`), or `None`.
fn number(element: &Element, name: &str, range: Range) -> Result<Option<f32>, SceneError> {
    let Some(value) = float(element, name)? else { return Ok(None) };
    if !range.contains(value) {
        let child = element.children.iter().find(|c| c.attr("name") == Some(name));
        return Err(child
            .unwrap_or(element)
            .error(format!("{name} is {value}, but must be {}", range.describe())));
    }
    Ok(Some(value as f32))
}

/// A weight: a `<texture>` (its mean channel), a `<float>` in `range`, or `default`.
fn param(
    element: &Element,
    name: &str,
    default: f32,
    range: Range,
    ids: &super::super::Ids,
    files: &FileResolver,
) -> Result<ParamDesc, SceneError> {
    if let Some(texture) = float_texture(element, name, range, ids, files)? {
        return Ok(ParamDesc::Texture(texture));
    }
    Ok(ParamDesc::Constant(number(element, name, range)?.unwrap_or(default)))
}
