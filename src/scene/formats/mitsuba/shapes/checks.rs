//! What a Mitsuba shape asks that embray would render otherwise than Mitsuba, refused by
//! name: a sphere whose `to_world` scales unevenly or mirrors, a BSDF looking up a mesh
//! attribute the shape lacks, or one whose colours lie outside [0, 1].

use super::super::tree::Element;
use super::super::values::property;
use crate::scene::desc::{MaterialDesc, Pattern, ShapeDesc};
use crate::scene::error::SceneError;
use glam::{DAffine3, DMat3};

/// How far (relative) the squared scales of a sphere's `to_world` may differ and still be
/// one scale: Mitsuba's `is_similarity` tolerance (relative 1e-3), which rotations written
/// to a few digits, or about an axis just off unit length, stay within.
const UNEVEN_SCALE: f64 = 1e-3;

/// Refuses a sphere whose `to_world` is not a rotation times one positive scale. Mitsuba
/// keeps only the scale of its x axis (a sphere where embray would draw an ellipsoid), and
/// turns a mirrored sphere inside out (its normals inwards: a one-sided BSDF black from
/// outside, an emitter lighting only its inside), which embray's spheres cannot.
pub(in super::super) fn sphere_to_world(
    element: &Element,
    world_from_object: &DAffine3,
) -> Result<(), SceneError> {
    let at = property(element, "transform", "to_world").unwrap_or(element);
    let linear = world_from_object.matrix3;
    let gram = linear.transpose() * linear;
    let squared_scale = (gram.x_axis.x + gram.y_axis.y + gram.z_axis.z) / 3.0;
    let uneven = (gram - DMat3::from_diagonal(glam::DVec3::splat(squared_scale)))
        .to_cols_array()
        .iter()
        .any(|d| d.abs() > UNEVEN_SCALE * squared_scale);
    if uneven {
        return Err(at.error(
            "a sphere's to_world scales unevenly (or shears); Mitsuba would render a sphere \
             (of its x axis's scale), not this ellipsoid: use a uniform scale, or a mesh",
        ));
    }
    if linear.determinant() < 0.0 {
        return Err(at.error(
            "a sphere's to_world mirrors it (a negative scale); Mitsuba would render it inside \
             out (normals inwards), which embray does not: use a rotation instead",
        ));
    }
    Ok(())
}

/// Refuses a shape without a mesh attribute its material looks up (as Mitsuba does), and
/// one whose attribute gives a colour (reflectance) outside [0, 1]: Mitsuba uses the values
/// as they are (a PLY's 8-bit colours as 0–255, 255 times too bright) and embray would
/// clamp them, so neither renders what was meant.
pub(in super::super) fn mesh_attributes(
    element: &Element,
    shapes: &[ShapeDesc],
    material: &MaterialDesc,
) -> Result<(), SceneError> {
    let colours = colour_attributes(material);
    for name in material.mesh_attributes() {
        for shape in shapes {
            let attributes = match shape {
                ShapeDesc::Mesh(mesh) => &mesh.attributes[..],
                ShapeDesc::Sphere { .. } | ShapeDesc::SdfGrid(_) => &[],
            };
            let Some(attribute) = attributes.iter().find(|a| a.name == name) else {
                let has: Vec<&str> = attributes.iter().map(|a| a.name.as_str()).collect();
                let has = if has.is_empty() { "none".to_owned() } else { has.join(", ") };
                return Err(element.error(format!(
                    "its BSDF looks up the mesh attribute `{name}`, which the shape does not \
                     have (it has: {has})"
                )));
            };
            // 1/255 as written (0.00392157) takes 255 to 1.0000002: past 1 by rounding only.
            let reflectance = 0.0..=1.0 + 1e-4;
            for &(_, scale) in colours.iter().filter(|(colour, _)| *colour == name) {
                let outside =
                    attribute.values.iter().map(|&v| v * scale).find(|v| !reflectance.contains(v));
                if let Some(value) = outside {
                    let file = property(element, "string", "filename")
                        .and_then(|f| f.attr("value"))
                        .map_or(String::new(), |f| format!(" of '{f}'"));
                    return Err(element.error(format!(
                        "its BSDF takes a reflectance from the mesh attribute `{name}`{file}, \
                         which reaches {value} (outside [0, 1]; 8-bit colours are not divided \
                         by 255): Mitsuba would use it as it is, embray would clamp it; store \
                         colours in [0, 1] or give the texture a scale (1/255: 0.00392157)"
                    )));
                }
            }
        }
    }
    Ok(())
}

/// The mesh attributes (with their scales) that `material` and its blend's parts use as a
/// colour: the reflectance or base colour, and the specular reflectance.
fn colour_attributes(material: &MaterialDesc) -> Vec<(&str, f32)> {
    let mut found: Vec<(&str, f32)> = [&material.texture, &material.specular_texture]
        .into_iter()
        .flatten()
        .filter_map(|t| match &t.pattern {
            Pattern::MeshAttribute { name, scale } => Some((name.as_str(), *scale)),
            _ => None,
        })
        .collect();
    for part in material.blend.iter().flat_map(|b| b.materials.iter()) {
        found.extend(colour_attributes(part));
    }
    found
}
