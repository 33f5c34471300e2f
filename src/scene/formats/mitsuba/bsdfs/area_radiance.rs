//! An area emitter's `radiance`: a constant colour, or a texture of the surface's texture
//! coordinates (a bitmap or checkerboard), as Mitsuba's `area` emitter takes it.

use super::super::Ids;
use super::super::tree::{Element, FileResolver};
use super::super::values::{ColorUse, PROPERTY_TAGS, color, float};
use super::texture::radiance_texture;
use crate::scene::desc::{Pattern, TextureDesc};
use crate::scene::error::SceneError;
use glam::{DVec3, Vec3};

/// The radiance of the `<emitter type="area">` `emitter`: the emission, and the texture it
/// is multiplied by per point (then the emission is 1).
pub(in super::super) fn area_radiance(
    emitter: &Element,
    ids: &Ids,
    files: &FileResolver,
) -> Result<(Vec3, Option<TextureDesc>), SceneError> {
    // Anything else would otherwise be dropped unseen. `sampling_weight` changes how Mitsuba
    // samples, not what it renders: checked, and not used (as for the other emitters).
    let radiance = |c: &&Element| {
        let tag = c.tag.as_str();
        (PROPERTY_TAGS.contains(&tag) || matches!(tag, "texture" | "ref"))
            && c.attr("name") == Some("radiance")
    };
    let weight = |c: &&Element| c.attr("name") == Some("sampling_weight");
    if let Some(other) = emitter.children.iter().find(|c| !radiance(c) && !weight(c)) {
        return Err(other.error(
            "an area emitter takes only its radiance (an <rgb>, <spectrum>, <float> or \
             <texture> named radiance) and a sampling_weight",
        ));
    }
    float(emitter, "sampling_weight")?;
    let Some(given) = emitter.children.iter().find(radiance) else {
        return Ok((Vec3::ONE, None));
    };
    if matches!(given.tag.as_str(), "texture" | "ref") {
        let texture = radiance_texture(given, ids, files)?;
        return match texture.pattern {
            Pattern::MeshAttribute { .. } => Err(given.error(
                "an area emitter's radiance cannot be a mesh_attribute (a bitmap, \
                 checkerboard or rawconstant can)",
            )),
            // The same everywhere: a constant radiance (sampled as one, written as one).
            Pattern::Constant(value) if value.cmpge(Vec3::ZERO).all() => Ok((value, None)),
            Pattern::Constant(value) => {
                Err(given.error(format!("a radiance must be >= 0, not {value}")))
            }
            _ => Ok((Vec3::ONE, Some(texture))),
        };
    }
    let radiance = color(given, ColorUse::Emission)?;
    if !radiance.cmpge(DVec3::ZERO).all() {
        return Err(emitter.error("radiance must be >= 0"));
    }
    Ok((radiance.as_vec3(), None))
}
