//! `Accel::intersect_batch` (coherent or not) returns exactly what `Accel::intersect` returns
//! ray by ray, and `Accel::occluded_batch` what `Accel::occluded` does (bit for
//! bit, counters included), for every backend and batch mode: on camera rays (coherent,
//! Embree traces them as packets), bounce rays, random rays with shutter times (moving
//! instances), rays exactly through the shared edge of two triangles (where Embree's packet
//! and single-ray kernels break ties differently), and invalid rays mixed into the batches.
//! The same rays queued in columns (`Accel::intersect_columns`, `Accel::occluded_columns`,
//! as the path tracer queues them) give the slices' answers bit for bit.

mod common;

use common::*;
use embray::accel::{AccelOptions, BackendKind, BatchMode, Coherence, build};
use embray::bench::speed;
use embray::choice::Choice;
use embray::intersect::{intersect_sphere, intersect_triangle};
use embray::ray::{Hit, Ray};
use embray::ray_columns::RayColumns;
use embray::render::{RenderOptions, prepare_scene};
use embray::render_scene::{Geometry, Placement, RenderScene};
use embray::scene::{MaterialDesc, MeshData, ObjectDesc, SceneDesc, ShapeDesc};
use embray::stats::TraversalCounters;
use glam::{DAffine3, DVec3, Vec2, Vec3};
use std::sync::Arc;

use embray::splitmix::SplitMix64 as Rng;

/// Rays no backend may be handed: each must come back as a miss.
fn invalid_rays() -> Vec<Ray> {
    let ok = Ray::new(Vec3::ZERO, Vec3::Z, f32::INFINITY);
    vec![
        Ray { dir: Vec3::new(f32::NAN, 0.0, 1.0), ..ok },
        Ray { dir: Vec3::ZERO, ..ok },
        Ray { origin: Vec3::splat(f32::INFINITY), ..ok },
        Ray { origin: Vec3::splat(1e30), ..ok },
        Ray { dir: Vec3::new(0.0, 1e20, 1.0), ..ok },
        Ray { tmin: -1.0, ..ok },
        Ray { tmin: 2.0, tmax: 1.0, ..ok },
        Ray { tmax: f32::NAN, ..ok },
        Ray { time: f32::NAN, ..ok },
    ]
}

/// Camera rays (pixel centres, then jittered with shutter times), bounce rays from their
/// hits, random rays through the region the camera sees with random times and ranges, and
/// invalid rays scattered among them.
fn test_rays(scene: &RenderScene, seed: u64) -> Vec<Ray> {
    let mut rng = Rng(seed);
    let camera = &scene.camera;
    let primary = speed::primary_rays(scene);
    let mut rays = primary.clone();
    for _ in 0..primary.len() {
        let raster =
            Vec2::new(rng.range(0.0, camera.width as f32), rng.range(0.0, camera.height as f32));
        let mut ray = camera.generate_ray(raster, Some(Vec2::new(rng.unit(), rng.unit())));
        ray.time = rng.unit();
        rays.push(ray);
    }
    let reference = build(BackendKind::default_compiled(), scene, &AccelOptions::default())
        .expect("backend builds");
    rays.extend(speed::diffuse_rays(scene, reference.as_ref(), &primary));
    let points: Vec<Vec3> = primary
        .iter()
        .filter_map(|r| {
            let hit = reference.intersect(r, &mut TraversalCounters::default())?;
            Some(r.origin + hit.t * r.dir)
        })
        .collect();
    if let Some(&first) = points.first() {
        let (lo, hi) = points.iter().fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        let margin = (hi - lo) * 0.1 + Vec3::splat(1e-3);
        for k in 0..primary.len() {
            let origin = rng.between(lo - margin, hi + margin);
            let target = points[rng.next_u64() as usize % points.len()];
            let mut ray = Ray::new(origin, (target - origin) * rng.range(0.3, 3.0), f32::INFINITY);
            ray.time = if k % 8 == 0 { (k / 8 % 2) as f32 } else { rng.unit() };
            if k % 4 == 1 {
                ray.tmin = rng.range(0.0, 0.5);
            }
            if k % 2 == 1 {
                ray.tmax = ray.tmin + rng.range(0.1, 2.0);
            }
            rays.push(ray);
        }
    }
    // Invalid rays at scattered places, so they land in every lane of a packet.
    let invalid = invalid_rays();
    for k in 0..rays.len() / 7 {
        let at = (k * 7 + k % 5).min(rays.len());
        rays.insert(at, invalid[k % invalid.len()]);
    }
    rays
}

