//! The course's reflectance models (`brdf`) and Phong terms (`phong`).

use crate::scene::desc::{CourseBrdf, PhongDesc};
use crate::scene::error::SceneError;
use crate::scene::formats::toml::format::{BrdfModelToml, BrdfToml, PhongToml, Vec3};
use crate::scene::formats::toml::source_map::FieldPath;
use crate::scene::formats::toml::validate::Ctx;

/// The model and exponent of a `brdf` table (`exponent` defaults to the `phong` one).
pub(super) fn brdf(
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

pub(super) fn phong(path: &FieldPath, p: &PhongToml, ctx: &Ctx) -> Result<PhongDesc, SceneError> {
    let zero: Vec3 = [0.0; 3];
    let ambient = ctx.color(&path.key("ambient"), p.ambient.unwrap_or(zero), false)?;
    let specular = ctx.color(&path.key("specular"), p.specular.unwrap_or(zero), false)?;
    let field = path.key("exponent");
    let exponent = ctx.positive(&field, p.exponent.unwrap_or(1.0))?;
    let exponent = ctx.f32(&field, exponent)?;
    Ok(PhongDesc { ambient, specular, exponent, brdf: Default::default() })
}
