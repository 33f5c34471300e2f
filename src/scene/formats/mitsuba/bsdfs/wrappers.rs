//! BSDFs that wrap others (`twosided`, `blendbsdf`, `mask`, `normalmap`, `bumpmap`): as in
//! Mitsuba, each takes its nested BSDFs under any name or none, beside its own parameters.

use super::super::tree::{Element, FileResolver};
use super::super::values::{boolean, float};
use super::texture::{float_texture, float_texture_of, reflectance_texture};
use super::{bsdf, check_properties, range};
use crate::limits::MAX_BLEND_MATERIALS;
use crate::scene::desc::{BlendDesc, BumpMapDesc, BumpScale, MaterialDesc, Opacity, Specular};
use crate::scene::error::SceneError;

type Ids = super::super::Ids;

pub(super) fn twosided(
    element: &Element,
    none: MaterialDesc,
    ids: &Ids,
    files: &FileResolver,
) -> Result<MaterialDesc, SceneError> {
    const PARAMETERS: [&str; 1] = ["allow_transmission"];
    check_properties(element, &PARAMETERS)?;
    let allowed = boolean(element, "allow_transmission")?;
    // Mitsuba's second nested BSDF shades the back: embray's materials have one BSDF for
    // both sides.
    let only = "twosided takes one nested <bsdf> (a different BSDF for the back is not supported)";
    let inner = nested_bsdf(element, &named(&PARAMETERS), ids, files, only)?;
    if transmits(&inner) {
        // As Mitsuba ("Only materials without a transmission component can be nested!"): the
        // back would be shaded as a second front. Mitsuba's allow_transmission renders that;
        // embray does not.
        let why = match allowed {
            Some(true) => "allow_transmission is not supported: ",
            _ => "",
        };
        return Err(element.error(format!(
            "{why}twosided cannot hold a transmitting BSDF (dielectric, roughdielectric, \
             thindielectric, mask, null, principledthin, or principled with spec_trans)"
        )));
    }
    Ok(MaterialDesc { name: none.name, ..two_sided(inner) })
}

pub(super) fn blendbsdf(
    element: &Element,
    none: MaterialDesc,
    ids: &Ids,
    files: &FileResolver,
) -> Result<MaterialDesc, SceneError> {
    check_properties(element, &["weight"])?;
    let parts = nested_bsdfs(element, &named(&["weight"]), ids, files)?;
    let [first, second] = <[MaterialDesc; 2]>::try_from(parts)
        .map_err(|_| element.error("blendbsdf takes two nested <bsdf>s"))?;
    let weight = number_or_texture(element, "weight", None, ids, files)?;
    if [&first, &second].iter().any(|m| m.normal_map.is_some() || m.bump_map.is_some()) {
        // Each would shade with its own normal: one frame serves the mixture.
        return Err(element.error("a normal or bump map inside a blendbsdf is not supported"));
    }
    let blend = BlendDesc { weight, materials: [first, second] };
    let material = MaterialDesc { blend: Some(Box::new(blend)), ..none };
    // Checked at every blend, so that its parts are in bounds and a chain whose links name
    // one `id` twice stops doubling at the limit.
    let count = material.blend_materials();
    if count > MAX_BLEND_MATERIALS {
        return Err(element.error(format!(
            "{count} materials in one blendbsdf, counting each as often as it is named (at \
             most {MAX_BLEND_MATERIALS})"
        )));
    }
    Ok(material)
}

pub(super) fn mask(
    element: &Element,
    none: MaterialDesc,
    ids: &Ids,
    files: &FileResolver,
) -> Result<MaterialDesc, SceneError> {
    check_properties(element, &["opacity"])?;
    let only = "mask takes one nested <bsdf>";
    let inner = nested_bsdf(element, &named(&["opacity"]), ids, files, only)?;
    if inner.opacity.is_some() {
        return Err(element.error("a mask inside a mask is not supported"));
    }
    let opacity = number_or_texture(element, "opacity", Some(0.5), ids, files)?;
    Ok(MaterialDesc { name: none.name, opacity: Some(opacity), ..inner })
}

