//! `<bsdf>` → `MaterialDesc`, one file per family, with Mitsuba's parameter names,
//! defaults and conventions (BSDFs are one-sided unless wrapped in `twosided`; glass is
//! two-sided by nature). Other BSDFs are refused with their type, file and line: none is
//! silently replaced.

mod area_radiance;
mod conductor;
mod dielectric;
mod plastic;
mod principled;
mod range;
mod texture;
mod wrappers;

use super::tree::{Element, FileResolver};
use super::values::{ColorUse, color, float, string};
use crate::scene::desc::{Distribution, MaterialDesc, TextureDesc};
use crate::scene::error::SceneError;
pub(super) use area_radiance::area_radiance;
use glam::{DVec3, Vec3};
use texture::{float_texture, reflectance_texture};

/// The BSDFs this reader knows, for messages.
pub(super) const SUPPORTED: &str = "diffuse, twosided, mask, normalmap, bumpmap, blendbsdf, \
                                    conductor, roughconductor, dielectric, roughdielectric, \
                                    thindielectric, null, plastic, roughplastic, principled, principledthin";

pub(super) fn bsdf(
    element: &Element,
    ids: &super::Ids,
    files: &FileResolver,
) -> Result<MaterialDesc, SceneError> {
    let kind = element.required("type")?;
    let name = element.attr("id").unwrap_or(kind).to_owned();
    let none = MaterialDesc { name, albedo: Vec3::ZERO, one_sided: true, ..Default::default() };
    match kind {
        "twosided" => wrappers::twosided(element, none, ids, files),
        "blendbsdf" => wrappers::blendbsdf(element, none, ids, files),
        "mask" => wrappers::mask(element, none, ids, files),
        "normalmap" => wrappers::normalmap(element, none, ids, files),
        "bumpmap" => wrappers::bumpmap(element, none, ids, files),
        "diffuse" => {
            let mut material = MaterialDesc { albedo: Vec3::splat(0.5), ..none };
            check_properties(element, &["reflectance"])?;
            if let Some(texture) = reflectance_texture(element, "reflectance", ids, files)? {
                material.texture = Some(texture);
            } else if let Some(rgb) = reflectance(element, "reflectance")? {
                material.albedo = rgb;
            }
            Ok(material)
        }
        "conductor" | "roughconductor" => {
            let roughness_textures = roughness_textures(element, ids, files)?;
            let material = conductor::conductor(element, kind, none)?;
            Ok(MaterialDesc { roughness_textures, ..material })
        }
        "dielectric" | "roughdielectric" => {
            let roughness_textures = roughness_textures(element, ids, files)?;
            let material = dielectric::dielectric(element, kind, none)?;
            Ok(MaterialDesc { roughness_textures, ..material })
        }
        "thindielectric" => dielectric::thin_dielectric(element, none),
        // Light passes it unchanged, as a mask of opacity 0: a bounce of the path (Mitsuba's
        // `path` counts it) that takes no light samples; shadow rays pass it too (a null
        // rectangle under a light casts no shadow, in Mitsuba's image as in embray's).
        "null" => {
            check_properties(element, &[])?;
            let opacity = Some(crate::scene::desc::Opacity::Constant(0.0));
            Ok(MaterialDesc { opacity, one_sided: false, ..none })
        }
        "plastic" | "roughplastic" => plastic::plastic(element, kind, none, ids, files),
        "principled" | "principledthin" => principled::principled(element, kind, none, ids, files),
        other => Err(element
            .error(format!("the BSDF '{other}' is not supported yet (supported: {SUPPORTED})"))),
    }
}

/// Refuses a parameter (a property, a texture or a reference by `name`) the BSDF does not
/// read, so that nothing in the file is silently ignored.
fn check_properties(element: &Element, known: &[&str]) -> Result<(), SceneError> {
    let kind = element.attr("type");
    let wrapper = matches!(kind, Some("twosided" | "mask" | "normalmap" | "bumpmap" | "blendbsdf"));
    for child in &element.children {
        let parameter = child.attr("name").is_some_and(|n| known.contains(&n));
        let nested = match child.tag.as_str() {
            // A nested BSDF, whatever its name (Mitsuba takes every nested object), or a
            // reference that the wrapper requires to be one (or a bumpmap's texture).
            "bsdf" | "ref" => wrapper && !parameter,
            // A bumpmap's height, whatever its name: `wrappers::bumpmap` takes exactly one.
            "texture" => kind == Some("bumpmap"),
            _ => false,
        };
        if nested {
            continue;
        }
        match child.attr("name") {
            Some(name) if !known.contains(&name) => {
                return Err(child.error(format!(
                    "{} does not take `{name}` (it takes: {})",
                    element.describe(),
                    known.join(", ")
                )));
            }
            Some(_) => {}
            None => {
                return Err(child.error(format!(
                    "{} does not take a <{}>",
                    element.describe(),
                    child.tag
                )));
            }
        }
    }
    Ok(())
}

/// The parameters of a microfacet distribution every rough BSDF takes.
const MICROFACET: [&str; 5] = ["alpha", "alpha_u", "alpha_v", "distribution", "sample_visible"];

/// A rough BSDF's distribution and α (along ∂p/∂u), and α along the bitangent where it
/// differs (`alpha_u` ≠ `alpha_v`).
struct Roughness {
    distribution: Distribution,
    alpha: f32,
    alpha_v: Option<f32>,
}

