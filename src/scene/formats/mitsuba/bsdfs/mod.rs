//! `<bsdf>` → `MaterialDesc`, one file per family, with Mitsuba's parameter names,
//! defaults and conventions (BSDFs are one-sided unless wrapped in `twosided`; glass is
//! two-sided by nature). Other BSDFs are refused with their type, file and line: none is
//! silently replaced.

mod conductor;
mod dielectric;
mod plastic;
mod principled;
mod range;
mod texture;

use super::tree::{Element, FileResolver};
use super::values::{ColorUse, color, float, property};
use crate::limits::MAX_BLEND_MATERIALS;
use crate::scene::desc::{
    BumpMapDesc, BumpScale, Distribution, MaterialDesc, Opacity, TextureDesc,
};
use crate::scene::error::SceneError;
use glam::{DVec3, Vec3};
pub(super) use texture::refuse_rgbe;
use texture::{float_texture, reflectance_texture};

/// The BSDFs this reader knows, for messages.
pub(super) const SUPPORTED: &str = "diffuse, twosided, mask, normalmap, bumpmap, blendbsdf, \
                                    conductor, roughconductor, dielectric, roughdielectric, \
                                    plastic, roughplastic, principled, principledthin";

pub(super) fn bsdf(
    element: &Element,
    ids: &super::Ids,
    files: &FileResolver,
) -> Result<MaterialDesc, SceneError> {
    let kind = element.required("type")?;
    let name = element.attr("id").unwrap_or(kind).to_owned();
    let none = MaterialDesc { name, albedo: Vec3::ZERO, one_sided: true, ..Default::default() };
    match kind {
        "twosided" => {
            const PARAMETERS: [&str; 1] = ["allow_transmission"];
            check_properties(element, &PARAMETERS)?;
            let allowed = super::values::boolean(element, "allow_transmission")?;
            let inner = nested_bsdf(
                element,
                &PARAMETERS,
                ids,
                files,
                "twosided takes one nested <bsdf> (two are not supported)",
            )?;
            if transmits(&inner) {
                // As Mitsuba ("Only materials without a transmission component can be
                // nested!"): the back would be shaded as a second front. Mitsuba's
                // allow_transmission renders that; embray does not.
                let why = match allowed {
                    Some(true) => "allow_transmission is not supported: ",
                    _ => "",
                };
                return Err(element.error(format!(
                    "{why}twosided cannot hold a transmitting BSDF (dielectric, \
                     roughdielectric, mask, principledthin, or principled with spec_trans)"
                )));
            }
            Ok(MaterialDesc { name: none.name, ..two_sided(inner) })
        }
        "blendbsdf" => {
            check_properties(element, &["weight"])?;
            let parts = nested_bsdfs(element, &["weight"], ids, files)?;
            let [first, second] = <[MaterialDesc; 2]>::try_from(parts)
                .map_err(|_| element.error("blendbsdf takes two nested <bsdf>s"))?;
            let weight = number_or_texture(element, "weight", None, ids, files)?;
            if [&first, &second].iter().any(|m| m.normal_map.is_some() || m.bump_map.is_some()) {
                // Each would shade with its own normal: one frame serves the mixture.
                return Err(
                    element.error("a normal or bump map inside a blendbsdf is not supported")
                );
            }
            let blend = crate::scene::desc::BlendDesc { weight, materials: [first, second] };
            let material = MaterialDesc { blend: Some(Box::new(blend)), ..none };
            // Checked at every blend, so that its parts are in bounds and a chain whose
            // links name one `id` twice stops doubling at the limit.
            let count = material.blend_materials();
            if count > MAX_BLEND_MATERIALS {
                return Err(element.error(format!(
                    "{count} materials in one blendbsdf, counting each as often as it is \
                     named (at most {MAX_BLEND_MATERIALS})"
                )));
            }
            Ok(material)
        }
        "mask" => {
            check_properties(element, &["opacity"])?;
            let inner =
                nested_bsdf(element, &["opacity"], ids, files, "mask takes one nested <bsdf>")?;
            if inner.opacity.is_some() {
                return Err(element.error("a mask inside a mask is not supported"));
            }
            let opacity = number_or_texture(element, "opacity", Some(0.5), ids, files)?;
            Ok(MaterialDesc { name: none.name, opacity: Some(opacity), ..inner })
        }
        "normalmap" => {
            check_properties(element, &["normalmap"])?;
            let only = "normalmap takes one nested <bsdf>";
            let inner = nested_bsdf(element, &["normalmap"], ids, files, only)?;
            let map = reflectance_texture(element, "normalmap", ids, files)?
                .ok_or_else(|| element.error("normalmap needs a <texture name=\"normalmap\">"))?;
            if inner.normal_map.is_some() || inner.bump_map.is_some() {
                return Err(element.error("a normal or bump map inside another is not supported"));
            }
            let bump_shadowing = true;
            Ok(MaterialDesc { name: none.name, normal_map: Some(map), bump_shadowing, ..inner })
        }
        "bumpmap" => {
            // Its texture under any name, as its BSDF: told apart by what a reference is.
            let is_texture = |c: &Element| match c.tag.as_str() {
                "texture" => true,
                "ref" => ids.resolve(c).is_ok_and(|target| target.tag != "bsdf"),
                _ => false,
            };
            let textures: Vec<&str> = element
                .children
                .iter()
                .filter(|c| is_texture(c))
                .filter_map(|c| c.attr("name"))
                .collect();
            let [name] = textures[..] else {
                return Err(element.error("bumpmap takes one height <texture>"));
            };
            check_properties(element, &["scale", name])?;
            let only = "bumpmap takes one nested <bsdf>";
            let inner = nested_bsdf(element, &["scale", name], ids, files, only)?;
            let texture = float_texture(element, name, range::ANY, ids, files)?
                .ok_or_else(|| element.error("bumpmap needs a height <texture>"))?;
            if inner.normal_map.is_some() || inner.bump_map.is_some() {
                return Err(element.error("a normal or bump map inside another is not supported"));
            }
            let factor = float(element, "scale")?.unwrap_or(1.0) as f32;
            let bump = BumpMapDesc { texture, factor, scale: BumpScale::Scene };
            let bump_shadowing = true;
            Ok(MaterialDesc { name: none.name, bump_map: Some(bump), bump_shadowing, ..inner })
        }
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
        "plastic" | "roughplastic" => plastic::plastic(element, kind, none, ids, files),
        "principled" | "principledthin" => principled::principled(element, kind, none, ids, files),
        other => Err(element
            .error(format!("the BSDF '{other}' is not supported yet (supported: {SUPPORTED})"))),
    }
}

