//! The `principled` table of a `principled` or `principledthin` material → `PrincipledDesc`,
//! with Mitsuba's names, defaults, ranges and conversions (as its reader has them).

use super::textures::{Use, texture_desc};
use crate::scene::desc::{ParamDesc, PrincipledDesc, solid_eta};
use crate::scene::error::SceneError;
use crate::scene::formats::toml::format::{ParamToml, PrincipledToml};
use crate::scene::formats::toml::source_map::FieldPath;
use crate::scene::formats::toml::validate::Ctx;
use std::path::Path;

/// The fields each model takes.
const BOTH: [&str; 8] = [
    "roughness",
    "anisotropic",
    "spec_tint",
    "sheen",
    "sheen_tint",
    "spec_trans",
    "flatness",
    "eta",
];
const SOLID: [&str; 7] = [
    "metallic",
    "clearcoat",
    "clearcoat_gloss",
    "specular",
    "main_specular_sampling_rate",
    "clearcoat_sampling_rate",
    "diffuse_reflectance_sampling_rate",
];
const THIN: [&str; 5] = [
    "diff_trans",
    "specular_reflectance_sampling_rate",
    "specular_transmittance_sampling_rate",
    "diffuse_transmittance_sampling_rate",
    "diffuse_reflectance_sampling_rate",
];

