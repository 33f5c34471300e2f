//! `<texture>` properties of BSDFs: bitmap and checkerboard, for a reflectance or a
//! mask's opacity.

use super::super::tree::{Element, FileResolver};
use super::super::values::{ColorUse, boolean, color, number_attr, property, vec3};
use super::reflectance;
use crate::scene::desc::{Interpolation, Pattern, TextureDesc, TextureMode, UvMapped, Wrap};
use crate::scene::error::{Line, SceneError};
use crate::scene::texture_image::{ImageRef, load};
use glam::{DAffine3, DVec3, Vec3};

/// A `<texture name="…">` read as a number (a roughness, a mask's opacity, a bump map's
/// height); see `texture`.
pub(super) fn float_texture(
    element: &Element,
    name: &str,
    ids: &super::super::Ids,
    files: &FileResolver,
) -> Result<Option<TextureDesc>, SceneError> {
    texture(element, name, ids, files, true)
}

/// A `<texture name="…">` (bitmap or checkerboard) for the reflectance `name`.
pub(super) fn reflectance_texture(
    element: &Element,
    name: &str,
    ids: &super::super::Ids,
    files: &FileResolver,
) -> Result<Option<TextureDesc>, SceneError> {
    texture(element, name, ids, files, false)
}

/// The texture `name`, looked up as a number (`as_number`) or a colour: Mitsuba's
/// checkerboard gives `color0` where u's and v's halves agree when a colour is looked up
/// (`eval`), and where they differ when a number is (`eval_1`); a colour read as a number
/// is its luminance (embray's number lookups take the mean channel, which of a grey is
/// the grey).
fn texture(
    element: &Element,
    name: &str,
    ids: &super::super::Ids,
    files: &FileResolver,
    as_number: bool,
) -> Result<Option<TextureDesc>, SceneError> {
    let Some(texture) = element
        .children
        .iter()
        .find(|c| matches!(c.tag.as_str(), "texture" | "ref") && c.attr("name") == Some(name))
    else {
        return Ok(None);
    };
    let texture = ids.resolve(texture)?;
    if texture.tag != "texture" {
        return Err(texture.error(format!("`{name}` must be a colour or a <texture>")));
    }
    let kind = texture.required("type")?;
    let known: &[&str] = match kind {
        "bitmap" => &["filename", "filter_type", "wrap_mode", "raw", "to_uv", "format", "accel"],
        "checkerboard" => &["color0", "color1", "to_uv"],
        "rawconstant" => &["value"],
        "mesh_attribute" => &["name", "scale"],
        _ => &[],
    };
    if let Some(child) =
        texture.children.iter().find(|c| !c.attr("name").is_some_and(|n| known.contains(&n)))
    {
        return Err(child.error(format!(
            "the {kind} texture does not take {} (it takes: {})",
            child.attr("name").map_or_else(|| format!("a <{}>", child.tag), |n| format!("`{n}`")),
            known.join(", ")
        )));
    }
    let pattern = match kind {
        "bitmap" => {
            let file = property(texture, "string", "filename")
                .ok_or_else(|| texture.error("a bitmap needs a filename"))?;
            let raw = boolean(texture, "raw")?.unwrap_or(false);
            let at = ImageRef {
                image: files.resolve(file.required("value")?),
                scene: &file.file,
                item: file.describe(),
                line: Line(Some(file.line)),
            };
            let image = load(&at, !raw)?;
            let image =
                if as_number { crate::scene::texture_image::as_luminance(&image) } else { image };
            let normalizer = if image.srgb_decoded || image.hdr { 1.0 } else { 255.0 };
            let interpolation = match property(texture, "string", "filter_type") {
                Some(f) if f.required("value")? == "nearest" => Interpolation::Nearest,
                _ => Interpolation::BilinearCentered,
            };
            Pattern::Image { image, interpolation, normalizer }
        }
        "checkerboard" => {
            // A colour, or a number for a float texture (a roughness).
            let color_of = |name: &str, default: f64| -> Result<Vec3, SceneError> {
                if let Some(rgb) = reflectance(texture, name)? {
                    return Ok(rgb);
                }
                let number = super::super::values::float(texture, name)?;
                Ok(Vec3::splat(number.unwrap_or(default) as f32))
            };
            let (color0, color1) = (color_of("color0", 0.4)?, color_of("color1", 0.2)?);
            let (even, odd) = if as_number {
                let grey = |c: Vec3| Vec3::splat(crate::color::luminance(c));
                (grey(color1), grey(color0))
            } else {
                (color0, color1)
            };
            Pattern::Checker2d { scale: 2.0, even, odd }
        }
        "rawconstant" => {
            let value = texture
                .children
                .iter()
                .find(|c| c.attr("name") == Some("value"))
                .ok_or_else(|| texture.error("a rawconstant needs a `value`"))?;
            let value = match value.tag.as_str() {
                "vector" | "point" => vec3(value, false)?,
                "rgb" => color(value, ColorUse::Unbounded)?,
                "float" => DVec3::splat(number_attr(value, "value")?),
                other => {
                    return Err(value.error(format!("a rawconstant's value cannot be <{other}>")));
                }
            };
            Pattern::Constant(value.as_vec3())
        }
        "mesh_attribute" => {
            let name = property(texture, "string", "name")
                .ok_or_else(|| texture.error("a mesh_attribute needs a `name`"))?
                .required("value")?;
            if !name.starts_with("vertex_") && !name.starts_with("face_") {
                return Err(texture.error(format!(
                    "the attribute name '{name}' must start with vertex_ or face_"
                )));
            }
            let scale = super::super::values::float(texture, "scale")?.unwrap_or(1.0) as f32;
            Pattern::MeshAttribute { name: name.to_owned(), scale }
        }
        other => {
            return Err(texture.error(format!(
                "the texture '{other}' is not supported yet (bitmap, checkerboard, \
                 rawconstant and mesh_attribute are)"
            )));
        }
    };
    let pattern = uv_mapped(texture, pattern)?;
    Ok(Some(TextureDesc {
        pattern,
        mode: TextureMode::Replace,
        texture_from_object: DAffine3::IDENTITY,
    }))
}

