//! Instances share one prototype: ten thousand cost far less than copies.

use super::*;

/// A 100 × 50 × 2 = 10,000-triangle grid.
fn grid_mesh() -> std::sync::Arc<embray::scene::MeshData> {
    let (nx, nz) = (100u32, 50u32);
    let mut positions = Vec::new();
    for j in 0..=nz {
        for i in 0..=nx {
            positions.push(DVec3::new(
                i as f64 * 0.01,
                ((i * 7 + j * 3) % 5) as f64 * 0.002,
                j as f64 * 0.01,
            ));
        }
    }
    let mut indices = Vec::new();
    for j in 0..nz {
        for i in 0..nx {
            let a = j * (nx + 1) + i;
            let (b, c, d) = (a + 1, a + nx + 1, a + nx + 2);
            indices.push([a, c, b]);
            indices.push([b, c, d]);
        }
    }
    std::sync::Arc::new(embray::scene::MeshData {
        positions,
        indices,
        normals: None,
        uvs: None,
        attributes: Vec::new(),
    })
}

fn instanced_scene(copies: usize) -> SceneDesc {
    let mut s = scene(camera([0.0, 5.0, 10.0], [0.0, 0.0, 0.0], 40.0, 8, 8));
    let m = add_material(&mut s, diffuse(0.5));
    let mesh = grid_mesh();
    for i in 0..copies {
        let at = DVec3::new((i % 100) as f64 * 1.1, 0.0, (i / 100) as f64 * 1.1);
        s.objects.push(object(
            "grid",
            ShapeDesc::Mesh(mesh.clone()),
            m,
            DAffine3::from_translation(at),
        ));
    }
    s
}

#[test]
fn ten_thousand_instances_cost_far_less_than_copies() {
    for backend in backends() {
        // The structure's own byte count (obvhs counts its arrays, Embree's memory monitor
        // its device): exact, and untouched by tests running alongside.
        let measure = |desc: SceneDesc| {
            let scene = prepare_scene(&desc, &options(&desc, backend, 1)).unwrap();
            let accel = build_accel(backend, &scene, &AccelOptions::default()).unwrap();
            accel.memory_bytes().expect("both backends count their bytes")
        };
        // Real copies for comparison: 200 placements of 200 distinct (equal) meshes.
        let copies_scene = |n: usize| {
            let mut desc = instanced_scene(n);
            for object in &mut desc.objects {
                if let ShapeDesc::Mesh(mesh) = &object.shape {
                    object.shape = ShapeDesc::Mesh(std::sync::Arc::new((**mesh).clone()));
                }
            }
            desc
        };
        let one = measure(copies_scene(200)) / 200;
        let many = measure(instanced_scene(10_000));
        println!(
            "{}: {one} bytes for one placed copy; 10,000 instances take {many} bytes \
             (copies would need ~{} bytes, {:.3} %)",
            backend.name(),
            one * 10_000,
            100.0 * many as f64 / (one * 10_000) as f64
        );
        // Measured 0.024 % (Embree) and 0.026 % (obvhs).
        assert!(
            many < one * 10_000 / 1000,
            "{}: instancing is not O(1) per instance",
            backend.name()
        );
    }
}
