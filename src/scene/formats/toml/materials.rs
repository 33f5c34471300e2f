//! `[materials.NAME]` → `MaterialDesc`: a Lambertian part (`albedo` or a `texture`), one
//! specular lobe chosen by `type`, emission, and the course's Phong terms. Each type takes
//! only its own fields.

use crate::scene::desc::{CourseBrdf, MaterialDesc, Pattern, PhongDesc, Specular, TextureDesc};
use crate::scene::desc::{Interpolation, NoiseConversion, TextureMode};
use crate::scene::error::SceneError;
use crate::scene::formats::toml::format::{
    BrdfModelToml, BrdfToml, ImageEncodingToml, InterpolationToml, MaterialKind, MaterialToml,
    MetalPreset, NoiseConversionToml, PhongToml, TextureKind, TextureModeToml,
};
use crate::scene::formats::toml::format::{BumpHeightsToml, TextureToml, Vec3};
use crate::scene::formats::toml::source_map::FieldPath;
use crate::scene::formats::toml::validate::Ctx;
use glam::DAffine3;
use std::path::Path;

/// Fields every material type takes.
const COMMON: [&str; 9] = [
    "type",
    "albedo",
    "emission",
    "texture",
    "specular_texture",
    "normal_map",
    "bump_map",
    "phong",
    "brdf",
];

/// Complex refractive index (eta, k) of the `preset` metals, per linear sRGB channel.
///
/// Source: the Tungsten renderer's `ComplexIorData.hpp`, which integrates the measured
/// spectral data shipped with pbrt-v3 and Mitsuba (`Au`, `Ag`, `Cu`, `Al` `.eta`/`.k`
/// spectra) against the sRGB colour matching functions.
pub(crate) fn metal_preset(preset: MetalPreset) -> ([f32; 3], [f32; 3]) {
    match preset {
        MetalPreset::Gold => {
            ([0.143_118_96, 0.374_957_04, 1.442_478_6], [3.983_160_4, 2.385_720_7, 1.603_215_3])
        }
        MetalPreset::Silver => {
            ([0.155_264_65, 0.116_723_3, 0.138_380_7], [4.828_343_3, 3.122_245_9, 2.146_950_4])
        }
        MetalPreset::Copper => {
            ([0.200_437_7, 0.924_033_4, 1.102_212], [3.912_948_6, 2.452_847_7, 2.142_188])
        }
        MetalPreset::Aluminium => {
            ([1.657_46, 0.880_368_96, 0.521_228_7], [9.223_869, 6.269_523_4, 4.837_001_3])
        }
    }
}

/// A copy of `material` whose texture (if any) maps the space of the object it is attached
/// to through `texture_from_object`: for a material given per instance, whose pattern
/// should follow the instance rather than the mesh's own vertex space.
pub fn with_texture_space(material: &MaterialDesc, texture_from_object: DAffine3) -> MaterialDesc {
    let mut material = material.clone();
    let textures =
        [&mut material.texture, &mut material.specular_texture, &mut material.normal_map];
    for texture in textures.into_iter().flatten() {
        texture.texture_from_object = texture_from_object;
    }
    material
}

