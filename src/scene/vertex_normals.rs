//! Shading normals for a mesh that has none: each vertex gets the normalised sum of the
//! normals of the triangles around it, weighted by their area (embray's own formats) or by
//! the triangle's angle at the vertex (Mitsuba's `recompute_vertex_normals`, after Thürmer and
//! Wüthrich, "Computing vertex normals from polygonal facets", JGT 1998). Angle weights do not
//! depend on how a face is cut into triangles: a cube's corner gets the diagonal either way.
//! A vertex whose weighted normals cancel gets none (the geometric normal is used there), where
//! Mitsuba writes an arbitrary (1, 0, 0) with a warning.

use glam::{DMat3, DVec3};

/// How the triangles around a vertex are weighted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum VertexNormals {
    /// By area (the unnormalised cross product).
    #[default]
    AreaWeighted,
    /// By the triangle's angle at the vertex, as Mitsuba 3 computes them.
    AngleWeighted,
}

impl VertexNormals {
    /// One normal per vertex. A vertex whose sum is zero (only degenerate triangles, or
    /// none) gets the zero vector, for which the renderer uses the geometric normal.
    pub fn of(self, positions: &[DVec3], indices: &[[u32; 3]]) -> Vec<DVec3> {
        let mut sums = vec![DVec3::ZERO; positions.len()];
        for &triangle in indices {
            let corners = triangle.map(|i| positions[i as usize]);
            let normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
            if !normal.is_finite() || normal == DVec3::ZERO {
                continue;
            }
            let weights = match self {
                VertexNormals::AreaWeighted => [normal; 3],
                VertexNormals::AngleWeighted => {
                    let unit = normal.normalize();
                    corner_angles(corners).map(|angle| unit * angle)
                }
            };
            for (i, weight) in triangle.into_iter().zip(weights) {
                sums[i as usize] += weight;
            }
        }
        sums.into_iter().map(DVec3::normalize_or_zero).collect()
    }
}

/// Whether `linear` keeps angles (a rotation, a mirror and a uniform scale): only then are
/// angle-weighted normals the same computed before or after it.
pub fn keeps_angles(linear: DMat3) -> bool {
    let [x, y, z] = [linear.x_axis, linear.y_axis, linear.z_axis];
    let scale = x.length_squared();
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * scale;
    close(y.length_squared(), scale)
        && close(z.length_squared(), scale)
        && close(x.dot(y), 0.0)
        && close(y.dot(z), 0.0)
        && close(z.dot(x), 0.0)
}

impl VertexNormals {
    /// `of` the mesh as `linear` places it (Mitsuba computes them after `to_world`), turned
    /// back into the mesh's own space, where the renderer's normal transform takes them to the
    /// placed ones. Each faces the side the object-space triangles around it face, as `of`'s
    /// do (a mirror's turn of the winding undone).
    pub fn of_placed(self, positions: &[DVec3], indices: &[[u32; 3]], linear: DMat3) -> Vec<DVec3> {
        let placed: Vec<DVec3> = positions.iter().map(|&p| linear * p).collect();
        let side = linear.determinant().signum();
        let back = linear.transpose() * side;
        self.of(&placed, indices).into_iter().map(|n| (back * n).normalize_or_zero()).collect()
    }
}