fn bits(hit: Option<Hit>) -> Option<(u32, u32, u32, u32, u32)> {
    hit.map(|h| (h.t.to_bits(), h.geom_id, h.prim_id, h.u.to_bits(), h.v.to_bits()))
}

/// Where the ray meets primitive `hit.prim_id` of geometry `hit.geom_id` (our own
/// intersection tests, in the primitive's space), if it does.
fn t_on_primitive(scene: &RenderScene, ray: &Ray, hit: &Hit) -> Option<f32> {
    let instance = &scene.instances[hit.geom_id as usize];
    let (origin, dir) = match &instance.placement {
        Placement::Baked { .. } => (ray.origin, ray.dir),
        Placement::Static { object_from_render, .. } => (
            object_from_render.transform_point3(ray.origin),
            object_from_render.transform_vector3(ray.dir),
        ),
        Placement::Moving { .. } => return None,
    };
    match &scene.prototypes[instance.prototype as usize].geometry {
        Geometry::Triangles(mesh) => {
            let tri = mesh.triangle(hit.prim_id);
            intersect_triangle(origin, dir, 0.0, f32::INFINITY, &tri).map(|(t, _, _)| t)
        }
        Geometry::Sphere(s) => {
            intersect_sphere(origin, dir, 0.0, f32::INFINITY, s.center, s.radius)
        }
        Geometry::SdfGrid(grid) => {
            let (voxel, corners) = grid.prim_corners(hit.prim_id)?;
            embray::intersect_sdf::intersect_voxel(origin, dir, 0.0, f32::INFINITY, voxel, &corners)
        }
    }
}

