//! Texture tables → `TextureDesc`: each texture type takes only its own fields, and each use (colour, normal map, bump map, background) only its own keys.

use crate::scene::desc::{
    Interpolation, NoiseConversion, Opacity, Pattern, TextureDesc, TextureMode,
};
use crate::scene::error::SceneError;
use crate::scene::formats::toml::format::{
    ImageEncodingToml, InterpolationToml, NoiseConversionToml, OpacityToml, TextureKind,
    TextureModeToml, TextureToml, Vec3,
};
use crate::scene::formats::toml::source_map::FieldPath;
use crate::scene::formats::toml::validate::Ctx;
use glam::DAffine3;
use std::path::Path;

/// What a texture table colours.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Use {
    /// `texture`: takes `mode`; images decode sRGB unless told otherwise.
    Diffuse,
    /// `specular_texture`: no `mode`.
    Specular,
    /// `normal_map`: no `mode`; images are data, `raw` unless told otherwise.
    Normal,
    /// `bump_map`: as a normal map, with `factor`.
    Bump,
    /// `[render] background_texture`: no `mode`; uv patterns only.
    Background,
    /// A principled material's weight or η: no `mode`; colours may be above 1 (its mean
    /// channel is the number); images are data, `raw` unless told otherwise.
    Param,
    /// `emission_texture`: no `mode`; uv patterns only (an emitter sampled for light knows
    /// its point's texture coordinates, not its object-space point); colours may be above 1.
    Emission,
}

/// `[render] background_texture`: an image or a 2-D checkerboard over the image plane.
pub(crate) fn background_texture(
    t: &TextureToml,
    ctx: &Ctx,
    base_dir: &Path,
) -> Result<TextureDesc, SceneError> {
    let path = FieldPath::root("render").key("background_texture");
    texture_desc(&path, t, Use::Background, ctx, base_dir)
}

/// The `type` of a texture table, as written.
pub(super) fn kind_name_of(t: &TextureToml) -> &'static str {
    match t.kind {
        TextureKind::Checker2d => "checker2d",
        TextureKind::Checker3d => "checker3d",
        TextureKind::Checker => "checker",
        TextureKind::Perlin => "perlin",
        TextureKind::Image => "image",
        TextureKind::Constant => "constant",
        TextureKind::MeshAttribute => "mesh_attribute",
    }
}

