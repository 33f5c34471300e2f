//! `<texture>` properties of BSDFs: bitmap and checkerboard, for a reflectance or a
//! mask's opacity.

use super::super::tree::{Element, FileResolver};
use super::super::values::{
    ColorUse, boolean, color, f32_sized, number_attr, property, string, vec3,
};
use super::range::Range;
use super::reflectance;
use crate::scene::desc::{Interpolation, Pattern, TextureDesc, TextureMode, UvMapped, Wrap};
use crate::scene::error::{Line, SceneError};
use crate::scene::texture_image::{self, ImageRef, load_radiance};
use glam::{DAffine3, DVec3, Vec3};

/// A `<texture name="…">` read as a number (a roughness, a mask's opacity, a bump map's
/// height); see `texture`.
/// A checkerboard's colours must lie in `range`, as the number they stand for must.
pub(super) fn float_texture(
    element: &Element,
    name: &str,
    range: Range,
    ids: &super::super::Ids,
    files: &FileResolver,
) -> Result<Option<TextureDesc>, SceneError> {
    texture(element, name, ids, files, LookedUp::Number(range))
}

/// A `<texture name="…">` (bitmap or checkerboard) for the reflectance `name`.
pub(super) fn reflectance_texture(
    element: &Element,
    name: &str,
    ids: &super::super::Ids,
    files: &FileResolver,
) -> Result<Option<TextureDesc>, SceneError> {
    texture(element, name, ids, files, LookedUp::Reflectance)
}

/// What a texture's values stand for, which decides how its constants are checked.
#[derive(Clone, Copy)]
enum LookedUp {
    /// A colour in [0, 1].
    Reflectance,
    /// An emitter's radiance: a colour >= 0, without an upper bound.
    Radiance,
    /// A number in a range (a roughness, an opacity, a height).
    Number(Range),
}

/// The texture `name`, looked up as a number in a range (`as_number`) or a colour: Mitsuba's
/// checkerboard gives `color0` where u's and v's halves agree when a colour is looked up
/// (`eval`), and where they differ when a number is (`eval_1`); a colour read as a number
/// is its luminance (embray's number lookups take the mean channel, which of a grey is
/// the grey).
fn texture(
    element: &Element,
    name: &str,
    ids: &super::super::Ids,
    files: &FileResolver,
    looked_up: LookedUp,
) -> Result<Option<TextureDesc>, SceneError> {
    let found = element
        .children
        .iter()
        .find(|c| matches!(c.tag.as_str(), "texture" | "ref") && c.attr("name") == Some(name));
    found.map(|texture| read(texture, name, ids, files, looked_up)).transpose()
}

/// The `<texture>` (or reference to one) `texture`, read as a number in `range` (a bump
/// map's height, which Mitsuba takes under any name or none); `used_as` names it in
/// messages.
pub(super) fn float_texture_of(
    texture: &Element,
    used_as: &str,
    range: Range,
    ids: &super::super::Ids,
    files: &FileResolver,
) -> Result<TextureDesc, SceneError> {
    read(texture, used_as, ids, files, LookedUp::Number(range))
}

/// The `<texture>` (or reference to one) `texture`, an area emitter's radiance.
pub(super) fn radiance_texture(
    texture: &Element,
    ids: &super::super::Ids,
    files: &FileResolver,
) -> Result<TextureDesc, SceneError> {
    read(texture, "radiance", ids, files, LookedUp::Radiance)
}

