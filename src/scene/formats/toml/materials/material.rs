//! `[materials.NAME]` → `MaterialDesc`: a Lambertian part (`albedo` or a `texture`), one specular lobe chosen by `type`, emission, and the course's Phong terms. Each type takes only its own fields.

use super::course::{brdf, phong};
use super::textures::{Use, number_or_texture, texture_desc};
use crate::scene::desc::{Distribution, MaterialDesc, PhongDesc, Shadowing};
use crate::scene::error::SceneError;
use crate::scene::formats::toml::format::{
    BumpHeightsToml, DistributionToml, MaterialKind, MaterialToml, RoughnessToml, TextureToml,
};
use crate::scene::formats::toml::source_map::FieldPath;
use crate::scene::formats::toml::validate::Ctx;
use glam::DAffine3;
use std::path::Path;

/// Fields every material type takes.
pub(super) const COMMON: [&str; 14] = [
    "type",
    "albedo",
    "emission",
    "two_sided_emission",
    "emission_texture",
    "texture",
    "specular_texture",
    "normal_map",
    "bump_map",
    "phong",
    "brdf",
    "opacity",
    "one_sided",
    "bump_shadowing",
];

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
    if let Some(blend) = &mut material.blend {
        if let crate::scene::desc::Opacity::Texture(t) = &mut blend.weight {
            t.texture_from_object = texture_from_object;
        }
        for part in &mut blend.materials {
            *part = with_texture_space(part, texture_from_object);
        }
    }
    for texture in material.principled.iter_mut().flat_map(|p| p.textures_mut()) {
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
        MaterialKind::Mirror => {
            ("mirror", &["reflectance", "roughness", "distribution", "shadowing"])
        }
        MaterialKind::Conductor => (
            "conductor",
            &["eta", "k", "preset", "reflectance", "roughness", "distribution", "shadowing"],
        ),
        MaterialKind::Dielectric => (
            "dielectric",
            &["ior", "absorption", "reflectance", "transmittance", "roughness", "distribution"],
        ),
        MaterialKind::Plastic => ("plastic", &["ior", "nonlinear", "roughness", "distribution"]),
        MaterialKind::ThinDielectric => {
            ("thindielectric", &["ior", "reflectance", "transmittance"])
        }
        MaterialKind::Blend => ("blend", &["weight", "materials"]),
        MaterialKind::Principled => ("principled", &["principled"]),
        MaterialKind::PrincipledThin => ("principledthin", &["principled"]),
    };
    let item = format!("{path} ({kind_name})");
    let principled = matches!(kind, MaterialKind::Principled | MaterialKind::PrincipledThin);
    // The course's terms would be ignored by a principled material's path tracing.
    let course = ["specular_texture", "phong", "brdf"];
    let common: &[&str] = match kind {
        // Its materials scatter: only what is the surface's own is its.
        MaterialKind::Blend => &super::blend::BLEND_COMMON,
        _ => &COMMON,
    };
    let allowed: Vec<&str> = common
        .iter()
        .filter(|field| !principled || !course.contains(field))
        .chain(own)
        .copied()
        .collect();
    let present = [
        ("reflectance", m.reflectance.is_some()),
        ("transmittance", m.transmittance.is_some()),
        ("roughness", m.roughness.is_some()),
        ("eta", m.eta.is_some()),
        ("k", m.k.is_some()),
        ("preset", m.preset.is_some()),
        ("ior", m.ior.is_some()),
        ("absorption", m.absorption.is_some()),
        ("distribution", m.distribution.is_some()),
        ("shadowing", m.shadowing.is_some()),
        ("nonlinear", m.nonlinear.is_some()),
        ("weight", m.weight.is_some()),
        ("materials", m.materials.is_some()),
        ("principled", m.principled.is_some()),
        ("specular_texture", m.specular_texture.is_some()),
        ("phong", m.phong.is_some()),
        ("brdf", m.brdf.is_some()),
    ];
    ctx.check_fields(&path, &item, &present, &allowed)?;

    let default_albedo = match kind {
        MaterialKind::Diffuse => 0.8,
        MaterialKind::Blend => 0.0,
        // Mitsuba's default base.
        MaterialKind::Plastic | MaterialKind::Principled | MaterialKind::PrincipledThin => 0.5,
        _ => 0.0,
    };
    let albedo = ctx.color(&path.key("albedo"), m.albedo.unwrap_or([default_albedo; 3]), true)?;
    let emission_texture = m
        .emission_texture
        .as_ref()
        .map(|t| texture_desc(&path.key("emission_texture"), t, Use::Emission, ctx, base_dir))
        .transpose()?;
    // A texture alone is the radiance: what it multiplies is 1 unless given.
    let unset = if emission_texture.is_some() { 1.0 } else { 0.0 };
    let emission = ctx.color(&path.key("emission"), m.emission.unwrap_or([unset; 3]), false)?;
    let field = path.key("roughness");
    let alpha = |r: f64| -> Result<f32, SceneError> {
        ctx.non_negative(&field, r)?;
        ctx.f32(&field, r)
    };
    let one_number = |what: &str| {
        let requirement = "one number: a plastic's coating is isotropic and untextured";
        ctx.require(kind != MaterialKind::Plastic, &field, what, requirement)
    };
    let texture =
        |field: &FieldPath, t: &TextureToml| texture_desc(field, t, Use::Specular, ctx, base_dir);
    // A textured α has a number too, for what is decided per material (rough or smooth):
    // Mitsuba's default α.
    let (roughness, roughness_v, roughness_textures) = match &m.roughness {
        Some(RoughnessToml::Isotropic(r)) => (alpha(*r)?, None, None),
        Some(RoughnessToml::Anisotropic([u, v])) => {
            one_number("a pair")?;
            let (u, v) = (alpha(*u)?, alpha(*v)?);
            (u, (v != u).then_some(v), None)
        }
        Some(RoughnessToml::Texture(t)) => {
            one_number("a texture")?;
            let t = texture(&field, t)?;
            (0.1, None, Some(Box::new([t.clone(), t])))
        }
        Some(RoughnessToml::Textures(pair)) => {
            one_number("textures")?;
            let [u, v] = &**pair;
            (
                0.1,
                None,
                Some(Box::new([texture(&field.index(0), u)?, texture(&field.index(1), v)?])),
            )
        }
        None => (0.0, None, None),
    };
    let specular = super::specular::specular(kind, &path, &item, m, ctx)?;
    let distribution = match m.distribution {
        None | Some(DistributionToml::Ggx) => Distribution::Ggx,
        Some(DistributionToml::Beckmann) => Distribution::Beckmann,
    };
    let shadowing = match &m.shadowing {
        None => Shadowing::HeightCorrelated,
        Some(name) => {
            use crate::choice::Choice;
            let field = path.key("shadowing");
            Shadowing::from_name(name).map_err(|e| {
                let expected = e.expected.join(" or ");
                ctx.out_of_range(&field, format!("'{}'", e.given), &format!("must be {expected}"))
            })?
        }
    };
    let opacity = m
        .opacity
        .as_ref()
        .map(|o| number_or_texture(&path.key("opacity"), o, ctx, base_dir))
        .transpose()?;
    let blend = match kind {
        MaterialKind::Blend => {
            Some(super::blend::unresolved_blend(&path, &item, m, ctx, base_dir)?)
        }
        _ => None,
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
        two_sided_emission: m.two_sided_emission.unwrap_or(false),
        emission_texture,
        specular,
        roughness,
        roughness_v,
        roughness_textures,
        distribution,
        shadowing,
        opacity,
        one_sided: m.one_sided.unwrap_or(false),
        texture,
        specular_texture,
        normal_map,
        bump_map,
        bump_shadowing: m.bump_shadowing.unwrap_or(false),
        phong,
        blend,
        principled: if principled {
            let thin = kind == MaterialKind::PrincipledThin;
            let table = m.principled.as_deref();
            Some(Box::new(super::principled::principled(&path, thin, table, ctx, base_dir)?))
        } else {
            None
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::desc::{Pattern, TextureDesc, TextureMode};

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
