//! Every backend against a brute-force linear scan, on random rays against random triangles,
//! spheres and quads — including rays that start on a surface and rays aimed at edges.

mod common;

use common::backends;
use embray::accel::{AccelOptions, BackendKind, BuildQuality, Intersection, build};
use embray::camera::Camera;
use embray::choice::Choice;
use embray::float_error::{TrianglePlane, triangle_point};
use embray::intersect::{intersect_sphere, intersect_triangle};
use embray::ray::{Hit, Ray};
use embray::render_scene::{Geometry, RenderScene, Sphere, TriangleMesh};
use embray::sampling::{hash4, to_unit_f32};
use embray::shading::material::Material;
use embray::shading::spawn::SurfacePoint;
use embray::stats::TraversalCounters;
use glam::Vec3;

struct Rng(u64);

impl Rng {
    fn f(&mut self) -> f32 {
        self.0 += 1;
        to_unit_f32(hash4(99, self.0, 0, 0))
    }
    fn in_box(&mut self, half: f32) -> Vec3 {
        Vec3::new(self.f() - 0.5, self.f() - 0.5, self.f() - 0.5) * 2.0 * half
    }
}

fn random_scene(rng: &mut Rng) -> RenderScene {
    let mut shapes = Vec::new();
    // Two meshes of random triangles.
    for _ in 0..2 {
        let mut mesh = TriangleMesh::default();
        for t in 0..300u32 {
            let c = rng.in_box(10.0);
            for _ in 0..3 {
                mesh.positions.push(c + rng.in_box(1.5));
            }
            mesh.indices.push([3 * t, 3 * t + 1, 3 * t + 2]);
        }
        shapes.push(mesh);
    }
    let mut shapes: Vec<(Geometry, u32)> =
        shapes.into_iter().map(|m| (Geometry::Triangles(m), 0)).collect();
    // Quads (two triangles sharing an edge), axis-aligned and not.
    for q in 0..20 {
        let corner = rng.in_box(10.0);
        let (u, v) = if q % 2 == 0 {
            (Vec3::X * 3.0, Vec3::Z * 2.0)
        } else {
            (rng.in_box(2.0), rng.in_box(2.0))
        };
        let mesh = TriangleMesh::new(
            vec![corner, corner + u, corner + u + v, corner + v],
            vec![[0, 1, 2], [0, 2, 3]],
            None,
            None,
        );
        shapes.push((Geometry::Triangles(mesh), 0));
    }
    for _ in 0..15 {
        let sphere = Sphere { center: rng.in_box(10.0), radius: 0.2 + 1.5 * rng.f() };
        shapes.push((Geometry::Sphere(sphere), 0));
    }
    embray::compile::baked_scene(Camera::default(), shapes, vec![Material::default()])
}

fn brute_force(scene: &RenderScene, ray: &Ray) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    let mut tmax = ray.tmax;
    for (geom_id, shape) in scene
        .instances
        .iter()
        .enumerate()
        .map(|(i, inst)| (i, &scene.prototypes[inst.prototype as usize]))
    {
        match &shape.geometry {
            Geometry::Triangles(mesh) => {
                for prim in 0..mesh.indices.len() as u32 {
                    if let Some((t, u, v)) = intersect_triangle(
                        ray.origin,
                        ray.dir,
                        ray.tmin,
                        tmax,
                        &mesh.triangle(prim),
                    ) {
                        tmax = t;
                        best = Some(Hit { t, geom_id: geom_id as u32, prim_id: prim, u, v });
                    }
                }
            }
            Geometry::Sphere(s) => {
                if let Some(t) =
                    intersect_sphere(ray.origin, ray.dir, ray.tmin, tmax, s.center, s.radius)
                {
                    tmax = t;
                    best = Some(Hit { t, geom_id: geom_id as u32, prim_id: 0, u: 0.0, v: 0.0 });
                }
            }
            Geometry::SdfGrid(_) => unreachable!("no grids in these scenes"),
        }
    }
    best
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum RayKind {
    /// From anywhere to anywhere in the scene.
    Through,
    /// Leaving a triangle, spawned with the renderer's robust offset.
    FromSurface { geom_id: u32, prim_id: u32 },
    /// Aimed at the shared diagonal edge of a quad.
    AtSharedEdge,
}

fn random_rays(scene: &RenderScene, rng: &mut Rng, count: usize) -> Vec<(RayKind, Ray)> {
    let mut rays = Vec::with_capacity(count);
    for i in 0..count {
        let ray = match i % 3 {
            0 => {
                let (origin, target) = (rng.in_box(15.0), rng.in_box(10.0));
                (RayKind::Through, Ray::new(origin, target - origin, f32::INFINITY))
            }
            1 => {
                let geom_id = (i % 2) as u32;
                let Geometry::Triangles(mesh) = &scene.prototypes[geom_id as usize].geometry else {
                    unreachable!()
                };
                let prim_id = (rng.f() * 299.0) as u32;
                let tri = mesh.triangle(prim_id);
                let (b1, b2) = (rng.f() * 0.5, rng.f() * 0.5);
                let (point, error) = triangle_point(&tri, &TrianglePlane::new(&tri), b1, b2);
                let normal = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize();
                let surface = SurfacePoint { point, error, normal };
                let ray = surface.spawn_ray(rng.in_box(10.0) - point, 0.0);
                (RayKind::FromSurface { geom_id, prim_id }, ray)
            }
            _ => {
                let Geometry::Triangles(mesh) = &scene.prototypes[2 + i % 20].geometry else {
                    unreachable!()
                };
                let s = rng.f();
                let on_edge = mesh.positions[0] + (mesh.positions[2] - mesh.positions[0]) * s;
                let origin = rng.in_box(15.0);
                (RayKind::AtSharedEdge, Ray::new(origin, on_edge - origin, f32::INFINITY))
            }
        };
        rays.push(ray);
    }
    rays
}