/// The parameters at `path` (the material's `principled` table; Mitsuba's defaults where
/// there is none).
pub(super) fn principled(
    path: &FieldPath,
    thin: bool,
    table: Option<&PrincipledToml>,
    ctx: &Ctx,
    base_dir: &Path,
) -> Result<PrincipledDesc, SceneError> {
    let path = path.key("principled");
    let empty = PrincipledToml::default();
    let t = table.unwrap_or(&empty);
    let kind = if thin { "principledthin" } else { "principled" };
    let item = format!("{path} ({kind})");
    let present = [
        ("roughness", t.roughness.is_some()),
        ("anisotropic", t.anisotropic.is_some()),
        ("metallic", t.metallic.is_some()),
        ("spec_tint", t.spec_tint.is_some()),
        ("specular", t.specular.is_some()),
        ("eta", t.eta.is_some()),
        ("sheen", t.sheen.is_some()),
        ("sheen_tint", t.sheen_tint.is_some()),
        ("clearcoat", t.clearcoat.is_some()),
        ("clearcoat_gloss", t.clearcoat_gloss.is_some()),
        ("spec_trans", t.spec_trans.is_some()),
        ("flatness", t.flatness.is_some()),
        ("diff_trans", t.diff_trans.is_some()),
        ("main_specular_sampling_rate", t.main_specular_sampling_rate.is_some()),
        ("clearcoat_sampling_rate", t.clearcoat_sampling_rate.is_some()),
        ("diffuse_reflectance_sampling_rate", t.diffuse_reflectance_sampling_rate.is_some()),
        ("specular_reflectance_sampling_rate", t.specular_reflectance_sampling_rate.is_some()),
        ("specular_transmittance_sampling_rate", t.specular_transmittance_sampling_rate.is_some()),
        ("diffuse_transmittance_sampling_rate", t.diffuse_transmittance_sampling_rate.is_some()),
    ];
    let own: &[&str] = if thin { &THIN } else { &SOLID };
    let allowed: Vec<&str> = BOTH.iter().chain(own).copied().collect();
    ctx.check_fields(&path, &item, &present, &allowed)?;

    let param = |name: &str, value: &Option<ParamToml>, default: f32, most: f64| {
        let field = path.key(name);
        match value {
            None => Ok(ParamDesc::Constant(default)),
            Some(ParamToml::Number(v)) => {
                let requirement = format!("in [0, {most}]");
                ctx.require((0.0..=most).contains(v), &field, v, &requirement)?;
                Ok(ParamDesc::Constant(*v as f32))
            }
            Some(ParamToml::Texture(texture)) => {
                Ok(ParamDesc::Texture(texture_desc(&field, texture, Use::Param, ctx, base_dir)?))
            }
        }
    };
    let mut desc = PrincipledDesc::new(thin);
    desc.roughness = param("roughness", &t.roughness, 0.5, 1.0)?;
    desc.anisotropic = param("anisotropic", &t.anisotropic, 0.0, 1.0)?;
    desc.spec_tint = param("spec_tint", &t.spec_tint, 0.0, 1.0)?;
    desc.sheen = param("sheen", &t.sheen, 0.0, 1.0)?;
    desc.sheen_tint = param("sheen_tint", &t.sheen_tint, 0.0, 1.0)?;
    desc.spec_trans = param("spec_trans", &t.spec_trans, 0.0, 1.0)?;
    desc.flatness = param("flatness", &t.flatness, 0.0, 1.0)?;
    desc.metallic = param("metallic", &t.metallic, 0.0, 1.0)?;
    desc.clearcoat = param("clearcoat", &t.clearcoat, 0.0, 1.0)?;
    desc.clearcoat_gloss = param("clearcoat_gloss", &t.clearcoat_gloss, 0.0, 1.0)?;
    desc.diff_trans = param("diff_trans", &t.diff_trans, 0.0, 2.0)?;
    let eta = |ctx: &Ctx, value: f64| -> Result<f32, SceneError> {
        let field = path.key("eta");
        ctx.positive(&field, value)?;
        ctx.f32(&field, value)
    };
    desc.eta = match (&t.eta, thin) {
        (Some(ParamToml::Texture(texture)), true) => {
            ParamDesc::Texture(texture_desc(&path.key("eta"), texture, Use::Param, ctx, base_dir)?)
        }
        (Some(ParamToml::Texture(_)), false) => {
            let requirement = "a number (a texture only in principledthin)";
            return Err(ctx.out_of_range(&path.key("eta"), "a texture", requirement));
        }
        (Some(ParamToml::Number(v)), true) => ParamDesc::Constant(eta(ctx, *v)?),
        (None, true) => ParamDesc::Constant(1.5),
        (number, false) => {
            let given = match number {
                Some(ParamToml::Number(v)) => Some(eta(ctx, *v)?),
                _ => None,
            };
            let specular = match t.specular {
                None => None,
                Some(s) => {
                    let field = path.key("specular");
                    ctx.require((0.0..=1.0).contains(&s), &field, s, "in [0, 1]")?;
                    Some(s as f32)
                }
            };
            let transmits = !desc.spec_trans.is_zero();
            let eta = solid_eta(given, specular, transmits)
                .ok_or_else(|| ctx.conflict(&path, &item, "eta", "specular"))?;
            ParamDesc::Constant(eta)
        }
    };
    let rate = |name: &str, value: Option<f64>| -> Result<f32, SceneError> {
        let field = path.key(name);
        let value = ctx.non_negative(&field, value.unwrap_or(1.0))?;
        ctx.f32(&field, value)
    };
    let rates = &mut desc.sampling_rates;
    if thin {
        rates.specular_reflectance =
            rate("specular_reflectance_sampling_rate", t.specular_reflectance_sampling_rate)?;
        rates.specular_transmittance =
            rate("specular_transmittance_sampling_rate", t.specular_transmittance_sampling_rate)?;
        rates.diffuse_transmittance =
            rate("diffuse_transmittance_sampling_rate", t.diffuse_transmittance_sampling_rate)?;
    } else {
        let main = rate("main_specular_sampling_rate", t.main_specular_sampling_rate)?;
        (rates.specular_reflectance, rates.specular_transmittance) = (main, main);
        rates.clearcoat = rate("clearcoat_sampling_rate", t.clearcoat_sampling_rate)?;
    }
    rates.diffuse_reflectance =
        rate("diffuse_reflectance_sampling_rate", t.diffuse_reflectance_sampling_rate)?;
    if rates.samples_nothing(thin) {
        // Named at the last rate the model reads, which every model has.
        let field = path.key("diffuse_reflectance_sampling_rate");
        let others = if thin { &THIN[1..4] } else { &SOLID[4..6] };
        let requirement = format!(
            "> 0 where {} are 0 too: at least one lobe must be sampled",
            others.join(" and ")
        );
        return Err(ctx.out_of_range(&field, 0, &requirement));
    }
    Ok(desc)
}
