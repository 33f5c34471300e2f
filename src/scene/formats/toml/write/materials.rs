//! Materials and their textures as TOML tables.

use super::TomlWriteError;
use super::textures::{texture_table, texture_toml};
use super::values::{c3, f, quoted};
use crate::choice::Choice;
use crate::scene::desc::{
    BlendDesc, CourseBrdf, Distribution, MaterialDesc, Opacity, Shadowing, Specular,
};
use glam::Vec3;
use std::fmt::Write as _;

/// A unique TOML key per material: its name, or with its index appended if taken.
pub(super) fn material_names(materials: &[MaterialDesc]) -> Vec<String> {
    let mut used = std::collections::HashSet::new();
    materials
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let base = if m.name.is_empty() { format!("material_{i}") } else { m.name.clone() };
            let name = if used.contains(&base) { format!("{base} ({i})") } else { base };
            used.insert(name.clone());
            name
        })
        .collect()
}

pub(super) fn write_material(
    m: &MaterialDesc,
    name: &str,
    out: &mut String,
) -> Result<(), TomlWriteError> {
    let unsupported = |problem: String| TomlWriteError::Unsupported {
        item: format!("material '{name}'"),
        problem,
    };
    let at_most_one = |what: &str, c: Vec3| {
        if c.max_element() > 1.0 {
            Err(unsupported(format!("{what} {} is above 1", c3(c))))
        } else {
            Ok(())
        }
    };
    at_most_one("the albedo", m.albedo)?;
    if let Some(blend) = &m.blend {
        return write_blend(m, blend, name, out);
    }
    let _ = writeln!(out, "\n[materials.{}]", quoted(name));
    let kind = match m.specular {
        Specular::None => "diffuse",
        Specular::Mirror { .. } => "mirror",
        Specular::Conductor { .. } => "conductor",
        Specular::Dielectric { .. } => "dielectric",
        Specular::Plastic { .. } => "plastic",
        Specular::ThinDielectric { .. } => "thindielectric",
    };
    let kind = super::principled::kind(m).unwrap_or(kind);
    let _ = writeln!(out, "type = \"{kind}\"\nalbedo = {}", c3(m.albedo));
    super::principled::write(m, out)?;
    write_emission(out, m)?;
    match m.specular {
        Specular::None => {}
        Specular::Mirror { reflectance } => {
            at_most_one("the reflectance", reflectance)?;
            let _ = writeln!(out, "reflectance = {}", c3(reflectance));
        }
        Specular::Conductor { eta, k, reflectance } => {
            at_most_one("the reflectance", reflectance)?;
            let _ = writeln!(
                out,
                "eta = {}\nk = {}\nreflectance = {}",
                c3(eta),
                c3(k),
                c3(reflectance)
            );
        }
        Specular::Dielectric { ior, absorption, reflectance, transmittance } => {
            let _ = writeln!(out, "ior = {:?}\nabsorption = {}", ior, c3(absorption));
            for (name, tint) in [("reflectance", reflectance), ("transmittance", transmittance)] {
                if tint != Vec3::ONE {
                    let _ = writeln!(out, "{name} = {}", c3(tint));
                }
            }
        }
        Specular::Plastic { ior, nonlinear } => {
            let _ = writeln!(out, "ior = {ior:?}\nnonlinear = {nonlinear}");
        }
        Specular::ThinDielectric { ior, reflectance, transmittance } => {
            let (r, t) = (c3(reflectance), c3(transmittance));
            let _ = writeln!(out, "ior = {ior:?}\nreflectance = {r}\ntransmittance = {t}");
        }
    }
    // A diffuse material's roughness means nothing to either integrator.
    if (m.roughness != 0.0 || m.roughness_v.is_some()) && m.specular != Specular::None {
        let _ = match &m.roughness_textures {
            Some(pair) if pair[0] == pair[1] => {
                writeln!(out, "roughness = {}", texture_toml(&pair[0], false)?)
            }
            Some(pair) => writeln!(
                out,
                "roughness = [{}, {}]",
                texture_toml(&pair[0], false)?,
                texture_toml(&pair[1], false)?
            ),
            None => match m.roughness_v {
                Some(v) => writeln!(out, "roughness = [{:?}, {v:?}]", m.roughness),
                None => writeln!(out, "roughness = {:?}", m.roughness),
            },
        };
        if m.distribution != Distribution::Ggx {
            let _ = writeln!(out, "distribution = \"{}\"", m.distribution.name());
        }
        let shadows = matches!(m.specular, Specular::Mirror { .. } | Specular::Conductor { .. });
        if shadows && m.shadowing != Shadowing::HeightCorrelated {
            let _ = writeln!(out, "shadowing = \"{}\"", m.shadowing.name());
        }
    }
    if m.one_sided {
        let _ = writeln!(out, "one_sided = true");
    }
    write_number_or_texture(out, "opacity", m.opacity.as_ref())?;
    if let Some(t) = &m.texture {
        let _ = writeln!(out, "texture = {}", texture_toml(t, true)?);
    }
    if let Some(t) = &m.specular_texture {
        let _ = writeln!(out, "specular_texture = {}", texture_toml(t, false)?);
    }
    if let Some(t) = &m.normal_map {
        let _ = writeln!(out, "normal_map = {}", texture_toml(t, false)?);
    }
    if let Some(b) = &m.bump_map {
        let table = texture_toml(&b.texture, false)?;
        let heights = match b.scale {
            crate::scene::BumpScale::Scene => "",
            crate::scene::BumpScale::CourseTexels => ", heights = \"course_texels\"",
        };
        let table =
            format!("{}, factor = {:?}{heights} }}", table.trim_end_matches(" }"), b.factor);
        let _ = writeln!(out, "bump_map = {table}");
    }
    if m.bump_shadowing {
        let _ = writeln!(out, "bump_shadowing = true");
    }
    if let Some(p) = &m.phong {
        let exponent = if p.exponent > 0.0 {
            format!(", exponent = {:?}", p.exponent)
        } else if p.specular == Vec3::ZERO {
            // Without a highlight the exponent does not matter; the format wants it > 0.
            String::new()
        } else {
            return Err(unsupported(format!("its Phong exponent is {}", p.exponent)));
        };
        let _ = writeln!(
            out,
            "phong = {{ ambient = {}, specular = {}{exponent} }}",
            c3(p.ambient),
            c3(p.specular)
        );
        let brdf = match p.brdf {
            CourseBrdf::OriginalBlinnPhong => None,
            CourseBrdf::OriginalPhong => Some("model = \"original_phong\"".to_owned()),
            CourseBrdf::ModifiedBlinnPhong { normalized } => {
                Some(format!("model = \"modified_blinn_phong\", normalized = {normalized}"))
            }
            CourseBrdf::ModifiedPhong { normalized } => {
                Some(format!("model = \"modified_phong\", normalized = {normalized}"))
            }
            CourseBrdf::TorranceSparrow { kd_fresnel, eta, k } => {
                if eta != Vec3::splat(eta.x) || k != Vec3::splat(k.x) {
                    return Err(unsupported("its Torrance-Sparrow index varies by channel".into()));
                }
                Some(format!(
                    "model = \"torrance_sparrow\", kd_fresnel = {kd_fresnel}, eta = {}, k = {}",
                    f(f64::from(eta.x)),
                    f(f64::from(k.x))
                ))
            }
        };
        if let Some(brdf) = brdf {
            let _ = writeln!(out, "brdf = {{ {brdf} }}");
        }
    }
    Ok(())
}