/// The one `<bsdf>` (or reference to one) inside a wrapper such as `twosided` or `mask`.
fn nested_bsdf(
    element: &Element,
    parameters: &[&str],
    ids: &super::Ids,
    files: &FileResolver,
    otherwise: &str,
) -> Result<MaterialDesc, SceneError> {
    let mut inner = nested_bsdfs(element, parameters, ids, files)?;
    match inner.len() {
        1 => Ok(inner.remove(0)),
        _ => Err(element.error(otherwise)),
    }
}

/// The `<bsdf>`s (or references to them) inside `element`, in order. As in Mitsuba, a
/// wrapper takes its BSDFs under any name, or none: every reference not by the name of one
/// of its `parameters` must be to a BSDF.
fn nested_bsdfs(
    element: &Element,
    parameters: &[&str],
    ids: &super::Ids,
    files: &FileResolver,
) -> Result<Vec<MaterialDesc>, SceneError> {
    let parameter = |c: &Element| c.attr("name").is_some_and(|n| parameters.contains(&n));
    ids.nested(element, || {
        element
            .children
            .iter()
            .filter(|c| c.tag == "bsdf" || (c.tag == "ref" && !parameter(c)))
            .map(|one| bsdf(ids.bsdf(one)?, ids, files))
            .collect()
    })
}

/// Whether `material` lets light through (Mitsuba's transmission flags, its mask's null
/// component too), itself or in a blend.
fn transmits(material: &MaterialDesc) -> bool {
    matches!(material.specular, crate::scene::desc::Specular::Dielectric { .. })
        || material.opacity.is_some()
        || material.principled.as_ref().is_some_and(|p| p.transmits())
        || material.blend.as_ref().is_some_and(|b| b.materials.iter().any(transmits))
}