/// Every batch mode of every backend against single-ray queries on `rays`, in batches of
/// several sizes; `what` names the case in failures.
///
/// Exact everywhere, with one documented exception (`BatchMode`): with Embree packets, a ray
/// whose closest hit is an exact or near-exact tie between two surfaces that share no edge
/// (coincident faces, e.g. a box's bottom on the floor seen from below) may report the
/// other surface. Such a difference must be a proven tie: `t` within a few ulps, and the ray
/// really meets both primitives there (by our own intersection tests). `BatchMode::Single`
/// has no exception.
fn assert_batches_match(scene: &RenderScene, rays: &[Ray], what: &str) {
    for backend in backends() {
        let modes: &[BatchMode] = match backend {
            BackendKind::Embree => &[BatchMode::Single, BatchMode::Packets8, BatchMode::Packets16],
            BackendKind::Obvhs => &[BatchMode::Packets8],
        };
        for &batch in modes {
            for count_traversal in [false, true] {
                let options = AccelOptions { count_traversal, batch, ..AccelOptions::default() };
                let accel = build(backend, scene, &options).expect("backend builds");
                // Counting mode traces one ray at a time, so it never has the exception.
                let packets = backend == BackendKind::Embree
                    && batch != BatchMode::Single
                    && !count_traversal;
                let mut single_counters = TraversalCounters::default();
                let single: Vec<Option<Hit>> =
                    rays.iter()
                        .map(|r| {
                            if r.is_valid() {
                                accel.intersect(r, &mut single_counters)
                            } else {
                                None
                            }
                        })
                        .collect();
                let mut single_blocked_counters = TraversalCounters::default();
                let single_blocked: Vec<bool> = rays
                    .iter()
                    .map(|r| !r.is_valid() || accel.occluded(r, &mut single_blocked_counters))
                    .collect();
                let sizes = [1, 7, 8, 13, 16, 1024, rays.len()];
                let coherences = [Coherence::Coherent, Coherence::Incoherent];
                for (size, coherence) in sizes.into_iter().flat_map(|s| coherences.map(|c| (s, c)))
                {
                    // Occlusion has no ties to break: exactly the single-ray answers.
                    let mut counters = TraversalCounters::default();
                    let mut blocked = vec![false; rays.len()];
                    for (r, b) in rays.chunks(size).zip(blocked.chunks_mut(size)) {
                        accel.occluded_batch(r, b, &mut counters);
                    }
                    assert_eq!(
                        blocked,
                        single_blocked,
                        "{what}, {} {batch:?}, occlusion in batches of {size}",
                        backend.name()
                    );
                    assert_eq!(counters, single_blocked_counters, "{what}: occlusion counters");
                    // The same rays queued in columns (as the path tracer queues its shadow
                    // rays): the same answers and counters.
                    let mut counters = TraversalCounters::default();
                    let mut blocked = vec![false; rays.len()];
                    // One queue reused, as the path tracer reuses its own: the spare lanes
                    // of a short last chunk hold the chunk before's rays.
                    let mut columns = RayColumns::default();
                    for (r, b) in rays.chunks(size).zip(blocked.chunks_mut(size)) {
                        columns.clear();
                        r.iter().for_each(|ray| columns.push(ray));
                        accel.occluded_columns(&columns, b, &mut counters);
                    }
                    assert_eq!(
                        blocked,
                        single_blocked,
                        "{what}, {} {batch:?}, occlusion of columns in batches of {size}",
                        backend.name()
                    );
                    assert_eq!(counters, single_blocked_counters, "{what}: columns' counters");
                    let mut counters = TraversalCounters::default();
                    let stale = Hit { t: -1.0, geom_id: 9, prim_id: 9, u: 0.0, v: 0.0 };
                    let mut hits = vec![Some(stale); rays.len()];
                    for (r, h) in rays.chunks(size).zip(hits.chunks_mut(size)) {
                        accel.intersect_batch(r, h, coherence, &mut counters);
                    }
                    // The same rays queued in columns fill the same packets: the same hits,
                    // ties broken alike, and the same counters.
                    let mut column_counters = TraversalCounters::default();
                    let mut column_hits = vec![Some(stale); rays.len()];
                    for (r, h) in rays.chunks(size).zip(column_hits.chunks_mut(size)) {
                        columns.clear();
                        r.iter().for_each(|ray| columns.push(ray));
                        accel.intersect_columns(&columns, h, coherence, &mut column_counters);
                    }
                    let same = hits.iter().zip(&column_hits).all(|(a, b)| bits(*a) == bits(*b));
                    assert!(same, "{what}, {batch:?}: columns' hits differ, batches of {size}");
                    assert_eq!(column_counters, counters, "{what}: columns' hit counters");
                    let mut ties = 0;
                    for (k, (batched, one)) in hits.iter().zip(&single).enumerate() {
                        if bits(*batched) == bits(*one) {
                            continue;
                        }
                        let context = format!(
                            "{what}, {} {batch:?} counting {count_traversal}, {coherence:?} \
                             batches of {size}: ray {k} {:?}: batch {batched:?}, single {one:?}",
                            backend.name(),
                            rays[k]
                        );
                        let (Some(b), Some(s)) = (batched, one) else { panic!("{context}") };
                        let meets = |h: &Hit| {
                            t_on_primitive(scene, &rays[k], h)
                                .is_some_and(|t| (t - h.t).abs() <= 1e-4 * h.t.abs())
                        };
                        let tie = (b.t - s.t).abs() <= 4.0 * f32::EPSILON * s.t.abs();
                        assert!(packets && tie && meets(b) && meets(s), "not a tie: {context}");
                        ties += 1;
                    }
                    if ties > 0 {
                        println!(
                            "{what}, {} {batch:?}, batches of {size}: {ties} of {} rays are \
                             (near-)exact ties between coincident surfaces, broken differently",
                            backend.name(),
                            rays.len()
                        );
                    }
                    assert!(ties * 100 <= rays.len(), "{what}: {ties} ties");
                    assert_eq!(
                        counters,
                        single_counters,
                        "{what}, {} {batch:?} counting {count_traversal}, batches of {size}",
                        backend.name()
                    );
                }
            }
        }
    }
}

