//! A transform list (`transform = [{ scale = .. }, { rotate = .. }, ..]`) → `world_from_object`.
//! Entries apply in the listed order, so for [A, B, C] the result is C * B * A, composed in
//! f64.

use crate::excerpt::short_number;
use crate::scene::formats::toml::format::{Rotate, TransformOp};
use glam::{DAffine3, DMat3, DVec3};

/// Why a transform list was rejected; `entry` is the index of the offending entry, or
/// `None` when only the composition as a whole fails.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct TransformProblem {
    pub entry: Option<usize>,
    pub message: String,
}

fn problem(entry: usize, message: String) -> TransformProblem {
    TransformProblem { entry: Some(entry), message }
}

/// Composes the list into `world_from_object` (identity for an empty list).
pub(crate) fn world_from_object(ops: &[TransformOp]) -> Result<DAffine3, TransformProblem> {
    let mut world_from_object = DAffine3::IDENTITY;
    for (i, op) in ops.iter().enumerate() {
        world_from_object = entry_transform(op).map_err(|m| problem(i, m))? * world_from_object;
    }
    let det = world_from_object.matrix3.determinant();
    if !world_from_object.is_finite() || !det.is_finite() || det == 0.0 {
        return Err(TransformProblem {
            entry: None,
            message: "the composed transform is singular or overflows".to_owned(),
        });
    }
    if !crate::transform::invertible_in_f32(&world_from_object) {
        return Err(TransformProblem {
            entry: None,
            message: "the composed transform is singular in f32, which render space holds it \
                      in (a scale too small, or too small against the others)"
                .to_owned(),
        });
    }
    Ok(world_from_object)
}

/// The affine transform of one entry, or why it is invalid.
fn entry_transform(op: &TransformOp) -> Result<DAffine3, String> {
    match op {
        TransformOp::Scale(scale) => {
            let factors = scale.factors();
            if factors.contains(&0.0) {
                return Err(format!("scale {} is singular (a factor is 0)", fmt_vec(&factors)));
            }
            Ok(DAffine3::from_scale(DVec3::from_array(factors)))
        }
        TransformOp::Rotate(Rotate { axis, degrees }) => {
            let Some(unit_axis) = DVec3::from_array(*axis).try_normalize() else {
                return Err(format!("rotate axis {} has zero length", fmt_vec(axis)));
            };
            Ok(DAffine3::from_axis_angle(unit_axis, degrees.to_radians()))
        }
        TransformOp::Translate(offset) => {
            Ok(DAffine3::from_translation(DVec3::from_array(*offset)))
        }
        TransformOp::Matrix(rows) => matrix_transform(rows),
    }
}

/// A row-major 4×4 matrix whose last row must be exactly 0 0 0 1.
fn matrix_transform(rows: &[[f64; 4]; 4]) -> Result<DAffine3, String> {
    if rows[3] != [0.0, 0.0, 0.0, 1.0] {
        return Err(format!(
            "matrix last row is {}, but must be [0, 0, 0, 1] (an affine transform)",
            fmt_vec(&rows[3])
        ));
    }
    let column = |c: usize| DVec3::new(rows[0][c], rows[1][c], rows[2][c]);
    let matrix3 = DMat3::from_cols(column(0), column(1), column(2));
    let det = matrix3.determinant();
    // Judged on unit columns, so that a rank-deficient matrix with rounding noise in its
    // entries is caught whatever its scale.
    // (Each scaled by its largest entry first: a column of 1e200 or 1e-200 has a direction
    // even where its squared length overflows or underflows.)
    let unit = |c: DVec3| (c / c.abs().max_element()).try_normalize();
    let unit_columns = [column(0), column(1), column(2)].map(unit);
    let unit_det = match unit_columns {
        [Some(a), Some(b), Some(c)] => DMat3::from_cols(a, b, c).determinant(),
        _ => 0.0,
    };
    if det == 0.0 || unit_det.abs() <= 1e-12 {
        let why = if det == 0.0 {
            "determinant 0".to_owned()
        } else {
            format!("determinant {det:e}, but its columns are nearly parallel")
        };
        return Err(format!("matrix is singular ({why})"));
    }
    Ok(DAffine3 { matrix3, translation: column(3) })
}

