//! `type = "blend"`: `weight` of the second of two named `materials` and the rest of the
//! first. Read with the other materials, then given its two materials' descriptions once
//! every material is read (`resolve_blends`), so that it may name any of them.

use super::textures::number_or_texture;
use crate::limits::MAX_BLEND_MATERIALS;
use crate::scene::desc::{BlendDesc, MaterialDesc, Opacity};
use crate::scene::error::SceneError;
use crate::scene::formats::toml::builder::Builder;
use crate::scene::formats::toml::format::{MaterialKind, MaterialToml};
use crate::scene::formats::toml::source_map::FieldPath;
use crate::scene::formats::toml::validate::Ctx;
use std::collections::BTreeMap;
use std::path::Path;

/// The fields of every material a blend takes: what belongs to the surface, not to how it
/// scatters.
pub(super) const BLEND_COMMON: [&str; 8] = [
    "type",
    "emission",
    "two_sided_emission",
    "emission_texture",
    "opacity",
    "normal_map",
    "bump_map",
    "bump_shadowing",
];

/// The blend of `m` with its weight, its materials still to be filled in.
pub(super) fn unresolved_blend(
    path: &FieldPath,
    item: &str,
    m: &MaterialToml,
    ctx: &Ctx,
    base_dir: &Path,
) -> Result<Box<BlendDesc>, SceneError> {
    let weight = ctx.required(path, item, "weight", m.weight.as_ref())?;
    let weight = number_or_texture(&path.key("weight"), weight, ctx, base_dir)?;
    let names = ctx.required(path, item, "materials", m.materials.as_ref())?;
    let count = names.len();
    ctx.require(count == 2, &path.key("materials"), format!("{count} names"), "two names")?;
    let placeholder = MaterialDesc::default();
    Ok(Box::new(BlendDesc { weight, materials: [placeholder.clone(), placeholder] }))
}

/// Fills every blend's two materials in from the materials they name (blends of blends
/// included; a blend that contains itself is an error).
pub(in crate::scene::formats::toml) fn resolve_blends(
    materials: &BTreeMap<String, MaterialToml>,
    builder: &mut Builder,
) -> Result<(), SceneError> {
    for name in materials.keys() {
        resolve(name, materials, builder, &mut Vec::new())?;
    }
    Ok(())
}

fn resolve(
    name: &str,
    materials: &BTreeMap<String, MaterialToml>,
    builder: &mut Builder,
    enclosing: &mut Vec<String>,
) -> Result<MaterialDesc, SceneError> {
    let index = builder.named[name] as usize;
    let toml = &materials[name];
    let Some(parts) = toml.materials.as_ref().filter(|_| toml.kind == Some(MaterialKind::Blend))
    else {
        return Ok(builder.materials[index].clone());
    };
    let path = FieldPath::root("materials").key(name).key("materials");
    if enclosing.iter().any(|e| e == name) {
        let chain = format!("{} → {name}", enclosing.join(" → "));
        return Err(builder.ctx.out_of_range(&path, chain, "a blend that does not contain itself"));
    }
    // A blend this deep holds more than the limit's materials (two a level): refused before
    // the recursion goes deeper.
    if enclosing.len() >= MAX_BLEND_MATERIALS {
        return Err(too_many_materials(
            builder,
            &path,
            format!("blends nested {} deep", enclosing.len()),
        ));
    }
    enclosing.push(name.to_owned());
    let mut resolved = Vec::with_capacity(2);
    for (i, part) in parts.iter().enumerate() {
        builder.lookup_material(&path.index(i), part)?;
        resolved.push(resolve(part, materials, builder, enclosing)?);
    }
    enclosing.pop();
    let [first, second] = <[MaterialDesc; 2]>::try_from(resolved).expect("two names, checked");
    let material = &mut builder.materials[index];
    let weight = match &material.blend {
        Some(blend) => blend.weight.clone(),
        None => Opacity::Constant(0.0),
    };
    material.blend = Some(Box::new(BlendDesc { weight, materials: [first, second] }));
    // Checked at every blend, so that its parts are in bounds and a chain that names one
    // material twice a link stops doubling at the limit.
    let count = material.blend_materials();
    if count > MAX_BLEND_MATERIALS {
        return Err(too_many_materials(builder, &path, format!("{count} materials")));
    }
    Ok(material.clone())
}

/// The error for a blend with more than `MAX_BLEND_MATERIALS` materials in it.
fn too_many_materials(builder: &Builder, path: &FieldPath, found: String) -> SceneError {
    let requirement = format!(
        "at most {MAX_BLEND_MATERIALS} materials in a blend, counting each as often as it is named"
    );
    builder.ctx.out_of_range(path, found, &requirement)
}