/// `pattern` with the texture's `to_uv` and `wrap_mode` applied (a uniform scale of a
/// checkerboard's coordinates stays a checkerboard: more checks).
fn uv_mapped(texture: &Element, pattern: Pattern) -> Result<Pattern, SceneError> {
    let wrap = match property(texture, "string", "wrap_mode") {
        None => Wrap::Repeat,
        Some(w) => match w.required("value")? {
            "repeat" => Wrap::Repeat,
            "mirror" => Wrap::Mirror,
            "clamp" => Wrap::Clamp,
            other => {
                return Err(w.error(format!(
                    "the wrap_mode '{}' is not known (repeat, mirror or clamp)",
                    crate::excerpt::excerpt(other)
                )));
            }
        },
    };
    let Some(to_uv) = property(texture, "transform", "to_uv") else {
        return Ok(match wrap {
            Wrap::Repeat => pattern,
            _ => Pattern::UvMapped(Box::new(UvMapped {
                uv_from_surface: glam::Affine2::IDENTITY,
                wrap,
                inner: pattern,
            })),
        });
    };
    let m = super::super::transform::transform(to_uv)?;
    if let Pattern::Checker2d { scale, even, odd } = pattern {
        let factor = m.matrix3.x_axis.x;
        let uniform = m.matrix3 == glam::DMat3::from_diagonal(DVec3::new(factor, factor, 1.0))
            || m.matrix3 == glam::DMat3::from_diagonal(DVec3::splat(factor));
        if uniform && m.translation == DVec3::ZERO && factor > 0.0 {
            return Ok(Pattern::Checker2d { scale: scale * factor as f32, even, odd });
        }
    }
    // Mitsuba's 2-D transform: the x and y rows and columns of the 3-D one, with its
    // translation.
    let uv_from_surface = glam::DAffine2::from_cols(
        m.matrix3.x_axis.truncate(),
        m.matrix3.y_axis.truncate(),
        m.translation.truncate(),
    );
    if !uv_from_surface.is_finite() {
        return Err(to_uv.error("to_uv is not finite"));
    }
    let uv_from_surface = glam::Affine2::from_mat3(glam::DMat3::from(uv_from_surface).as_mat3());
    Ok(Pattern::UvMapped(Box::new(UvMapped { uv_from_surface, wrap, inner: pattern })))
}
