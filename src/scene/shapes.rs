//! Built-in shapes that become triangle meshes: the quad (parallelogram), the
//! axis-aligned box, and Mitsuba's cube.

use crate::scene::desc::MeshData;
use crate::scene::formats::toml::transform_list::fmt_vec;
use glam::{DVec3, Vec2};

/// The parallelogram corner, corner+u, corner+u+v, corner+v as two triangles with uvs
/// (0,0), (1,0), (1,1), (0,1). Errors (with the reason) if u and v span no area.
pub(crate) fn quad_mesh(corner: DVec3, u: DVec3, v: DVec3) -> Result<MeshData, String> {
    // The sine of the angle between u and v (0 for a zero edge): parallel edges give
    // rounding noise rather than exactly 0, so the test is relative.
    let sine = u.normalize_or_zero().cross(v.normalize_or_zero()).length();
    if sine <= 1e-12 {
        return Err(format!(
            "u {} and v {} are zero or parallel, so the quad has no area",
            fmt_vec(&u.to_array()),
            fmt_vec(&v.to_array())
        ));
    }
    // Render space keeps it in f32, where a triangle's area (half of this) below f32's
    // smallest normal number is 0: the quad, and the light it may be, would vanish unseen.
    let area = u.cross(v).length();
    if area < 2.0 * f64::from(f32::MIN_POSITIVE) {
        return Err(format!(
            "u {} and v {} span an area of {area:e}, too small for f32 (at least {:e})",
            fmt_vec(&u.to_array()),
            fmt_vec(&v.to_array()),
            2.0 * f64::from(f32::MIN_POSITIVE)
        ));
    }
    let positions = vec![corner, corner + u, corner + u + v, corner + v];
    if !positions.iter().all(|p| p.is_finite()) {
        return Err("a corner of the quad overflows".to_owned());
    }
    Ok(MeshData {
        positions,
        indices: vec![[0, 1, 2], [0, 2, 3]],
        normals: None,
        uvs: Some(vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0),
        ]),
        attributes: Vec::new(),
    })
}

/// The box from `min` to `max`: 8 vertices, 12 triangles wound counter-clockwise seen from
/// outside (so `(b - a) × (c - a)` points out). Errors if min >= max on some axis.
pub(crate) fn box_mesh(min: DVec3, max: DVec3) -> Result<MeshData, String> {
    for (axis, name) in ["x", "y", "z"].iter().enumerate() {
        if min[axis] >= max[axis] {
            return Err(format!(
                "min {} must be less than max {} on every axis, but not on {name} ({} >= {})",
                fmt_vec(&min.to_array()),
                fmt_vec(&max.to_array()),
                min[axis],
                max[axis]
            ));
        }
    }
    // Vertex i has x from bit 0, y from bit 1, z from bit 2 (0 → min, 1 → max).
    let positions: Vec<DVec3> = (0..8)
        .map(|i| {
            DVec3::new(
                if i & 1 == 0 { min.x } else { max.x },
                if i & 2 == 0 { min.y } else { max.y },
                if i & 4 == 0 { min.z } else { max.z },
            )
        })
        .collect();
    // Faces as quads, each listed counter-clockwise seen from outside.
    const FACES: [[u32; 4]; 6] = [
        [0, 4, 6, 2], // -x
        [1, 3, 7, 5], // +x
        [0, 1, 5, 4], // -y
        [2, 6, 7, 3], // +y
        [0, 2, 3, 1], // -z
        [4, 5, 7, 6], // +z
    ];
    let indices = FACES.iter().flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]]).collect();
    Ok(MeshData { positions, indices, normals: None, uvs: None, attributes: Vec::new() })
}