/// One `texture`, `specular_texture` or `normal_map` table.
pub(super) fn texture_desc(
    path: &FieldPath,
    t: &TextureToml,
    usage: Use,
    ctx: &Ctx,
    base_dir: &Path,
) -> Result<TextureDesc, SceneError> {
    let uv_only = matches!(usage, Use::Background | Use::Emission);
    if uv_only && !matches!(t.kind, TextureKind::Image | TextureKind::Checker2d) {
        let requirement = "a pattern with texture coordinates (image or checker2d)";
        return Err(ctx.out_of_range(&path.key("type"), kind_name_of(t), requirement));
    }
    let (kind_name, own): (&str, &[&str]) = match t.kind {
        TextureKind::Checker2d => ("checker2d", &["scale", "even", "odd"]),
        TextureKind::Checker3d => ("checker3d", &["scale", "even", "odd"]),
        TextureKind::Checker => ("checker", &["scale", "offset", "black", "white"]),
        TextureKind::Perlin => ("perlin", &["scale", "conversion"]),
        TextureKind::Constant => ("constant", &["value"]),
        TextureKind::MeshAttribute => ("mesh_attribute", &["name", "scale"]),
        TextureKind::Image => {
            ("image", &["file", "interpolation", "encoding", "normalizer", "flip_v"])
        }
    };
    let item = format!("{path} ({kind_name})");
    let mut allowed = vec!["type"];
    if usage == Use::Diffuse {
        allowed.push("mode");
    }
    if usage == Use::Bump {
        allowed.extend(["factor", "heights"]);
    }
    allowed.extend(own);
    let present = [
        ("mode", t.mode.is_some()),
        ("scale", t.scale.is_some()),
        ("even", t.even.is_some()),
        ("odd", t.odd.is_some()),
        ("offset", t.offset.is_some()),
        ("black", t.black.is_some()),
        ("white", t.white.is_some()),
        ("conversion", t.conversion.is_some()),
        ("file", t.file.is_some()),
        ("value", t.value.is_some()),
        ("name", t.name.is_some()),
        ("interpolation", t.interpolation.is_some()),
        ("encoding", t.encoding.is_some()),
        ("normalizer", t.normalizer.is_some()),
        ("flip_v", t.flip_v.is_some()),
        ("factor", t.factor.is_some()),
        ("heights", t.heights.is_some()),
    ];
    ctx.check_fields(path, &item, &present, &allowed)?;
    let scale = |ctx: &Ctx| -> Result<f32, SceneError> {
        let field = path.key("scale");
        let scale = ctx.positive(&field, t.scale.unwrap_or(1.0))?;
        ctx.f32(&field, scale)
    };
    let color = |ctx: &Ctx, name: &str, value: Option<Vec3>, default: f64| {
        let in_unit_range = !matches!(usage, Use::Param | Use::Emission);
        ctx.color(&path.key(name), value.unwrap_or([default; 3]), in_unit_range)
    };
    let pattern = match t.kind {
        TextureKind::Checker2d | TextureKind::Checker3d => {
            ctx.required(path, &item, "scale", t.scale)?;
            let scale = scale(ctx)?;
            let even = color(ctx, "even", Some(ctx.required(path, &item, "even", t.even)?), 0.0)?;
            let odd = color(ctx, "odd", Some(ctx.required(path, &item, "odd", t.odd)?), 0.0)?;
            if t.kind == TextureKind::Checker2d {
                Pattern::Checker2d { scale, even, odd }
            } else {
                Pattern::Checker3d { scale, even, odd }
            }
        }
        TextureKind::Checker => {
            let field = path.key("offset");
            let offset = ctx.f32(&field, t.offset.unwrap_or(0.0))?;
            Pattern::CourseChecker {
                scale: scale(ctx)?,
                offset,
                black: color(ctx, "black", t.black, 0.0)?,
                white: color(ctx, "white", t.white, 1.0)?,
            }
        }
        TextureKind::Perlin => Pattern::Perlin {
            scale: scale(ctx)?,
            conversion: match t.conversion.unwrap_or(NoiseConversionToml::Absval) {
                NoiseConversionToml::Absval => NoiseConversion::Absolute,
                NoiseConversionToml::Linear => NoiseConversion::Linear,
            },
        },
        TextureKind::Constant => {
            let value = ctx.required(path, &item, "value", t.value)?;
            if usage == Use::Bump {
                // A constant height bumps nothing, whatever its value (a Mitsuba
                // `rawconstant`, which has no range, converts to one).
                let ok = value.iter().all(|v| v.is_finite() && v.abs() <= f32::MAX as f64);
                ctx.require(ok, &path.key("value"), format!("{value:?}"), "three finite numbers")?;
                Pattern::Constant(glam::DVec3::from_array(value).as_vec3())
            } else {
                // Checked as the checkers' colours are: the renderer would clamp an albedo
                // of 5 to 1 without a word.
                Pattern::Constant(color(ctx, "value", Some(value), 0.0)?)
            }
        }
        TextureKind::MeshAttribute => Pattern::MeshAttribute {
            name: ctx.required(path, &item, "name", t.name.clone())?,
            scale: scale(ctx)?,
        },
        TextureKind::Image => {
            let file = ctx.required(path, &item, "file", t.file.as_deref())?;
            let default = if matches!(usage, Use::Normal | Use::Bump | Use::Param) {
                ImageEncodingToml::Raw
            } else {
                ImageEncodingToml::Srgb
            };
            let srgb = t.encoding.unwrap_or(default) == ImageEncodingToml::Srgb;
            if srgb && t.normalizer.is_some() {
                let requirement = "given only with encoding = \"raw\"";
                ctx.require(false, &path.key("normalizer"), "given", requirement)?;
            }
            let field = path.key("normalizer");
            let normalizer =
                if srgb { 1.0 } else { ctx.positive(&field, t.normalizer.unwrap_or(255.0))? };
            let at = crate::scene::texture_image::ImageRef {
                image: base_dir.join(file),
                scene: ctx.file,
                item: path.key("file").to_string(),
                line: ctx.line(&path.key("file")),
            };
            let image = crate::scene::texture_image::load_radiance(&at, srgb)?;
            Pattern::Image {
                image: match t.flip_v {
                    Some(true) => crate::scene::texture_image::with_rows_flipped(&image),
                    _ => image,
                },
                interpolation: match t.interpolation.unwrap_or(InterpolationToml::Bilinear) {
                    InterpolationToml::Nearest => Interpolation::Nearest,
                    InterpolationToml::Bilinear => Interpolation::Bilinear,
                    InterpolationToml::BilinearCentered => Interpolation::BilinearCentered,
                },
                normalizer: ctx.f32(&field, normalizer)?,
            }
        }
    };
    let mode = match t.mode.unwrap_or(TextureModeToml::Replace) {
        TextureModeToml::Replace => TextureMode::Replace,
        TextureModeToml::Blend => TextureMode::Blend,
        TextureModeToml::ReplaceAll => TextureMode::ReplaceAll,
    };
    // A material from the table is attached to objects directly: its pattern lives in the
    // space of each object's own vertices.
    Ok(TextureDesc { pattern, mode, texture_from_object: DAffine3::IDENTITY })
}

/// A number in [0, 1] or a texture's mean channel: an opacity, a blend's weight.
pub(super) fn number_or_texture(
    field: &FieldPath,
    value: &OpacityToml,
    ctx: &Ctx,
    base_dir: &Path,
) -> Result<Opacity, SceneError> {
    match value {
        OpacityToml::Constant(value) => {
            ctx.require((0.0..=1.0).contains(value), field, value, "in [0, 1]")?;
            Ok(Opacity::Constant(*value as f32))
        }
        OpacityToml::Texture(t) => {
            Ok(Opacity::Texture(texture_desc(field, t, Use::Specular, ctx, base_dir)?))
        }
    }
}