/// The texture `texture` is (or refers to), looked up as `fn texture` describes; `used_as`
/// names it in messages.
fn read(
    texture: &Element,
    used_as: &str,
    ids: &super::super::Ids,
    files: &FileResolver,
    looked_up: LookedUp,
) -> Result<TextureDesc, SceneError> {
    let as_number = match looked_up {
        LookedUp::Number(range) => Some(range),
        LookedUp::Reflectance | LookedUp::Radiance => None,
    };
    let texture = ids.resolve(texture)?;
    if texture.tag != "texture" {
        return Err(texture.error(format!("`{used_as}` must be a colour or a <texture>")));
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
            let interpolation = match choice(texture, "filter_type", &["bilinear", "nearest"])? {
                Some("nearest") => Interpolation::Nearest,
                _ => Interpolation::BilinearCentered,
            };
            // Storage precision only (Mitsuba's spectral variants refuse uint8; RGB's do not).
            choice(texture, "format", &["auto", "variant", "float16", "fp16", "uint8"])?;
            boolean(texture, "accel")?;
            let raw = boolean(texture, "raw")?.unwrap_or(false);
            let at = ImageRef {
                image: files.resolve(file.required("value")?),
                scene: &file.file,
                item: file.describe(),
                line: Line(Some(file.line)),
            };
            // EXR files hold linear values: read as TOML's and CENG795's textures read them.
            let image = load_radiance(&at, !raw)?;
            let image =
                if as_number.is_some() { texture_image::as_luminance(&image) } else { image };
            let normalizer = if image.srgb_decoded || image.hdr { 1.0 } else { 255.0 };
            Pattern::Image { image, interpolation, normalizer }
        }
        "checkerboard" => {
            if let Some(nested) =
                texture.children.iter().find(|c| matches!(c.tag.as_str(), "texture" | "ref"))
            {
                return Err(nested.error("a checkerboard of textures is not supported"));
            }
            // A colour or a number, in [0, 1] for a reflectance, >= 0 for a radiance and in
            // the number's range for a number (a roughness, a principled weight) either way.
            let color_of = |name: &str, default: f32| -> Result<Vec3, SceneError> {
                let child = texture.children.iter().find(|c| c.attr("name") == Some(name));
                let range = match looked_up {
                    LookedUp::Reflectance => {
                        return Ok(reflectance(texture, name)?.unwrap_or(Vec3::splat(default)));
                    }
                    LookedUp::Radiance => return radiance(child, default),
                    LookedUp::Number(range) => range,
                };
                let Some(child) = child else { return Ok(Vec3::splat(default)) };
                let rgb = color(child, ColorUse::Reflectance)?;
                if let Some(bad) = rgb.to_array().into_iter().find(|v| !range.contains(*v)) {
                    return Err(child.error(format!(
                        "{name} is {bad}, but must be {} (as `{}` is)",
                        range.describe(),
                        used_as
                    )));
                }
                Ok(rgb.as_vec3())
            };
            let (color0, color1) = (color_of("color0", 0.4)?, color_of("color1", 0.2)?);
            let (even, odd) = if as_number.is_some() {
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
                "vector" | "point" => vec3(value, None)?,
                "rgb" => color(value, ColorUse::Unbounded)?,
                "float" => DVec3::splat(number_attr(value, "value")?),
                other => {
                    return Err(value.error(format!("a rawconstant's value cannot be <{other}>")));
                }
            };
            Pattern::Constant(f32_sized(texture, value)?.as_vec3())
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
    Ok(TextureDesc { pattern, mode: TextureMode::Replace, texture_from_object: DAffine3::IDENTITY })
}

/// A checkerboard's colour `child` as a radiance (`default` where it is not given).
fn radiance(child: Option<&Element>, default: f32) -> Result<Vec3, SceneError> {
    let Some(child) = child else { return Ok(Vec3::splat(default)) };
    let rgb = color(child, ColorUse::Emission)?;
    if !rgb.cmpge(DVec3::ZERO).all() {
        return Err(child.error(format!("a radiance must be >= 0, not {rgb}")));
    }
    Ok(rgb.as_vec3())
}

/// The `<string>` `name` of `texture`, one of `choices` (as Mitsuba checks it), or `None`.
fn choice<'a>(
    texture: &'a Element,
    name: &str,
    choices: &[&str],
) -> Result<Option<&'a str>, SceneError> {
    let Some(found) = string(texture, name)? else { return Ok(None) };
    let value = found.required("value")?;
    if !choices.contains(&value) {
        return Err(found.error(format!(
            "the {name} '{}' is not known ({})",
            crate::excerpt::excerpt(value),
            choices.join(", ")
        )));
    }
    Ok(Some(value))
}

/// `pattern` with the texture's `to_uv` and `wrap_mode` applied (a uniform scale of a
/// checkerboard's coordinates stays a checkerboard: more checks).
fn uv_mapped(texture: &Element, pattern: Pattern) -> Result<Pattern, SceneError> {
    let wrap = match choice(texture, "wrap_mode", &["repeat", "mirror", "clamp"])? {
        None | Some("repeat") => Wrap::Repeat,
        Some("mirror") => Wrap::Mirror,
        _ => Wrap::Clamp,
    };
    let to_uv = match texture.children.iter().find(|c| c.attr("name") == Some("to_uv")) {
        Some(other) if other.tag != "transform" => {
            return Err(other.error("`to_uv` must be a <transform>"));
        }
        found => found,
    };
    let Some(to_uv) = to_uv else {
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