/// The triangle's angle at each corner, from the chord between unit edges (accurate near 0
/// and π, where an arc cosine is not).
fn corner_angles([a, b, c]: [DVec3; 3]) -> [f64; 3] {
    let angle = |at: DVec3, p: DVec3, q: DVec3| {
        let (u, v) = ((p - at).normalize_or_zero(), (q - at).normalize_or_zero());
        if u.dot(v) < 0.0 {
            std::f64::consts::PI - 2.0 * ((u + v).length() / 2.0).min(1.0).asin()
        } else {
            2.0 * ((u - v).length() / 2.0).min(1.0).asin()
        }
    };
    [angle(a, b, c), angle(b, c, a), angle(c, a, b)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes::box_mesh;

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn box_corner_normals_are_area_weighted() {
        let mesh = box_mesh(DVec3::ZERO, DVec3::ONE).unwrap();
        let normals = VertexNormals::AreaWeighted.of(&mesh.positions, &mesh.indices);
        // Vertices 0 and 7 are in both triangles of each of their three faces.
        assert!(close(normals[0], -DVec3::ONE / 3f64.sqrt()), "{}", normals[0]);
        assert!(close(normals[7], DVec3::ONE / 3f64.sqrt()), "{}", normals[7]);
        // Vertex 1 (max x): both +x triangles, one of the −y face, one of the −z face.
        assert!(close(normals[1], DVec3::new(2.0, -1.0, -1.0) / 6f64.sqrt()), "{}", normals[1]);
    }

    #[test]
    fn box_corner_normals_by_angle_are_the_diagonals() {
        let mesh = box_mesh(DVec3::ZERO, DVec3::ONE).unwrap();
        let normals = VertexNormals::AngleWeighted.of(&mesh.positions, &mesh.indices);
        for (p, n) in mesh.positions.iter().zip(&normals) {
            // Each corner's three faces meet at right angles, however each face is cut.
            let diagonal = (*p - DVec3::splat(0.5)).normalize();
            assert!(close(*n, diagonal), "at {p}: {n}, not {diagonal}");
        }
    }

    #[test]
    fn corner_angles_sum_to_pi_and_match_acos() {
        let triangles = [
            [DVec3::ZERO, DVec3::X, DVec3::Y],
            [DVec3::ZERO, DVec3::new(1e3, 0.0, 0.0), DVec3::new(500.0, 1e-3, 0.0)],
            [DVec3::new(0.3, -2.0, 1.0), DVec3::new(4.0, 0.5, -1.0), DVec3::new(-1.0, 1.0, 2.0)],
        ];
        for t in triangles {
            let angles = corner_angles(t);
            assert!((angles.iter().sum::<f64>() - std::f64::consts::PI).abs() < 1e-12, "{t:?}");
            let acos = (t[1] - t[0]).normalize().dot((t[2] - t[0]).normalize()).acos();
            assert!((angles[0] - acos).abs() < 1e-6, "{} against {acos}", angles[0]);
        }
    }

    #[test]
    fn a_fan_is_weighted_by_angle_not_by_count() {
        // Vertex 0 is in one triangle of the z = 0 plane spanning 90° and in three thin
        // ones of the x = 0 plane that span 90° together: by angle it is the diagonal of
        // the two planes' normals, by area it leans to the bigger triangles' plane.
        let positions = [
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::new(0.0, 1.0, 1.0),
            DVec3::new(0.0, 0.3, 1.0),
            DVec3::Z,
        ];
        let indices = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]];
        let by_angle = VertexNormals::AngleWeighted.of(&positions, &indices);
        let diagonal = DVec3::new(1.0, 0.0, 1.0).normalize();
        assert!(close(by_angle[0], diagonal), "{}", by_angle[0]);
        let by_area = VertexNormals::AreaWeighted.of(&positions, &indices);
        assert!((by_area[0] - diagonal).length() > 0.1, "{}", by_area[0]);
    }

    #[test]
    fn normals_placed_by_a_stretch_are_weighted_where_placed() {
        // A cube stretched tenfold along z: its corners' angles stay right, so Mitsuba's
        // normals (computed on the stretched cube) are the stretched cube's corner
        // diagonals; computed before the stretch and carried through it they lean to z.
        let mesh = box_mesh(DVec3::ZERO, DVec3::ONE).unwrap();
        let stretch = DMat3::from_diagonal(DVec3::new(1.0, 1.0, 10.0));
        let placed =
            VertexNormals::AngleWeighted.of_placed(&mesh.positions, &mesh.indices, stretch);
        let unplaced = VertexNormals::AngleWeighted.of(&mesh.positions, &mesh.indices);
        let carried = |n: DVec3| (stretch.inverse().transpose() * n).normalize();
        for ((p, n), m) in mesh.positions.iter().zip(&placed).zip(&unplaced) {
            let diagonal = (*p - DVec3::splat(0.5)).signum() / 3f64.sqrt();
            assert!(close(carried(*n), diagonal), "at {p}: {}", carried(*n));
            assert!((carried(*m) - diagonal).length() > 0.5, "at {p}: {}", carried(*m));
        }
        // Under a mirror too, each normal still faces the object's own outside.
        let mirror = DMat3::from_diagonal(DVec3::new(-1.0, 1.0, 10.0));
        let mirrored =
            VertexNormals::AngleWeighted.of_placed(&mesh.positions, &mesh.indices, mirror);
        for (p, n) in mesh.positions.iter().zip(&mirrored) {
            assert!(n.dot(*p - DVec3::splat(0.5)) > 0.0, "at {p}: {n}");
        }
        assert!(keeps_angles(DMat3::from_diagonal(DVec3::splat(-2.0))));
        assert!(!keeps_angles(stretch));
    }

    #[test]
    fn degenerate_and_unused_vertices_get_zero() {
        let positions = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::X * 2.0, DVec3::Z];
        // A proper triangle, and a degenerate one (0, 1, 3 are collinear).
        for weighting in [VertexNormals::AreaWeighted, VertexNormals::AngleWeighted] {
            let normals = weighting.of(&positions, &[[0, 1, 2], [0, 1, 3]]);
            assert_eq!(normals[0], DVec3::Z);
            assert_eq!(normals[3], DVec3::ZERO);
            assert_eq!(normals[4], DVec3::ZERO);
        }
    }
}