impl Roughness {
    const SMOOTH: Roughness =
        Roughness { distribution: Distribution::Ggx, alpha: 0.0, alpha_v: None };
}

/// The distribution and its α (Mitsuba's defaults: Beckmann, 0.1), or `alpha_u` and
/// `alpha_v`; a textured α is refused.
fn microfacet(element: &Element) -> Result<Roughness, SceneError> {
    let distribution = match string(element, "distribution")? {
        None => Distribution::Beckmann,
        Some(d) => match d.required("value")?.to_ascii_lowercase().as_str() {
            "beckmann" => Distribution::Beckmann,
            "ggx" => Distribution::Ggx,
            other => {
                return Err(
                    d.error(format!("the distribution '{other}' is not known (beckmann or ggx)"))
                );
            }
        },
    };
    if ROUGHNESS_NAMES.iter().any(|name| texture_child(element, name).is_some()) {
        // `roughness_textures` reads them; the numbers here are not used.
        return Ok(Roughness { distribution, alpha: 0.1, alpha_v: None });
    }
    let (u, v) = (float(element, "alpha_u")?, float(element, "alpha_v")?);
    if u.is_some() || v.is_some() {
        if u.is_none() || v.is_none() {
            return Err(element.error("alpha_u and alpha_v are given together"));
        }
        if float(element, "alpha")?.is_some() {
            return Err(element.error("give either alpha or alpha_u and alpha_v, not both"));
        }
    }
    let alpha = float(element, "alpha")?.or(u).unwrap_or(0.1);
    for (name, value) in [("alpha", Some(alpha)), ("alpha_v", v)] {
        if let Some(value) = value.filter(|a| !(0.0..=1.0).contains(a)) {
            return Err(element.error(format!("{name} is {value}, but must be in [0, 1]")));
        }
    }
    // `sample_visible` chooses how directions are drawn, not what the BSDF is: read (a
    // non-boolean is refused) and the visible normals drawn either way, for the same image.
    super::values::boolean(element, "sample_visible")?;
    let alpha_v = v.filter(|&v| Some(v) != u).map(|v| v as f32);
    Ok(Roughness { distribution, alpha: alpha as f32, alpha_v })
}

const ROUGHNESS_NAMES: [&str; 3] = ["alpha", "alpha_u", "alpha_v"];

/// The `<texture>` (or reference to one) named `name`.
fn texture_child<'a>(element: &'a Element, name: &str) -> Option<&'a Element> {
    element
        .children
        .iter()
        .find(|c| c.attr("name") == Some(name) && matches!(c.tag.as_str(), "texture" | "ref"))
}

/// A textured roughness: `alpha`, or `alpha_u` and `alpha_v`, where one of them is a
/// `<texture>` (a number beside one is a constant texture); `None` if none is textured.
fn roughness_textures(
    element: &Element,
    ids: &super::Ids,
    files: &FileResolver,
) -> Result<Option<Box<[TextureDesc; 2]>>, SceneError> {
    if !ROUGHNESS_NAMES.iter().any(|name| texture_child(element, name).is_some()) {
        return Ok(None);
    }
    let read = |name: &str| -> Result<Option<TextureDesc>, SceneError> {
        if let Some(texture) = float_texture(element, name, range::UNIT, ids, files)? {
            return Ok(Some(texture));
        }
        Ok(float(element, name)?.map(|alpha| TextureDesc {
            pattern: crate::scene::Pattern::Constant(Vec3::splat(alpha as f32)),
            mode: Default::default(),
            texture_from_object: glam::DAffine3::IDENTITY,
        }))
    };
    match (read("alpha")?, read("alpha_u")?, read("alpha_v")?) {
        (Some(alpha), None, None) => Ok(Some(Box::new([alpha.clone(), alpha]))),
        (None, Some(u), Some(v)) => Ok(Some(Box::new([u, v]))),
        _ => Err(element.error("give either alpha or alpha_u and alpha_v, not both")),
    }
}

/// The constant reflectance named `name`, each component in [0, 1]. A texture by that name
/// is refused (callers that take one look for it first): passed over, it would leave the
/// default in its place unseen.
fn reflectance(element: &Element, name: &str) -> Result<Option<Vec3>, SceneError> {
    let Some(found) = element.children.iter().find(|c| c.attr("name") == Some(name)) else {
        return Ok(None);
    };
    if matches!(found.tag.as_str(), "texture" | "ref") {
        return Err(found.error(format!(
            "a textured `{name}` is not supported in {} (only a colour)",
            element.describe()
        )));
    }
    let rgb = color(found, ColorUse::Reflectance)?;
    if !rgb.cmpge(DVec3::ZERO).all() || !rgb.cmple(DVec3::ONE).all() {
        return Err(found.error(format!("a reflectance must be in [0, 1], not {rgb}")));
    }
    Ok(Some(rgb.as_vec3()))
}

/// Refuses a `specular_reflectance`/`specular_transmittance` other than 1 (not modelled).
fn unit_only(element: &Element, names: &[&str]) -> Result<(), SceneError> {
    for name in names {
        let textured = element
            .children
            .iter()
            .any(|c| c.attr("name") == Some(name) && matches!(c.tag.as_str(), "texture" | "ref"));
        if textured {
            return Err(element.error(format!("a textured {name} is not supported")));
        }
        if reflectance(element, name)?.is_some_and(|r| r != Vec3::ONE) {
            return Err(element.error(format!("{name} other than 1 is not supported")));
        }
    }
    Ok(())
}