/// `material` scattering on both sides (`twosided`), a blend's materials too.
fn two_sided(material: MaterialDesc) -> MaterialDesc {
    let blend = material.blend.map(|b| {
        let [first, second] = b.materials;
        Box::new(crate::scene::desc::BlendDesc {
            materials: [two_sided(first), two_sided(second)],
            ..*b
        })
    });
    MaterialDesc { one_sided: false, blend, ..material }
}

/// A number in [0, 1] (`default` where it may be left out) or a texture read as one: a
/// mask's opacity, a blend's weight.
fn number_or_texture(
    element: &Element,
    name: &str,
    default: Option<f64>,
    ids: &super::Ids,
    files: &FileResolver,
) -> Result<Opacity, SceneError> {
    if let Some(texture) = float_texture(element, name, range::UNIT, ids, files)? {
        return Ok(Opacity::Texture(texture));
    }
    let value = float(element, name)?
        .or(default)
        .ok_or_else(|| element.error(format!("the property `{name}` is missing")))?;
    if !(0.0..=1.0).contains(&value) {
        return Err(element.error(format!("{name} is {value}, but must be in [0, 1]")));
    }
    Ok(Opacity::Constant(value as f32))
}

/// Refuses a parameter (a property, a texture or a reference by `name`) the BSDF does not
/// read, so that nothing in the file is silently ignored.
fn check_properties(element: &Element, known: &[&str]) -> Result<(), SceneError> {
    let wrapper = matches!(
        element.attr("type"),
        Some("twosided" | "mask" | "normalmap" | "bumpmap" | "blendbsdf")
    );
    for child in &element.children {
        let parameter = child.attr("name").is_some_and(|n| known.contains(&n));
        if wrapper && matches!(child.tag.as_str(), "bsdf" | "ref") && !parameter {
            // A nested BSDF, whatever its name (Mitsuba takes every nested object), or a
            // reference that `nested_bsdfs` requires to be one.
            continue;
        }
        if let Some(name) = child.attr("name") {
            if !known.contains(&name) {
                return Err(child.error(format!(
                    "{} does not take `{name}` (it takes: {})",
                    element.describe(),
                    known.join(", ")
                )));
            }
        } else if !(wrapper && matches!(child.tag.as_str(), "bsdf" | "ref")) {
            return Err(child.error(format!(
                "{} does not take a <{}>",
                element.describe(),
                child.tag
            )));
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
    let distribution = match property(element, "string", "distribution") {
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
    if super::values::boolean(element, "sample_visible")? == Some(false) {
        return Err(
            element.error("sample_visible = false is not supported (visible normals are sampled)")
        );
    }
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

/// The constant reflectance named `name` (anything but a texture: what is not a colour is
/// refused by `color`), each component in [0, 1].
fn reflectance(element: &Element, name: &str) -> Result<Option<Vec3>, SceneError> {
    let found = element
        .children
        .iter()
        .find(|c| c.attr("name") == Some(name) && !matches!(c.tag.as_str(), "texture" | "ref"));
    let Some(found) = found else { return Ok(None) };
    let rgb = color(found, ColorUse::Reflectance)?;
    if !rgb.cmpge(DVec3::ZERO).all() || !rgb.cmple(DVec3::ONE).all() {
        return Err(found.error(format!("a reflectance must be in [0, 1], not {rgb}")));
    }
    Ok(Some(rgb.as_vec3()))
}

/// Refuses a `specular_reflectance`/`specular_transmittance` other than 1 (not modelled).
fn unit_only(element: &Element, names: &[&str]) -> Result<(), SceneError> {
    for name in names {
        if reflectance(element, name)?.is_some_and(|r| r != Vec3::ONE) {
            return Err(element.error(format!("{name} other than 1 is not supported")));
        }
        let textured = element
            .children
            .iter()
            .any(|c| c.attr("name") == Some(name) && matches!(c.tag.as_str(), "texture" | "ref"));
        if textured {
            return Err(element.error(format!("a textured {name} is not supported")));
        }
    }
    Ok(())
}
