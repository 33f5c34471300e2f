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
    if axis == DVec3::ZERO {
        return Err(op.error("the rotation axis is zero"));
    }
    Ok(DAffine3::from_mat3(mitsuba_rotation(axis, angle)))
}

/// Mitsuba's rotation matrix about `axis`, `radians` (Dr.Jit's `rotate`, fused multiply-adds
/// as there). Mitsuba does not normalise the axis: one not of unit length scales and shears
/// along with the turn, and embray reproduces that matrix (`axis_warnings` says so).
fn mitsuba_rotation(axis: DVec3, radians: f64) -> DMat3 {
    let (sin, cos) = radians.sin_cos();
    let one_minus_cos = 1.0 - cos;
    let a = axis;
    let (shuf1, shuf2) = (DVec3::new(a.y, a.z, a.x), DVec3::new(a.z, a.x, a.y));
    let fmadd = |x: DVec3, y: f64, z: DVec3| {
        DVec3::new(x.x.mul_add(y, z.x), x.y.mul_add(y, z.y), x.z.mul_add(y, z.z))
    };
    let tmp0 = fmadd(a * a, one_minus_cos, DVec3::splat(cos));
    let tmp1 = fmadd(a * shuf1, one_minus_cos, shuf2 * sin);
    let tmp2 = fmadd(a * shuf2, one_minus_cos, -(shuf1 * sin));
    DMat3::from_cols(
        DVec3::new(tmp0.x, tmp1.x, tmp2.x),
        DVec3::new(tmp2.y, tmp0.y, tmp1.y),
        DVec3::new(tmp1.z, tmp2.z, tmp0.z),
    )
}

/// A warning for each `<rotate>` under `root` whose axis is not of unit length: Mitsuba's
/// matrix (and so embray's) then scales and shears, which is rarely what was meant.
pub(super) fn axis_warnings(root: &Element, warnings: &mut Vec<String>) {
    for child in &root.children {
        if child.tag == "rotate" {
            if let Ok(axis) = vec3(child, Some(0.0)) {
                if axis != DVec3::ZERO && (axis.length() - 1.0).abs() > 1e-6 {
                    warnings.push(format!(
                        "{}: line {}: the rotation axis {axis} is not of unit length: Mitsuba's \
                         matrix (which embray reproduces) then scales and shears as well as \
                         rotating; normalise the axis for a pure rotation",
                        child.file.display(),
                        child.line
                    ));
                }
            }
        } else {
            axis_warnings(child, warnings);
        }
    }
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