/// `[1, 0.5, -2]`.
pub(crate) fn fmt_vec(values: &[f64]) -> String {
    let parts: Vec<String> = values.iter().map(|v| short_number(v.to_string())).collect();
    format!("[{}]", parts.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::formats::toml::format::Scale;

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12 * (1.0 + b.length())
    }

    #[test]
    fn empty_list_is_identity() {
        assert_eq!(world_from_object(&[]).unwrap(), DAffine3::IDENTITY);
    }

    #[test]
    fn entries_apply_in_listed_order() {
        let ops =
            [TransformOp::Scale(Scale::Uniform(2.0)), TransformOp::Translate([10.0, 0.0, 0.0])];
        let t = world_from_object(&ops).unwrap();
        // Scale first, then translate: (1,1,1) → (2,2,2) → (12,2,2).
        assert!(close(t.transform_point3(DVec3::ONE), DVec3::new(12.0, 2.0, 2.0)));
        let reversed = [ops[1].clone(), ops[0].clone()];
        let t = world_from_object(&reversed).unwrap();
        assert!(close(t.transform_point3(DVec3::ONE), DVec3::new(22.0, 2.0, 2.0)));
    }

    #[test]
    fn rotation_is_right_handed_about_normalised_axis() {
        let ops = [TransformOp::Rotate(Rotate { axis: [0.0, 0.0, 5.0], degrees: 90.0 })];
        let t = world_from_object(&ops).unwrap();
        assert!(close(t.transform_point3(DVec3::X), DVec3::Y));
    }

    #[test]
    fn matrix_is_row_major() {
        let rows = [
            [0.0, -1.0, 0.0, 5.0],
            [1.0, 0.0, 0.0, 6.0],
            [0.0, 0.0, 1.0, 7.0],
            [0.0, 0.0, 0.0, 1.0],
        ];
        let t = world_from_object(&[TransformOp::Matrix(rows)]).unwrap();
        assert!(close(t.transform_point3(DVec3::X), DVec3::new(5.0, 7.0, 7.0)));
    }

    #[test]
    fn per_axis_scale() {
        let t = world_from_object(&[TransformOp::Scale(Scale::PerAxis([1.0, 2.0, 3.0]))]).unwrap();
        assert!(close(t.transform_point3(DVec3::ONE), DVec3::new(1.0, 2.0, 3.0)));
    }

    #[test]
    fn singular_entries_name_the_entry() {
        let ops = [
            TransformOp::Translate([1.0, 2.0, 3.0]),
            TransformOp::Scale(Scale::PerAxis([1.0, 0.0, 1.0])),
        ];
        let err = world_from_object(&ops).unwrap_err();
        assert_eq!(err.entry, Some(1));
        assert!(err.message.contains("singular"), "{}", err.message);

        let rows = [
            [1.0, 2.0, 3.0, 0.0],
            [2.0, 4.0, 6.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ];
        let err = world_from_object(&[TransformOp::Matrix(rows)]).unwrap_err();
        assert_eq!(err.entry, Some(0));
        assert!(err.message.contains("determinant"), "{}", err.message);
    }

    #[test]
    fn matrix_last_row_must_be_affine() {
        let mut rows = [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ];
        rows[3] = [0.0, 0.0, 1.0, 1.0];
        let err = world_from_object(&[TransformOp::Matrix(rows)]).unwrap_err();
        assert!(err.message.contains("[0, 0, 1, 1]"), "{}", err.message);
    }

    #[test]
    fn zero_rotation_axis_is_rejected() {
        let ops = [TransformOp::Rotate(Rotate { axis: [0.0; 3], degrees: 10.0 })];
        assert!(world_from_object(&ops).unwrap_err().message.contains("zero length"));
    }

    #[test]
    fn composition_underflow_is_singular() {
        let tiny = TransformOp::Scale(Scale::Uniform(1e-200));
        let err = world_from_object(&[tiny.clone(), tiny]).unwrap_err();
        assert_eq!(err.entry, None);
    }
}
