//! f64 affine transforms (glam `DAffine3`, pbrt-style `x_from_y` naming) and the few
//! operations on them that the renderer needs beyond glam.

use glam::{DAffine3, DMat3, DQuat, DVec3};

/// Matrix that maps object-space normals: the inverse transpose of the linear part.
/// `None` when the transform is singular.
pub fn normal_matrix(transform: &DAffine3) -> Option<DMat3> {
    let linear = transform.matrix3;
    let det = linear.determinant();
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    Some(linear.inverse().transpose())
}

/// Whether the linear part of `transform` is invertible once in f32, as render space and
/// both backends hold it: a scale of 1e-200 along one axis is invertible in f64 but rounds to
/// 0 in f32, and its f32 inverse would send NaN rays (Embree inverts without checking).
pub fn invertible_in_f32(transform: &DAffine3) -> bool {
    let linear = transform.matrix3.as_mat3();
    let det = linear.determinant();
    linear.is_finite() && det.is_normal() && linear.inverse().is_finite()
}

/// Scale, rotation and translation of `transform`, or `None` if it shears (or does not
/// decompose into finite parts): what an object moving from one transform to another
/// interpolates. The scale's signs say which axes it mirrors (glam puts a negative
/// determinant's sign on x).
pub fn scale_rotation_translation(transform: &DAffine3) -> Option<(DVec3, DQuat, DVec3)> {
    let (scale, rotation, translation) = transform.to_scale_rotation_translation();
    let back = DAffine3::from_scale_rotation_translation(scale, rotation, translation);
    let largest = transform.matrix3.abs().to_cols_array().iter().fold(1.0f64, |a, &b| a.max(b));
    let sheared = !back.matrix3.abs_diff_eq(transform.matrix3, 1e-9 * largest);
    (!sheared && scale.is_finite()).then_some((scale, rotation, translation))
}

/// The scale, rotation and translation of `start` and `end` that an object moving from one
/// to the other interpolates part by part, or why it cannot move so: an end that shears, or
/// a scale that is zero or changes sign on the way (the transform would be singular in
/// between).
pub fn motion_parts(
    start: &DAffine3,
    end: &DAffine3,
) -> Result<[(DVec3, DQuat, DVec3); 2], String> {
    let (Some(from), Some(to)) =
        (scale_rotation_translation(start), scale_rotation_translation(end))
    else {
        return Err("a moving object's transform must be translation · rotation · scale (no \
                    shear) at both ends of the shutter interval"
            .to_owned());
    };
    if (from.0 * to.0).cmple(DVec3::ZERO).any() {
        return Err(format!(
            "the scale is zero or changes sign on the way (from {} to {}): the transform would \
             be singular in between",
            from.0, to.0
        ));
    }
    Ok([from, to])
}

/// The uniform scale factor of a similarity transform (rotation × uniform scale ×
/// translation), or `None` if the linear part shears or scales unevenly.
pub fn uniform_scale(transform: &DAffine3) -> Option<f64> {
    let m = transform.matrix3;
    let gram = m.transpose() * m;
    let s2 = gram.x_axis.x;
    let tolerance = 1e-9 * s2.max(1e-300);
    let off_diagonal = [gram.x_axis.y, gram.x_axis.z, gram.y_axis.z];
    let uniform = (gram.y_axis.y - s2).abs() <= tolerance
        && (gram.z_axis.z - s2).abs() <= tolerance
        && off_diagonal.iter().all(|v| v.abs() <= tolerance);
    (uniform && s2 > 0.0).then(|| s2.sqrt())
}

/// How far from orthonormal a rotation written out may be: Mitsuba's `has_scale` test (Mᵀ·M
/// within 1e-3 of the identity, entry by entry). Exporters write matrices to six digits or
/// so, whose columns miss unit length by about 1e-6.
pub const ROTATION_TOLERANCE: f64 = 1e-3;

/// Whether `m` is a rotation, possibly mirrored, to within `ROTATION_TOLERANCE`: no scale
/// or shear.
pub fn is_orthonormal(m: DMat3) -> bool {
    (m.transpose() * m - DMat3::IDENTITY)
        .to_cols_array()
        .iter()
        .all(|e| e.abs() <= ROTATION_TOLERANCE)
}

/// The exact rotation that `m`, a rotation written to a few digits, stands for (its nearest
/// orthonormal matrix, by the polar decomposition's iteration); `None` if `m` scales,
/// shears or mirrors beyond `ROTATION_TOLERANCE`. Code that inverts a rotation by
/// transposing it needs it exact.
pub fn nearest_rotation(m: DMat3) -> Option<DMat3> {
    if !(is_orthonormal(m) && m.determinant() > 0.0) {
        return None;
    }
    if (m.transpose() * m - DMat3::IDENTITY).to_cols_array().iter().all(|e| e.abs() <= 1e-15) {
        // Already a rotation to the last bit or so: kept as written, so that a rotation
        // read twice (a Mitsuba scene converted to TOML and read back) stays the same.
        return Some(m);
    }
    let mut rotation = m;
    // Newton's iteration R ← (R + R⁻ᵀ) / 2 converges quadratically from this close.
    for _ in 0..6 {
        let next = (rotation + rotation.inverse().transpose()) * 0.5;
        let settled = next.abs_diff_eq(rotation, 1e-16);
        rotation = next;
        if settled {
            break;
        }
    }
    Some(rotation)
}