pub(super) fn normalmap(
    element: &Element,
    none: MaterialDesc,
    ids: &Ids,
    files: &FileResolver,
) -> Result<MaterialDesc, SceneError> {
    check_properties(element, &["normalmap"])?;
    let only = "normalmap takes one nested <bsdf>";
    let inner = nested_bsdf(element, &named(&["normalmap"]), ids, files, only)?;
    let map = reflectance_texture(element, "normalmap", ids, files)?
        .ok_or_else(|| element.error("normalmap needs a <texture name=\"normalmap\">"))?;
    if inner.normal_map.is_some() || inner.bump_map.is_some() {
        return Err(element.error("a normal or bump map inside another is not supported"));
    }
    let bump_shadowing = true;
    Ok(MaterialDesc { name: none.name, normal_map: Some(map), bump_shadowing, ..inner })
}

pub(super) fn bumpmap(
    element: &Element,
    none: MaterialDesc,
    ids: &Ids,
    files: &FileResolver,
) -> Result<MaterialDesc, SceneError> {
    // Its texture under any name or none, as its BSDF: a reference is told apart by what it
    // refers to.
    let is_texture = |c: &Element| match c.tag.as_str() {
        "texture" => true,
        "ref" => ids.resolve(c).is_ok_and(|target| target.tag != "bsdf"),
        _ => false,
    };
    check_properties(element, &["scale"])?;
    let textures: Vec<&Element> = element.children.iter().filter(|c| is_texture(c)).collect();
    let [height] = textures[..] else {
        let count = textures.len();
        return Err(element.error(format!("bumpmap takes one height <texture>, not {count}")));
    };
    let parameter = |c: &Element| is_texture(c) || c.attr("name") == Some("scale");
    let only = "bumpmap takes one nested <bsdf>";
    let inner = nested_bsdf(element, &parameter, ids, files, only)?;
    let used_as = height.attr("name").unwrap_or("bumpmap's height");
    let texture = float_texture_of(height, used_as, range::ANY, ids, files)?;
    if inner.normal_map.is_some() || inner.bump_map.is_some() {
        return Err(element.error("a normal or bump map inside another is not supported"));
    }
    let factor = float(element, "scale")?.unwrap_or(1.0) as f32;
    let bump = BumpMapDesc { texture, factor, scale: BumpScale::Scene };
    let bump_shadowing = true;
    Ok(MaterialDesc { name: none.name, bump_map: Some(bump), bump_shadowing, ..inner })
}

/// Whether a child is one of the wrapper's `parameters`, by its name.
fn named<'a>(parameters: &'a [&str]) -> impl Fn(&Element) -> bool + 'a {
    |c: &Element| c.attr("name").is_some_and(|n| parameters.contains(&n))
}

/// The one `<bsdf>` (or reference to one) inside a wrapper such as `twosided` or `mask`.
fn nested_bsdf(
    element: &Element,
    parameter: &dyn Fn(&Element) -> bool,
    ids: &Ids,
    files: &FileResolver,
    otherwise: &str,
) -> Result<MaterialDesc, SceneError> {
    let mut inner = nested_bsdfs(element, parameter, ids, files)?;
    match inner.len() {
        1 => Ok(inner.remove(0)),
        _ => Err(element.error(otherwise)),
    }
}

/// The `<bsdf>`s (or references to them) inside `element`, in order. As in Mitsuba, a
/// wrapper takes its BSDFs under any name, or none: every reference that is not one of its
/// parameters must be to a BSDF.
fn nested_bsdfs(
    element: &Element,
    parameter: &dyn Fn(&Element) -> bool,
    ids: &Ids,
    files: &FileResolver,
) -> Result<Vec<MaterialDesc>, SceneError> {
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
    matches!(material.specular, Specular::Dielectric { .. } | Specular::ThinDielectric { .. })
        || material.opacity.is_some()
        || material.principled.as_ref().is_some_and(|p| p.transmits())
        || material.blend.as_ref().is_some_and(|b| b.materials.iter().any(transmits))
}

/// `material` scattering on both sides (`twosided`), a blend's materials too.
fn two_sided(material: MaterialDesc) -> MaterialDesc {
    let blend = material.blend.map(|b| {
        let [first, second] = b.materials;
        Box::new(BlendDesc { materials: [two_sided(first), two_sided(second)], ..*b })
    });
    MaterialDesc { one_sided: false, blend, ..material }
}

/// A number in [0, 1] (`default` where it may be left out) or a texture read as one: a
/// mask's opacity, a blend's weight.
fn number_or_texture(
    element: &Element,
    name: &str,
    default: Option<f64>,
    ids: &Ids,
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
