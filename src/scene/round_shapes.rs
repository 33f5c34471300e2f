//! Mitsuba's disk and open cylinder as fine triangle meshes with their exact normals and
//! texture coordinates (Mitsuba's parameterisations): the unit disk at z = 0 facing +Z,
//! uv = (r, φ/2π); the unit-radius cylinder from z = 0 to 1, facing outwards, uv = (φ/2π,
//! z). With `SEGMENTS` around, a silhouette is within 1 − cos(π/SEGMENTS) ≈ 1.9·10⁻⁵ of
//! the radius of the true curve: a hundredth of a pixel for a curve 500 pixels wide.

use crate::scene::desc::MeshData;
use glam::{DVec3, Vec2};
use std::f64::consts::TAU;

const SEGMENTS: u32 = 512;

/// The azimuth of segment edge `i`, and its v (or u) in [0, 1]; the seam has both 0 and 1.
fn azimuth(i: u32) -> (f64, f64) {
    let t = i as f64 / SEGMENTS as f64;
    (TAU * t, t)
}

/// The unit disk in the xy plane, normal +Z, as rings of triangles (so that r is
/// interpolated along radii, as the disk defines it).
pub(crate) fn disk_mesh() -> MeshData {
    const RINGS: u32 = 8;
    let mut mesh =
        MeshData { normals: Some(Vec::new()), uvs: Some(Vec::new()), ..Default::default() };
    for ring in 0..=RINGS {
        let r = ring as f64 / RINGS as f64;
        for i in 0..=SEGMENTS {
            let (phi, v) = azimuth(i);
            mesh.positions.push(DVec3::new(r * phi.cos(), r * phi.sin(), 0.0));
            mesh.normals.as_mut().unwrap().push(DVec3::Z);
            mesh.uvs.as_mut().unwrap().push(Vec2::new(r as f32, v as f32));
        }
    }
    let row = SEGMENTS + 1;
    for ring in 0..RINGS {
        for i in 0..SEGMENTS {
            let (inner, outer) = (ring * row + i, (ring + 1) * row + i);
            // Counter-clockwise seen from +Z.
            if ring > 0 {
                mesh.indices.push([inner, outer, inner + 1]);
            }
            mesh.indices.push([inner + 1, outer, outer + 1]);
        }
    }
    mesh
}

/// The open cylinder of radius 1 around the z axis from z = 0 to z = 1, normals outwards.
pub(crate) fn cylinder_mesh() -> MeshData {
    let mut mesh =
        MeshData { normals: Some(Vec::new()), uvs: Some(Vec::new()), ..Default::default() };
    for z in [0.0, 1.0] {
        for i in 0..=SEGMENTS {
            let (phi, u) = azimuth(i);
            let outward = DVec3::new(phi.cos(), phi.sin(), 0.0);
            mesh.positions.push(outward + DVec3::Z * z);
            mesh.normals.as_mut().unwrap().push(outward);
            mesh.uvs.as_mut().unwrap().push(Vec2::new(u as f32, z as f32));
        }
    }
    let row = SEGMENTS + 1;
    for i in 0..SEGMENTS {
        let (bottom, top) = (i, row + i);
        // Counter-clockwise seen from outside.
        mesh.indices.push([bottom, bottom + 1, top + 1]);
        mesh.indices.push([bottom, top + 1, top]);
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    fn face_normal(mesh: &MeshData, [a, b, c]: [u32; 3]) -> DVec3 {
        let p = |i: u32| mesh.positions[i as usize];
        (p(b) - p(a)).cross(p(c) - p(a)).normalize()
    }

    #[test]
    fn the_disk_faces_up_and_its_uvs_are_radius_and_turn() {
        let disk = disk_mesh();
        assert!(disk.indices.iter().all(|&t| face_normal(&disk, t).z > 0.999));
        let area: f64 = disk
            .indices
            .iter()
            .map(|&[a, b, c]| {
                let p = |i: u32| disk.positions[i as usize];
                0.5 * (p(b) - p(a)).cross(p(c) - p(a)).length()
            })
            .sum();
        assert!((area - std::f64::consts::PI).abs() < 1e-4, "{area}");
        for (p, uv) in disk.positions.iter().zip(disk.uvs.as_ref().unwrap()) {
            assert!((p.length() - uv.x as f64).abs() < 1e-6);
        }
    }

    #[test]
    fn the_cylinder_faces_outwards_with_the_normals_of_the_true_surface() {
        let cylinder = cylinder_mesh();
        for &t in &cylinder.indices {
            let n = face_normal(&cylinder, t);
            let centre = t.iter().map(|&i| cylinder.positions[i as usize]).sum::<DVec3>() / 3.0;
            assert!(n.dot(DVec3::new(centre.x, centre.y, 0.0)) > 0.99, "{t:?}");
        }
        let normals = cylinder.normals.as_ref().unwrap();
        for (p, n) in cylinder.positions.iter().zip(normals) {
            assert!((DVec3::new(p.x, p.y, 0.0) - *n).length() < 1e-12);
        }
    }
}