fn same_hit(a: Option<Hit>, b: Option<Hit>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => (a.t - b.t).abs() <= 1e-4 * a.t.abs().max(1.0),
        _ => false,
    }
}

#[test]
fn backends_agree_with_linear_scan_on_random_rays() {
    let mut rng = Rng(0);
    let scene = random_scene(&mut rng);
    let rays = random_rays(&scene, &mut rng, 6000);
    let reference: Vec<Option<Hit>> = rays.iter().map(|(_, r)| brute_force(&scene, r)).collect();
    let hits = reference.iter().filter(|h| h.is_some()).count();
    assert!(hits > rays.len() / 4, "the rays must actually hit things: {hits}");
    for (backend, options) in every_build() {
        let accel = build(backend, &scene, &options).unwrap();
        let name = format!("{} {options:?}", backend.name());
        let mut counters = TraversalCounters::default();
        let (mut disagree, mut occluded_disagree, mut self_hits, mut edge_misses) = (0, 0, 0, 0);
        for ((kind, ray), expected) in rays.iter().zip(&reference) {
            let got = accel.intersect(ray, &mut counters);
            match kind {
                RayKind::Through => {
                    disagree += !same_hit(got, *expected) as usize;
                    occluded_disagree +=
                        (accel.occluded(ray, &mut counters) != expected.is_some()) as usize;
                }
                RayKind::FromSurface { geom_id, prim_id } => {
                    if got.is_some_and(|h| (h.geom_id, h.prim_id) == (*geom_id, *prim_id)) {
                        self_hits += 1;
                    }
                    disagree += !same_hit(got, *expected) as usize;
                }
                // The linear scan's Möller–Trumbore test may slip through the crack between
                // the two triangles; a watertight backend must not.
                RayKind::AtSharedEdge => edge_misses += (got.is_none()) as usize,
            }
        }
        println!(
            "{name}: {} rays, {hits} reference hits; {disagree} closest-hit and \
             {occluded_disagree} occlusion disagreements, {self_hits} self-intersections, \
             {edge_misses} rays through a shared edge that found nothing",
            rays.len()
        );
        // Every build agrees with the scan on every one of these rays (measured).
        assert_eq!(disagree, 0, "{name}: closest hits differ from the linear scan");
        assert_eq!(occluded_disagree, 0, "{name}: occlusion differs from the linear scan");
        assert_eq!(self_hits, 0, "{name}: spawned rays re-hit their own triangle");
        // Only the robust test promises not to; the fast one's leaks are what it saves on.
        if options.intersection == Intersection::Robust {
            assert_eq!(edge_misses, 0, "{name}: rays leaked through shared edges");
        }
    }
}

/// Every backend with every way it can be built: build quality × compact × counting mode
/// (compact changes only Embree's layout; the batch mode only how batches are traced), and
/// Embree's fast triangle test beside its robust one.
fn every_build() -> Vec<(BackendKind, AccelOptions)> {
    let mut all = Vec::new();
    for backend in backends() {
        let tests: &[Intersection] = match backend {
            BackendKind::Embree => Intersection::ALL,
            BackendKind::Obvhs => &[Intersection::Robust],
        };
        for &intersection in tests {
            for &build_quality in BuildQuality::ALL {
                for compact in [false, true] {
                    for count_traversal in [false, true] {
                        let options = AccelOptions {
                            build_quality,
                            compact,
                            count_traversal,
                            intersection,
                            ..AccelOptions::default()
                        };
                        all.push((backend, options));
                    }
                }
            }
        }
    }
    all
}

#[test]
fn invalid_rays_never_reach_a_backend() {
    let mut rng = Rng(5);
    let scene = random_scene(&mut rng);
    for backend in backends() {
        let accel = build(backend, &scene, &AccelOptions::default()).unwrap();
        let mut counters = TraversalCounters::default();
        for ray in [
            Ray::new(Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X, 1.0),
            Ray::new(Vec3::ZERO, Vec3::new(0.0, f32::INFINITY, 0.0), 1.0),
            Ray::new(Vec3::ZERO, Vec3::ZERO, 1.0),
            Ray { tmin: -1.0, ..Ray::new(Vec3::ZERO, Vec3::X, 1.0) },
        ] {
            assert!(accel.intersect(&ray, &mut counters).is_none());
            assert!(!accel.occluded(&ray, &mut counters));
        }
    }
}

#[test]
fn empty_scene_has_no_hits() {
    let scene = embray::compile::baked_scene(Camera::default(), Vec::new(), Vec::new());
    for backend in backends() {
        let accel = build(backend, &scene, &AccelOptions::default()).unwrap();
        let ray = Ray::new(Vec3::ZERO, Vec3::X, f32::INFINITY);
        assert!(accel.intersect(&ray, &mut TraversalCounters::default()).is_none());
    }
}
