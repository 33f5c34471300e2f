//! A material table's specular lobe, chosen by its `type`: a mirror, a conductor (a named
//! metal or its complex index), glass, a thin sheet, a plastic coating, or none.

use crate::scene::desc::Specular;
use crate::scene::error::SceneError;
use crate::scene::formats::toml::format::{MaterialKind, MaterialToml, MetalPreset};
use crate::scene::formats::toml::source_map::FieldPath;
use crate::scene::formats::toml::validate::Ctx;

/// The specular lobe of the material `m` of type `kind` at `path` (`item` in messages).
pub(super) fn specular(
    kind: MaterialKind,
    path: &FieldPath,
    item: &str,
    m: &MaterialToml,
    ctx: &Ctx,
) -> Result<Specular, SceneError> {
    let reflectance =
        |ctx: &Ctx| ctx.color(&path.key("reflectance"), m.reflectance.unwrap_or([1.0; 3]), true);
    // `ior`, > 0, or the type's `default`.
    let ior = |default: f64| -> Result<f32, SceneError> {
        let field = path.key("ior");
        let ior = ctx.positive(&field, m.ior.unwrap_or(default))?;
        ctx.f32(&field, ior)
    };
    let transmittance = |ctx: &Ctx| {
        ctx.color(&path.key("transmittance"), m.transmittance.unwrap_or([1.0; 3]), true)
    };
    Ok(match kind {
        MaterialKind::Diffuse
        | MaterialKind::Blend
        | MaterialKind::Principled
        | MaterialKind::PrincipledThin => Specular::None,
        MaterialKind::Mirror => Specular::Mirror { reflectance: reflectance(ctx)? },
        MaterialKind::Conductor => {
            let (eta, k) = conductor_index(path, item, m, ctx)?;
            Specular::Conductor { eta, k, reflectance: reflectance(ctx)? }
        }
        MaterialKind::Dielectric => {
            let absorption =
                ctx.color(&path.key("absorption"), m.absorption.unwrap_or([0.0; 3]), false)?;
            Specular::Dielectric {
                ior: ior(1.5)?,
                absorption,
                reflectance: reflectance(ctx)?,
                transmittance: transmittance(ctx)?,
            }
        }
        MaterialKind::ThinDielectric => Specular::ThinDielectric {
            ior: ior(1.5)?,
            reflectance: reflectance(ctx)?,
            transmittance: transmittance(ctx)?,
        },
        // Polypropylene, Mitsuba's default coating.
        MaterialKind::Plastic => {
            Specular::Plastic { ior: ior(1.49)?, nonlinear: m.nonlinear.unwrap_or(false) }
        }
    })
}

/// Complex refractive index (eta, k) of the `preset` metals, per linear sRGB channel.
///
/// Source: the Tungsten renderer's `ComplexIorData.hpp`, which integrates the measured
/// spectral data shipped with pbrt-v3 and Mitsuba (`Au`, `Ag`, `Cu`, `Al` `.eta`/`.k`
/// spectra) against the sRGB colour matching functions.
fn metal_preset(preset: MetalPreset) -> ([f32; 3], [f32; 3]) {
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