/// A material's emission, its sides and its texture, where it emits.
fn write_emission(out: &mut String, m: &MaterialDesc) -> Result<(), TomlWriteError> {
    // Written whenever there is a texture: without it, a texture's emission reads back as 1.
    if m.emission != Vec3::ZERO || m.emission_texture.is_some() {
        let _ = writeln!(out, "emission = {}", c3(m.emission));
    }
    if m.two_sided_emission {
        let _ = writeln!(out, "two_sided_emission = true");
    }
    if let Some(t) = &m.emission_texture {
        // A radiance has no upper bound.
        let _ = writeln!(out, "emission_texture = {}", texture_table(t, false, false)?);
    }
    Ok(())
}

/// `key = number` or `key = { texture }`, if there is one.
fn write_number_or_texture(
    out: &mut String,
    key: &str,
    value: Option<&Opacity>,
) -> Result<(), TomlWriteError> {
    match value {
        None => {}
        Some(Opacity::Constant(value)) => {
            let _ = writeln!(out, "{key} = {value:?}");
        }
        Some(Opacity::Texture(t)) => {
            let _ = writeln!(out, "{key} = {}", texture_toml(t, false)?);
        }
    }
    Ok(())
}

/// A blend's table (its weight, what is the surface's own) and its two materials', named
/// after it.
fn write_blend(
    m: &MaterialDesc,
    blend: &BlendDesc,
    name: &str,
    out: &mut String,
) -> Result<(), TomlWriteError> {
    let parts = [format!("{name}/first"), format!("{name}/second")];
    let _ = writeln!(out, "\n[materials.{}]\ntype = \"blend\"", quoted(name));
    write_number_or_texture(out, "weight", Some(&blend.weight))?;
    let _ = writeln!(out, "materials = [{}, {}]", quoted(&parts[0]), quoted(&parts[1]));
    write_emission(out, m)?;
    write_number_or_texture(out, "opacity", m.opacity.as_ref())?;
    if m.normal_map.is_some() || m.bump_map.is_some() {
        let problem = "a blend's mapped normals have no TOML form yet".to_owned();
        return Err(TomlWriteError::Unsupported { item: format!("material '{name}'"), problem });
    }
    for (part, part_name) in blend.materials.iter().zip(&parts) {
        write_material(part, part_name, out)?;
    }
    Ok(())
}