/// Mitsuba's `cube` (v3.9.1 `cube.cpp`), vertex for vertex: the cube from (−1, −1, −1) to
/// (1, 1, 1) as 24 vertices, four per face, each face with its own normal and the uv square
/// (0,1), (1,1), (1,0), (0,0), so that a texture lands on every face as Mitsuba puts it.
/// Face `s` is the triangles {4s, 4s+1, 4s+2} and {4s+3, 4s, 4s+2}, wound outwards.
pub(crate) fn mitsuba_cube_mesh() -> MeshData {
    // Four vertices a face: −y, +y, +x, +z, −x, −z.
    #[rustfmt::skip]
    const CORNERS: [[f64; 3]; 24] = [
        [1., -1., -1.], [1., -1., 1.], [-1., -1., 1.], [-1., -1., -1.],
        [1., 1., -1.], [-1., 1., -1.], [-1., 1., 1.], [1., 1., 1.],
        [1., -1., -1.], [1., 1., -1.], [1., 1., 1.], [1., -1., 1.],
        [1., -1., 1.], [1., 1., 1.], [-1., 1., 1.], [-1., -1., 1.],
        [-1., -1., 1.], [-1., 1., 1.], [-1., 1., -1.], [-1., -1., -1.],
        [1., 1., -1.], [1., -1., -1.], [-1., -1., -1.], [-1., 1., -1.],
    ];
    const FACE_NORMALS: [DVec3; 6] =
        [DVec3::NEG_Y, DVec3::Y, DVec3::X, DVec3::Z, DVec3::NEG_X, DVec3::NEG_Z];
    const FACE_UVS: [[f32; 2]; 4] = [[0., 1.], [1., 1.], [1., 0.], [0., 0.]];
    MeshData {
        positions: CORNERS.iter().map(|&c| DVec3::from_array(c)).collect(),
        indices: (0..6u32)
            .flat_map(|s| {
                let v = 4 * s;
                [[v, v + 1, v + 2], [v + 3, v, v + 2]]
            })
            .collect(),
        normals: Some((0..24).map(|i| FACE_NORMALS[i / 4]).collect()),
        uvs: Some((0..24).map(|i| Vec2::from_array(FACE_UVS[i % 4])).collect()),
        attributes: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn face_normal(mesh: &MeshData, tri: [u32; 3]) -> DVec3 {
        let [a, b, c] = tri.map(|i| mesh.positions[i as usize]);
        (b - a).cross(c - a)
    }

    #[test]
    fn box_triangles_face_outward() {
        let (min, max) = (DVec3::new(-1.0, 0.0, 2.0), DVec3::new(3.0, 1.0, 2.5));
        let mesh = box_mesh(min, max).unwrap();
        assert_eq!(mesh.indices.len(), 12);
        let center = (min + max) / 2.0;
        for &tri in &mesh.indices {
            let centroid = tri.map(|i| mesh.positions[i as usize]).iter().sum::<DVec3>() / 3.0;
            let n = face_normal(&mesh, tri);
            assert!(n.length() > 0.0);
            assert!(n.dot(centroid - center) > 0.0, "triangle {tri:?} faces inward");
        }
    }

    #[test]
    fn mitsubas_cube_faces_outward_with_its_normals_and_uv_squares() {
        let cube = mitsuba_cube_mesh();
        assert_eq!((cube.positions.len(), cube.indices.len()), (24, 12));
        let normals = cube.normals.as_ref().unwrap();
        for &tri in &cube.indices {
            let n = face_normal(&cube, tri).normalize();
            for i in tri {
                assert_eq!(n, normals[i as usize], "triangle {tri:?}");
                // Every vertex lies on its face's plane x·n = 1.
                assert_eq!(cube.positions[i as usize].dot(n), 1.0);
            }
        }
        let uvs = cube.uvs.as_ref().unwrap();
        assert_eq!(uvs[..4], [Vec2::Y, Vec2::ONE, Vec2::X, Vec2::ZERO]);
        assert_eq!(uvs[4..8], uvs[..4]);
    }

    #[test]
    fn box_needs_min_below_max() {
        let err = box_mesh(DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0)).unwrap_err();
        assert!(err.contains("on y"), "{err}");
    }

    #[test]
    fn quad_vertices_and_uvs() {
        let mesh = quad_mesh(DVec3::ONE, DVec3::X * 2.0, DVec3::Z).unwrap();
        assert_eq!(mesh.positions[2], DVec3::new(3.0, 1.0, 2.0));
        assert_eq!(mesh.uvs.as_ref().unwrap()[2], Vec2::ONE);
        // Both triangles wind the same way: normal along u × v.
        for &tri in &mesh.indices {
            assert!(face_normal(&mesh, tri).dot(DVec3::X.cross(DVec3::Z)) > 0.0);
        }
    }

    #[test]
    fn parallel_quad_edges_are_rejected() {
        assert!(quad_mesh(DVec3::ZERO, DVec3::X, DVec3::X * 3.0).is_err());
        assert!(quad_mesh(DVec3::ZERO, DVec3::ZERO, DVec3::Y).is_err());
    }
}