/// Validates and converts one `[materials.NAME]` table.
pub(crate) fn material(
    name: &str,
    m: &MaterialToml,
    ctx: &Ctx,
    base_dir: &Path,
) -> Result<MaterialDesc, SceneError> {
    let path = FieldPath::root("materials").key(name);
    let kind = m.kind.unwrap_or_default();
    let (kind_name, own): (&str, &[&str]) = match kind {
        MaterialKind::Diffuse => ("diffuse", &[]),
        MaterialKind::Mirror => ("mirror", &["reflectance", "roughness"]),
        MaterialKind::Conductor => {
            ("conductor", &["eta", "k", "preset", "reflectance", "roughness"])
        }
        MaterialKind::Dielectric => ("dielectric", &["ior", "absorption", "roughness"]),
    };
    let item = format!("{path} ({kind_name})");
    let allowed: Vec<&str> = COMMON.iter().chain(own).copied().collect();
    let present = [
        ("reflectance", m.reflectance.is_some()),
        ("roughness", m.roughness.is_some()),
        ("eta", m.eta.is_some()),
        ("k", m.k.is_some()),
        ("preset", m.preset.is_some()),
        ("ior", m.ior.is_some()),
        ("absorption", m.absorption.is_some()),
    ];
    ctx.check_fields(&path, &item, &present, &allowed)?;

    let default_albedo = if kind == MaterialKind::Diffuse { 0.8 } else { 0.0 };
    let albedo = ctx.color(&path.key("albedo"), m.albedo.unwrap_or([default_albedo; 3]), true)?;
    let emission = ctx.color(&path.key("emission"), m.emission.unwrap_or([0.0; 3]), false)?;
    let roughness = match m.roughness {
        Some(r) => {
            let field = path.key("roughness");
            ctx.non_negative(&field, r)?;
            ctx.f32(&field, r)?
        }
        None => 0.0,
    };
    let reflectance =
        |ctx: &Ctx| ctx.color(&path.key("reflectance"), m.reflectance.unwrap_or([1.0; 3]), true);
    let specular = match kind {
        MaterialKind::Diffuse => Specular::None,
        MaterialKind::Mirror => Specular::Mirror { reflectance: reflectance(ctx)? },
        MaterialKind::Conductor => {
            let (eta, k) = conductor_index(&path, &item, m, ctx)?;
            Specular::Conductor { eta, k, reflectance: reflectance(ctx)? }
        }
        MaterialKind::Dielectric => {
            // `roughness` is kept (GGX α) for renderers that support rough glass; the path
            // tracer treats dielectrics as smooth.
            let field = path.key("ior");
            let ior = ctx.positive(&field, m.ior.unwrap_or(1.5))?;
            let ior = ctx.f32(&field, ior)?;
            let absorption =
                ctx.color(&path.key("absorption"), m.absorption.unwrap_or([0.0; 3]), false)?;
            Specular::Dielectric { ior, absorption }
        }
    };
    let texture = m
        .texture
        .as_ref()
        .map(|t| texture_desc(&path.key("texture"), t, Use::Diffuse, ctx, base_dir))
        .transpose()?;
    let specular_texture = m
        .specular_texture
        .as_ref()
        .map(|t| texture_desc(&path.key("specular_texture"), t, Use::Specular, ctx, base_dir))
        .transpose()?;
    let normal_map = m
        .normal_map
        .as_ref()
        .map(|t| texture_desc(&path.key("normal_map"), t, Use::Normal, ctx, base_dir))
        .transpose()?;
    let bump_map = match &m.bump_map {
        None => None,
        Some(t) => {
            let field = path.key("bump_map");
            let texture = texture_desc(&field, t, Use::Bump, ctx, base_dir)?;
            let factor = ctx.f32(&field.key("factor"), t.factor.unwrap_or(1.0))?;
            let scale = match t.heights {
                None | Some(BumpHeightsToml::Scene) => crate::scene::desc::BumpScale::Scene,
                Some(BumpHeightsToml::CourseTexels) => crate::scene::desc::BumpScale::CourseTexels,
            };
            Some(crate::scene::desc::BumpMapDesc { texture, factor, scale })
        }
    };
    let mut phong = m.phong.as_ref().map(|p| phong(&path.key("phong"), p, ctx)).transpose()?;
    if let Some(b) = &m.brdf {
        // A BRDF without a `phong` table reflects only its diffuse part (no specular).
        let p = phong.get_or_insert(PhongDesc {
            ambient: glam::Vec3::ZERO,
            specular: glam::Vec3::ZERO,
            exponent: 1.0,
            brdf: Default::default(),
        });
        (p.brdf, p.exponent) = brdf(&path.key("brdf"), b, p.exponent, ctx)?;
    }
    Ok(MaterialDesc {
        name: name.to_owned(),
        albedo,
        emission,
        specular,
        roughness,
        texture,
        specular_texture,
        normal_map,
        bump_map,
        phong,
    })
}