/// A rigid transform that maps the standard axes onto an orthonormal `basis` placed at
/// `origin`.
pub fn from_basis_and_origin(basis: DMat3, origin: DVec3) -> DAffine3 {
    DAffine3 { matrix3: basis, translation: origin }
}

/// The course's (CENG795) axes of a square facing `normal` (area lights, glossy
/// perturbation): the normal with its smallest component set to 1 gives a second direction;
/// u = normalize(n × n′), v = n × u.
pub fn course_square_axes(normal: DVec3) -> (DVec3, DVec3) {
    let n = normal.normalize();
    let a = n.abs();
    let mut other = n;
    if a.x <= a.y && a.x <= a.z {
        other.x = 1.0;
    } else if a.y <= a.z {
        other.y = 1.0;
    } else {
        other.z = 1.0;
    }
    let u = n.cross(other).normalize();
    (u, n.cross(u))
}

/// Orthonormal camera basis (columns: right, up, back) for a camera looking along `forward`.
///
/// Stays well defined when `up` is parallel to `forward` (looking straight up or down): the
/// world axis least aligned with `forward` is used instead, which is what a user pointing a
/// camera at the zenith expects (a stable, level-ish frame) rather than NaNs.
pub fn camera_basis(forward: DVec3, up: DVec3) -> DMat3 {
    let forward = forward.normalize();
    let mut right = forward.cross(up);
    if right.length_squared() <= 1e-20 * up.length_squared().max(f64::MIN_POSITIVE) {
        let a = forward.abs();
        let fallback = if a.x <= a.y && a.x <= a.z {
            DVec3::X
        } else if a.y <= a.z {
            DVec3::Y
        } else {
            DVec3::Z
        };
        right = forward.cross(fallback);
    }
    let right = right.normalize();
    let true_up = right.cross(forward);
    DMat3::from_cols(right, true_up, -forward)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_orthonormal_when_up_is_parallel_to_view() {
        for forward in [DVec3::Y, DVec3::NEG_Y, DVec3::new(0.0, 1.0, 1e-12)] {
            let b = camera_basis(forward, DVec3::Y);
            assert!(b.is_finite());
            assert!((b.determinant() - 1.0).abs() < 1e-9);
            assert!((b.z_axis + forward.normalize()).length() < 1e-9);
        }
    }

    #[test]
    fn a_rotation_written_to_six_digits_is_made_exact_and_a_scale_is_not() {
        let exact = DMat3::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
        let written =
            DMat3::from_cols_array(&exact.to_cols_array().map(|x| (x * 1e6).round() / 1e6));
        assert!(
            (written.transpose() * written - DMat3::IDENTITY)
                .to_cols_array()
                .iter()
                .any(|e| e.abs() > 1e-9)
        );
        let rotation = nearest_rotation(written).expect("within Mitsuba's tolerance");
        let off = (rotation.transpose() * rotation - DMat3::IDENTITY).to_cols_array();
        assert!(off.iter().all(|e| e.abs() < 1e-15), "{off:?}");
        assert!(rotation.abs_diff_eq(exact, 1e-6), "{rotation} vs {exact}");
        assert!(
            nearest_rotation(exact * DMat3::from_diagonal(DVec3::new(1.0, 1.01, 1.0))).is_none()
        );
        assert!(
            nearest_rotation(exact * DMat3::from_diagonal(DVec3::new(1.0, -1.0, 1.0))).is_none()
        );
        assert!(nearest_rotation(DMat3::from_cols_array(&[f64::NAN; 9])).is_none());
        assert!(is_orthonormal(DMat3::from_diagonal(DVec3::new(1.0, -1.0, 1.0))));
    }

    #[test]
    fn uniform_scale_detects_similarity() {
        let t = DAffine3::from_scale_rotation_translation(
            DVec3::splat(2.5),
            glam::DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7),
            DVec3::new(1e7, -3.0, 2.0),
        );
        assert!((uniform_scale(&t).unwrap() - 2.5).abs() < 1e-12);
        let stretched = DAffine3::from_scale(DVec3::new(1.0, 2.0, 1.0));
        assert!(uniform_scale(&stretched).is_none());
    }

    #[test]
    fn normal_matrix_keeps_normals_perpendicular_under_nonuniform_scale() {
        let t = DAffine3::from_scale(DVec3::new(1.0, 4.0, 1.0));
        let tangent = t.transform_vector3(DVec3::new(1.0, -1.0, 0.0));
        let normal = normal_matrix(&t).unwrap() * DVec3::new(1.0, 1.0, 0.0);
        assert!(tangent.dot(normal).abs() < 1e-12);
    }
}
