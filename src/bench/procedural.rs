//! Procedurally generated benchmark scenes, so the large ones need no files.

use crate::scene::{
    CameraDesc, LightDesc, MaterialDesc, MeshData, ObjectDesc, Point, RenderSettings, SceneDesc,
    ShapeDesc,
};
use glam::{DAffine3, DVec3, Vec3};
use std::sync::Arc;

/// A bumpy sphere of about `triangles` triangles (a latitude/longitude grid with a smooth
/// radial displacement), like the 1M-triangle mesh of the Embree measurements.
pub fn displaced_sphere(triangles: usize) -> MeshData {
    let rings = ((triangles as f64 / 4.0).sqrt().round() as u32).max(4);
    let segments = 2 * rings;
    let mut positions = Vec::with_capacity(((rings + 1) * (segments + 1)) as usize);
    for i in 0..=rings {
        let theta = std::f64::consts::PI * i as f64 / rings as f64;
        for j in 0..=segments {
            let phi = std::f64::consts::TAU * j as f64 / segments as f64;
            let dir = DVec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin());
            let bump = 1.0
                + 0.05 * (7.0 * theta).sin() * (9.0 * phi).cos()
                + 0.02 * (31.0 * theta).cos() * (29.0 * phi).sin();
            positions.push(dir * bump);
        }
    }
    let mut indices = Vec::with_capacity((rings * segments * 2) as usize);
    for i in 0..rings {
        for j in 0..segments {
            let a = i * (segments + 1) + j;
            let (b, c, d) = (a + 1, a + segments + 1, a + segments + 2);
            if i > 0 {
                indices.push([a, b, c]);
            }
            if i + 1 < rings {
                indices.push([b, d, c]);
            }
        }
    }
    MeshData { positions, indices, normals: None, uvs: None, attributes: Vec::new() }
}

/// The displaced sphere on a ground quad, lit by a point light.
pub fn displaced_sphere_scene(triangles: usize, width: u32, height: u32) -> SceneDesc {
    let camera = CameraDesc::pinhole(
        DVec3::new(0.0, 1.2, 3.2),
        DVec3::new(0.0, 0.1, 0.0),
        40.0,
        width,
        height,
    );
    let ground = MeshData {
        positions: vec![
            DVec3::new(-10.0, -1.1, -10.0),
            DVec3::new(10.0, -1.1, -10.0),
            DVec3::new(10.0, -1.1, 10.0),
            DVec3::new(-10.0, -1.1, 10.0),
        ],
        indices: vec![[0, 2, 1], [0, 3, 2]],
        normals: None,
        uvs: None,
        attributes: Vec::new(),
    };
    let material =
        MaterialDesc { name: "grey".into(), albedo: Vec3::splat(0.7), ..Default::default() };
    let object = |name: &str, mesh: MeshData| ObjectDesc {
        name: name.into(),
        shape: ShapeDesc::Mesh(Arc::new(mesh)),
        material: 0,
        world_from_object: DAffine3::IDENTITY,
        world_from_object_end: None,
    };
    SceneDesc {
        source: format!("displaced sphere ({triangles} triangles)").into(),
        reading_bytes: 0,
        camera,
        settings: RenderSettings { spp: 4, max_depth: 3, ..Default::default() },
        materials: vec![material],
        objects: vec![object("sphere", displaced_sphere(triangles)), object("ground", ground)],
        lights: vec![LightDesc::Point(Point {
            position: DVec3::new(3.0, 5.0, 4.0),
            intensity: Vec3::splat(60.0),
        })],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn displaced_sphere_has_about_the_requested_size() {
        let mesh = displaced_sphere(100_000);
        let n = mesh.indices.len();
        assert!((90_000..110_000).contains(&n), "{n}");
        assert!(mesh.indices.iter().flatten().all(|&i| (i as usize) < mesh.positions.len()));
    }
}