/// `preset`, or `eta` (each > 0) and `k` (each >= 0).
fn conductor_index(
    path: &FieldPath,
    item: &str,
    m: &MaterialToml,
    ctx: &Ctx,
) -> Result<(glam::Vec3, glam::Vec3), SceneError> {
    if let Some(preset) = m.preset {
        if m.eta.is_some() {
            return Err(ctx.conflict(path, item, "preset", "eta"));
        }
        if m.k.is_some() {
            return Err(ctx.conflict(path, item, "preset", "k"));
        }
        let (eta, k) = metal_preset(preset);
        return Ok((glam::Vec3::from_array(eta), glam::Vec3::from_array(k)));
    }
    let eta = ctx.required(path, item, "eta", m.eta)?;
    let k = ctx.required(path, item, "k", m.k)?;
    for (i, &c) in eta.iter().enumerate() {
        ctx.positive(&path.key("eta").index(i), c)?;
    }
    let eta = ctx.color(&path.key("eta"), eta, false)?;
    let k = ctx.color(&path.key("k"), k, false)?;
    Ok((eta, k))
}

/// What a texture table colours.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Use {
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
}

/// `[render] background_texture`: an image or a 2-D checkerboard over the image plane.
pub(crate) fn background_texture(
    t: &TextureToml,
    ctx: &Ctx,
    base_dir: &Path,
) -> Result<TextureDesc, SceneError> {
    let path = FieldPath::root("render").key("background_texture");
    if !matches!(t.kind, TextureKind::Image | TextureKind::Checker2d) {
        let requirement = "a pattern with texture coordinates (image or checker2d)";
        return Err(ctx.out_of_range(&path.key("type"), kind_name_of(t), requirement));
    }
    texture_desc(&path, t, Use::Background, ctx, base_dir)
}

/// The `type` of a texture table, as written.
fn kind_name_of(t: &TextureToml) -> &'static str {
    match t.kind {
        TextureKind::Checker2d => "checker2d",
        TextureKind::Checker3d => "checker3d",
        TextureKind::Checker => "checker",
        TextureKind::Perlin => "perlin",
        TextureKind::Image => "image",
    }
}

