//! The Whitted integrator shades only the course's model: an object whose material has more
//! (a principled BSDF, a blend, opacity) is refused by name, as its image would otherwise be
//! that of a plain diffuse material.

use super::source_map::FieldPath;
use super::validate::Ctx;
use crate::scene::desc::{MaterialDesc, ObjectDesc, Opacity, WhittedGap};
use crate::scene::error::SceneError;
use std::collections::BTreeMap;

/// Refuses the first of `placed` (the objects `objects[index]` made) whose material the
/// Whitted integrator cannot shade, at the line of the `[materials]` field that asks for
/// it, or of the object for a mesh file's own (MTL) material. `named` maps the
/// `[materials]` table's names to indices into `materials`.
pub(super) fn check_objects(
    ctx: &Ctx,
    index: usize,
    placed: &[ObjectDesc],
    materials: &[MaterialDesc],
    named: &BTreeMap<String, u32>,
) -> Result<(), SceneError> {
    for object in placed {
        let material = &materials[object.material as usize];
        let Some(gap) = material.unshaded_by_whitted() else { continue };
        let cannot = format!(
            "the whitted integrator cannot shade {}; integrator = \"path\" can",
            gap.describe()
        );
        let name = named.iter().find(|&(_, &m)| m == object.material).map(|(name, _)| name);
        let (field, value, requirement) = match name {
            Some(name) => {
                let path = FieldPath::root("materials").key(name);
                match (gap, &material.opacity) {
                    (WhittedGap::Opacity, Some(Opacity::Constant(v))) => {
                        (path.key("opacity"), v.to_string(), format!("1 ({cannot})"))
                    }
                    (WhittedGap::Opacity, _) => {
                        (path.key("opacity"), "a texture".to_owned(), format!("1 ({cannot})"))
                    }
                    (WhittedGap::Blend, _) => {
                        (path.key("type"), "blend".to_owned(), format!("another type ({cannot})"))
                    }
                    (WhittedGap::Principled, _) => {
                        let thin = material.principled.as_ref().is_some_and(|p| p.thin);
                        let kind = if thin { "principledthin" } else { "principled" };
                        (path.key("type"), kind.to_owned(), format!("another type ({cannot})"))
                    }
                }
            }
            None => {
                let value = format!("material '{}'", crate::excerpt::excerpt(&material.name));
                let requirement = format!("a material without it ({cannot})");
                (FieldPath::root("objects").index(index), value, requirement)
            }
        };
        return Err(ctx.out_of_range(&field, value, &requirement));
    }
    Ok(())
}
