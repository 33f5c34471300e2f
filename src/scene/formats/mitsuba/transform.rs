//! `<transform name="to_world">`: translate, rotate, scale, matrix and lookat, each applied
//! after the ones before it (in f64).

use super::tree::Element;
use super::values::{numbers, vec3};
use crate::scene::error::SceneError;
use glam::{DAffine3, DMat3, DMat4, DVec3};

/// The transform an element describes (identity when it has no operations).
pub(super) fn transform(element: &Element) -> Result<DAffine3, SceneError> {
    let mut world = DAffine3::IDENTITY;
    for op in &element.children {
        let step = match op.tag.as_str() {
            "translate" => DAffine3::from_translation(vec3(op, Some(0.0))?),
            "scale" => scale(op)?,
            "rotate" => rotate(op)?,
            "matrix" => matrix(op)?,
            "lookat" => lookat(op)?,
            other => {
                return Err(op.error(format!(
                    "<{other}> is not a transform operation (translate, rotate, scale, matrix, \
                     lookat)"
                )));
            }
        };
        world = step * world;
    }
    if !(world.matrix3.determinant().abs() > 0.0) || !world.is_finite() {
        return Err(element.error("the transform is singular or not finite"));
    }
    Ok(world)
}

fn scale(op: &Element) -> Result<DAffine3, SceneError> {
    Ok(DAffine3::from_scale(vec3(op, Some(1.0))?))
}

fn rotate(op: &Element) -> Result<DAffine3, SceneError> {
    let axis = vec3(op, Some(0.0))?;
    let angle = match numbers(op, op.required("angle")?)?[..] {
        [degrees] => degrees.to_radians(),
        _ => return Err(op.error("`angle` must be one number (degrees)")),
    };
    let axis = axis.try_normalize().ok_or_else(|| op.error("the rotation axis is zero"))?;
    Ok(DAffine3::from_axis_angle(axis, angle))
}

/// A 4×4 (or 3×3) matrix, row by row.
fn matrix(op: &Element) -> Result<DAffine3, SceneError> {
    let v = numbers(op, op.required("value")?)?;
    match v.len() {
        16 => {
            if v[12..] != [0.0, 0.0, 0.0, 1.0] {
                return Err(op.error("the last row of the matrix must be 0 0 0 1"));
            }
            let rows = DMat4::from_cols_slice(&v).transpose();
            Ok(DAffine3::from_mat4(rows))
        }
        9 => Ok(DAffine3::from_mat3(DMat3::from_cols_slice(&v).transpose())),
        n => Err(op.error(format!("a matrix has 16 (or 9) numbers, not {n}"))),
    }
}

/// Mitsuba's look-at: the camera's +z towards `target`, +y along `up`, +x to its left.
fn lookat(op: &Element) -> Result<DAffine3, SceneError> {
    let point = |name: &str| -> Result<DVec3, SceneError> {
        match numbers(op, op.required(name)?)?[..] {
            [x, y, z] => Ok(DVec3::new(x, y, z)),
            _ => Err(op.error(format!("`{name}` must be three numbers"))),
        }
    };
    let (origin, target) = (point("origin")?, point("target")?);
    let dir = (target - origin).try_normalize().ok_or_else(|| op.error("origin equals target"))?;
    let up = match op.attr("up") {
        Some(_) => point("up")?,
        None => DVec3::ZERO,
    };
    // Without an up vector, Mitsuba takes the first axis of its frame around the view.
    let up = if up == DVec3::ZERO { frame_axis(dir) } else { up };
    let left =
        up.cross(dir).try_normalize().ok_or_else(|| op.error("up is parallel to the view"))?;
    let new_up = dir.cross(left);
    Ok(DAffine3 { matrix3: DMat3::from_cols(left, new_up, dir), translation: origin })
}

/// The first tangent of Duff et al.'s orthonormal basis around the unit vector `n`
/// (Mitsuba's `coordinate_system`).
fn frame_axis(n: DVec3) -> DVec3 {
    let sign = 1f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x)
}