fn render_scene(desc: &SceneDesc) -> RenderScene {
    prepare_scene(desc, &RenderOptions::for_scene(desc)).expect("scene converts")
}

#[test]
fn batches_equal_single_rays_on_bundled_scenes() {
    // Meshes, instanced meshes, instanced spheres and an ellipsoid, moving instances,
    // spheres with depth of field.
    for (seed, name) in
        ["cornell", "instances", "textured_instances", "moving_boxes", "dof_spheres"]
            .into_iter()
            .enumerate()
    {
        let mut desc = load_bundled(name);
        let scale = 40.0 / desc.camera.width.max(desc.camera.height) as f64;
        desc.camera.width = ((desc.camera.width as f64 * scale).round() as u32).max(1);
        desc.camera.height = ((desc.camera.height as f64 * scale).round() as u32).max(1);
        let scene = render_scene(&desc);
        let rays = test_rays(&scene, seed as u64 + 1);
        assert!(rays.len() > 3000, "{name}: {} rays", rays.len());
        assert_batches_match(&scene, &rays, name);
    }
}

fn load_bundled(name: &str) -> SceneDesc {
    embray::scene::load(&repo_path(&format!("scenes/{name}.toml"))).expect("bundled scene loads")
}

/// A unit square of two triangles sharing the diagonal (0,0,0)–(1,1,0), and rays straight
/// down through points of that diagonal: both triangles are hit at exactly the same `t`.
/// Embree's single-ray kernel keeps the first triangle of the leaf, its packet kernel the
/// last; the backend must still return the single-ray hit.
#[test]
fn ties_on_a_shared_edge_are_broken_as_single_rays_do() {
    let square = MeshData {
        positions: vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        normals: None,
        uvs: None,
        attributes: Vec::new(),
    };
    let mut desc = build::scene(build::camera([0.5, 0.5, 3.0], [0.5, 0.5, 0.0], 40.0, 16, 16));
    desc.materials.push(MaterialDesc { name: "grey".into(), ..Default::default() });
    desc.objects.push(ObjectDesc {
        name: "square".into(),
        shape: ShapeDesc::Mesh(Arc::new(square)),
        material: 0,
        world_from_object: DAffine3::IDENTITY,
        world_from_object_end: None,
    });
    let scene = render_scene(&desc);
    // Render space is camera-relative: find the square's corners through the camera.
    let origin = scene.camera.generate_ray(Vec2::ZERO, None).origin;
    let corner = origin + Vec3::new(-0.5, -0.5, -3.0);
    let mut rays = Vec::new();
    for k in 0..4096 {
        let s = (k as f32 + 0.5) / 4096.0;
        let on_diagonal = corner + Vec3::new(s, s, 0.0);
        rays.push(Ray::new(on_diagonal + Vec3::Z, Vec3::NEG_Z, f32::INFINITY));
    }
    // Make sure the case arises: both triangles really are hit at the same `t`.
    let ties = rays
        .iter()
        .filter(|r| {
            let tri = |i: usize| match &scene.prototypes[0].geometry {
                Geometry::Triangles(mesh) => mesh.triangle(i as u32),
                Geometry::Sphere(_) | Geometry::SdfGrid(_) => unreachable!("a mesh"),
            };
            let a = intersect_triangle(r.origin, r.dir, 0.0, 9.0, &tri(0));
            let b = intersect_triangle(r.origin, r.dir, 0.0, 9.0, &tri(1));
            matches!((a, b), (Some(a), Some(b)) if a.0 == b.0)
        })
        .count();
    assert!(ties > 100, "only {ties} rays are ties");
    assert_batches_match(&scene, &rays, "shared edge");
}
