//! Textures as inline TOML tables.

use super::TomlWriteError;
use super::values::{c3, f, quoted};
use crate::scene::desc::{Pattern, TextureDesc, TextureMode};
use glam::{DAffine3, Vec3};

/// The inline table of a texture; `with_mode` for the diffuse one (a specular texture
/// always replaces).
pub(super) fn texture_toml(t: &TextureDesc, with_mode: bool) -> Result<String, TomlWriteError> {
    texture_table(t, with_mode, true)
}

/// `texture_toml`, with colours above 1 refused only if `bounded` (a principled material's
/// weights and η may exceed 1).
pub(super) fn texture_table(
    t: &TextureDesc,
    with_mode: bool,
    bounded: bool,
) -> Result<String, TomlWriteError> {
    let unsupported = |problem: &str| TomlWriteError::Unsupported {
        item: "a texture".to_owned(),
        problem: problem.to_owned(),
    };
    if t.texture_from_object != DAffine3::IDENTITY {
        return Err(unsupported("it is mapped through a transform"));
    }
    let at_most_one = |c: Vec3| {
        if bounded && c.max_element() > 1.0 { Err(unsupported("a colour above 1")) } else { Ok(()) }
    };
    let fields = match &t.pattern {
        Pattern::Checker2d { scale, even, odd } | Pattern::Checker3d { scale, even, odd } => {
            at_most_one(even.max(*odd))?;
            let kind = if matches!(t.pattern, Pattern::Checker2d { .. }) {
                "checker2d"
            } else {
                "checker3d"
            };
            format!(
                "type = \"{kind}\", scale = {}, even = {}, odd = {}",
                f(*scale as f64),
                c3(*even),
                c3(*odd)
            )
        }
        Pattern::Constant(value) => format!("type = \"constant\", value = {}", c3(*value)),
        // The writer's meshes are OBJ files, which keep no attributes.
        Pattern::UvMapped(_) => {
            return Err(unsupported("its texture coordinates are mapped (no TOML form yet)"));
        }
        Pattern::MeshAttribute { .. } => {
            return Err(unsupported(
                "it looks up a mesh attribute, which the OBJ meshes convert writes do not carry",
            ));
        }
        Pattern::CourseChecker { scale, offset, black, white } => {
            at_most_one(black.max(*white))?;
            format!(
                "type = \"checker\", scale = {}, offset = {}, black = {}, white = {}",
                f(*scale as f64),
                f(*offset as f64),
                c3(*black),
                c3(*white)
            )
        }
        Pattern::Perlin { scale, conversion } => {
            format!(
                "type = \"perlin\", scale = {}, conversion = \"{conversion}\"",
                f(*scale as f64)
            )
        }
        Pattern::Image { image, interpolation, normalizer } => {
            // Absolute, so that the TOML finds the image wherever it is written.
            let file = std::path::absolute(&image.file).unwrap_or_else(|_| image.file.clone());
            let encoding = if image.srgb_decoded {
                "encoding = \"srgb\"".to_owned()
            } else {
                format!("encoding = \"raw\", normalizer = {}", f(*normalizer as f64))
            };
            let flip = if image.rows_flipped { ", flip_v = true" } else { "" };
            format!(
                "type = \"image\", file = {}, interpolation = \"{interpolation}\", \
                 {encoding}{flip}",
                quoted(&file.to_string_lossy())
            )
        }
    };
    let mode = if with_mode && t.mode != TextureMode::Replace {
        format!(", mode = \"{}\"", t.mode)
    } else {
        String::new()
    };
    Ok(format!("{{ {fields}{mode} }}"))
}
