//! `<Transformations>`: the named Scaling, Rotation ("angle x y z", degrees, right-handed
//! about the axis), Translation and Composite (a 4×4 matrix, row by row, last row 0 0 0 1)
//! entries, and the reference lists ("s1 r2 t1 c1") objects use, applied in the listed order (the result is t1 · r2 · s1), composed in f64.

use super::xml::{Xml, tokens};
use crate::scene::error::SceneError;
use glam::{DAffine3, DVec3};
use roxmltree::Node;
use std::collections::HashMap;

/// Every named transformation, keyed by its reference ("s1", "r2", "t1").
#[derive(Default)]
pub(super) struct Transforms {
    named: HashMap<String, DAffine3>,
}

pub(super) fn transforms<'a, 'i: 'a>(
    x: &Xml,
    lists: impl Iterator<Item = Node<'a, 'i>>,
) -> Result<Transforms, SceneError> {
    let mut out = Transforms::default();
    for list in lists {
        x.check_children(list, &["Scaling", "Rotation", "Translation", "Composite"])?;
        for node in list.children().filter(Node::is_element) {
            let id = node.attribute("id").map(str::trim).unwrap_or("");
            if id.is_empty() {
                return Err(x.error(node, "the transformation has no id attribute"));
            }
            let (prefix, transform) = match node.tag_name().name() {
                "Scaling" => {
                    let s = x.vec3(node)?;
                    if s.x * s.y * s.z == 0.0 {
                        return Err(x.out_of_range(node, s, "non-zero factors"));
                    }
                    ("s", DAffine3::from_scale(s))
                }
                "Rotation" => {
                    let [angle, ax, ay, az] = x.numbers::<4>(node, false)?;
                    let Some(axis) = DVec3::new(ax, ay, az).try_normalize() else {
                        return Err(x.out_of_range(node, "axis 0 0 0", "a non-zero axis"));
                    };
                    ("r", DAffine3::from_axis_angle(axis, angle.to_radians()))
                }
                "Composite" => {
                    let m = x.numbers::<16>(node, false)?;
                    if m[12..] != [0.0, 0.0, 0.0, 1.0] {
                        return Err(x.error(node, "the last row of the matrix must be 0 0 0 1"));
                    }
                    let matrix = glam::DMat4::from_cols_array(&m).transpose();
                    let affine = DAffine3::from_mat4(matrix);
                    let det = affine.matrix3.determinant();
                    if !det.is_finite() || det == 0.0 {
                        return Err(x.error(node, "the matrix is singular"));
                    }
                    ("c", affine)
                }
                _ => ("t", DAffine3::from_translation(x.vec3(node)?)),
            };
            let key = format!("{prefix}{id}");
            if out.named.insert(key.clone(), transform).is_some() {
                return Err(x.error(node, format!("transformation \"{key}\" is defined twice")));
            }
        }
    }
    Ok(out)
}

impl Transforms {
    /// The object's `<Transformations>` reference list composed into `world_from_object`
    /// (identity when `node` is `None`).
    pub fn compose(&self, x: &Xml, node: Option<Node>) -> Result<DAffine3, SceneError> {
        let Some(node) = node else { return Ok(DAffine3::IDENTITY) };
        let mut world_from_object = DAffine3::IDENTITY;
        for (token, pos) in tokens(node) {
            let transform = self.named.get(token).ok_or_else(|| {
                let mut defined: Vec<&str> = self.named.keys().map(String::as_str).collect();
                defined.sort();
                let defined =
                    if defined.is_empty() { "(none)".to_owned() } else { defined.join(" ") };
                x.token_error(
                    node,
                    pos,
                    format!("transformation '{token}' is not defined; defined: {defined}"),
                )
            })?;
            world_from_object = *transform * world_from_object;
        }
        Ok(world_from_object)
    }
}