/// One `texture`, `specular_texture` or `normal_map` table.
fn texture_desc(
    path: &FieldPath,
    t: &TextureToml,
    usage: Use,
    ctx: &Ctx,
    base_dir: &Path,
) -> Result<TextureDesc, SceneError> {
    let (kind_name, own): (&str, &[&str]) = match t.kind {
        TextureKind::Checker2d => ("checker2d", &["scale", "even", "odd"]),
        TextureKind::Checker3d => ("checker3d", &["scale", "even", "odd"]),
        TextureKind::Checker => ("checker", &["scale", "offset", "black", "white"]),
        TextureKind::Perlin => ("perlin", &["scale", "conversion"]),
        TextureKind::Image => ("image", &["file", "interpolation", "encoding", "normalizer"]),
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
        ("interpolation", t.interpolation.is_some()),
        ("encoding", t.encoding.is_some()),
        ("normalizer", t.normalizer.is_some()),
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
        ctx.color(&path.key(name), value.unwrap_or([default; 3]), true)
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
        TextureKind::Image => {
            let file = ctx.required(path, &item, "file", t.file.as_deref())?;
            let default = if matches!(usage, Use::Normal | Use::Bump) {
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
            Pattern::Image {
                image: crate::scene::texture_image::load_radiance(&at, srgb)?,
                interpolation: match t.interpolation.unwrap_or(InterpolationToml::Bilinear) {
                    InterpolationToml::Nearest => Interpolation::Nearest,
                    InterpolationToml::Bilinear => Interpolation::Bilinear,
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

/// The model and exponent of a `brdf` table (`exponent` defaults to the `phong` one).
fn brdf(
    path: &FieldPath,
    b: &BrdfToml,
    exponent: f32,
    ctx: &Ctx,
) -> Result<(CourseBrdf, f32), SceneError> {
    let modified =
        matches!(b.model, BrdfModelToml::ModifiedBlinnPhong | BrdfModelToml::ModifiedPhong);
    let torrance = b.model == BrdfModelToml::TorranceSparrow;
    for (field, given, allowed, for_what) in [
        ("normalized", b.normalized.is_some(), modified, "the modified Phong models"),
        ("kd_fresnel", b.kd_fresnel.is_some(), torrance, "torrance_sparrow"),
        ("eta", b.eta.is_some(), torrance, "torrance_sparrow"),
        ("k", b.k.is_some(), torrance, "torrance_sparrow"),
    ] {
        let requirement = format!("only for {for_what}");
        ctx.require(!given || allowed, &path.key(field), "given", &requirement)?;
    }
    let exponent = match b.exponent {
        Some(e) => {
            let field = path.key("exponent");
            let e = ctx.positive(&field, e)?;
            ctx.f32(&field, e)?
        }
        None => exponent,
    };
    let normalized = b.normalized.unwrap_or(false);
    let model = match b.model {
        BrdfModelToml::OriginalBlinnPhong => CourseBrdf::OriginalBlinnPhong,
        BrdfModelToml::OriginalPhong => CourseBrdf::OriginalPhong,
        BrdfModelToml::ModifiedBlinnPhong => CourseBrdf::ModifiedBlinnPhong { normalized },
        BrdfModelToml::ModifiedPhong => CourseBrdf::ModifiedPhong { normalized },
        BrdfModelToml::TorranceSparrow => {
            let eta = ctx.required(path, &path.to_string(), "eta", b.eta)?;
            let eta = ctx.positive(&path.key("eta"), eta)?;
            let k = ctx.non_negative(&path.key("k"), b.k.unwrap_or(0.0))?;
            CourseBrdf::TorranceSparrow {
                kd_fresnel: b.kd_fresnel.unwrap_or(false),
                eta: glam::Vec3::splat(ctx.f32(&path.key("eta"), eta)?),
                k: glam::Vec3::splat(ctx.f32(&path.key("k"), k)?),
            }
        }
    };
    Ok((model, exponent))
}

fn phong(path: &FieldPath, p: &PhongToml, ctx: &Ctx) -> Result<PhongDesc, SceneError> {
    let zero: Vec3 = [0.0; 3];
    let ambient = ctx.color(&path.key("ambient"), p.ambient.unwrap_or(zero), false)?;
    let specular = ctx.color(&path.key("specular"), p.specular.unwrap_or(zero), false)?;
    let field = path.key("exponent");
    let exponent = ctx.positive(&field, p.exponent.unwrap_or(1.0))?;
    let exponent = ctx.f32(&field, exponent)?;
    Ok(PhongDesc { ambient, specular, exponent, brdf: Default::default() })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::desc::Pattern;

    #[test]
    fn presets_are_metals() {
        for preset in
            [MetalPreset::Gold, MetalPreset::Silver, MetalPreset::Copper, MetalPreset::Aluminium]
        {
            let (eta, k) = metal_preset(preset);
            assert!(eta.iter().all(|&e| e > 0.0) && k.iter().all(|&k| k > 1.0), "{preset:?}");
        }
        // Gold reflects red more than blue: its k falls from red to blue.
        let (_, k) = metal_preset(MetalPreset::Gold);
        assert!(k[0] > k[1] && k[1] > k[2]);
    }

    #[test]
    fn texture_space_is_replaced_only_when_there_is_a_texture() {
        let plain = MaterialDesc::default();
        let moved = DAffine3::from_translation(glam::DVec3::X);
        assert_eq!(with_texture_space(&plain, moved), plain);
        let textured = MaterialDesc {
            texture: Some(TextureDesc {
                pattern: Pattern::Checker3d {
                    scale: 2.0,
                    even: glam::Vec3::ONE,
                    odd: glam::Vec3::ZERO,
                },
                mode: TextureMode::Replace,
                texture_from_object: DAffine3::IDENTITY,
            }),
            ..MaterialDesc::default()
        };
        let attached = with_texture_space(&textured, moved);
        assert_eq!(attached.texture.unwrap().texture_from_object, moved);
    }
}
