//! Counting mode (`AccelOptions::count_traversal`): same hits as normal mode, faithful and
//! deterministic primitive-test counts, and (ignored by default) what counting costs.

use super::EmbreeAccel;
use super::tests::{
    Rng, close, grid, is_graze, is_sphere, random_rays, random_scene, render_scene, shape, sphere,
};
use crate::accel::{Accel, AccelOptions, Observes};
use crate::ray::Ray;
use crate::render_scene::{self, RenderScene};
use crate::stats::TraversalCounters;
use glam::Vec3;

const NORMAL: AccelOptions = AccelOptions { count_traversal: false, ..AccelOptions::DEFAULT };
const COUNTING: AccelOptions = AccelOptions { count_traversal: true, ..AccelOptions::DEFAULT };

/// Primitive tests of each ray: (closest-hit query, occlusion query).
fn per_ray_counts(accel: &dyn Accel, rays: &[Ray]) -> Vec<(u64, u64)> {
    rays.iter()
        .map(|ray| {
            let mut hit = TraversalCounters::default();
            accel.intersect(ray, &mut hit);
            let mut shadow = TraversalCounters::default();
            accel.occluded(ray, &mut shadow);
            assert_eq!(
                (hit.node_visits, shadow.node_visits),
                (0, 0),
                "node visits are not observed"
            );
            (hit.prim_tests, shadow.prim_tests)
        })
        .collect()
}

#[test]
fn observes_primitive_tests_only_in_counting_mode() {
    let scene = random_scene();
    let normal = EmbreeAccel::build(&scene, &NORMAL).unwrap();
    let counting = EmbreeAccel::build(&scene, &COUNTING).unwrap();
    assert_eq!(normal.observes(), Observes::default());
    assert_eq!(counting.observes(), Observes { node_visits: false, prim_tests: true });
    // Normal mode leaves the counters alone, spheres (user geometry there too) included.
    let mut c = TraversalCounters::default();
    for ray in random_rays(500) {
        normal.intersect(&ray, &mut c);
        normal.occluded(&ray, &mut c);
    }
    assert_eq!(c, TraversalCounters::default());
}

#[test]
fn counting_mode_hits_match_normal_mode() {
    let scene = random_scene();
    let normal = EmbreeAccel::build(&scene, &NORMAL).unwrap();
    let counting = EmbreeAccel::build(&scene, &COUNTING).unwrap();
    let rays = random_rays(4000);
    let mut c = TraversalCounters::default();
    let (mut same, mut grazes, mut shadow_grazes) = (0, 0, 0);
    for (k, ray) in rays.iter().enumerate() {
        let (n, m) = (normal.intersect(ray, &mut c), counting.intersect(ray, &mut c));
        match (n, m) {
            (Some(n), Some(m)) if (n.geom_id, n.prim_id) == (m.geom_id, m.prim_id) => {
                same += 1;
                if is_sphere(&scene, &n) {
                    // The same callback code in both modes: identical bits.
                    assert_eq!(n, m, "ray {k}");
                } else {
                    assert!(close(m.t, n.t), "ray {k}: t {n:?} vs {m:?}");
                    assert!((n.u - m.u).abs() < 1e-3 && (n.v - m.v).abs() < 1e-3, "ray {k}");
                }
            }
            (None, None) => {}
            (n, m) if is_graze(&scene, ray, n, m) => grazes += 1,
            (n, m) => panic!("ray {k} {ray:?}: normal {n:?}, counting {m:?}"),
        }
        if normal.occluded(ray, &mut c) != counting.occluded(ray, &mut c) {
            assert!(is_graze(&scene, ray, n, m), "ray {k} {ray:?}: occlusion differs");
            shadow_grazes += 1;
        }
    }
    assert!(same > 1500, "too few hits to mean anything: {same}");
    assert!(grazes * 1000 < rays.len(), "{grazes} grazing disagreements");
    assert!(shadow_grazes * 1000 < rays.len(), "{shadow_grazes} grazing disagreements");
    assert!(c.prim_tests > 0);
}

#[test]
fn counts_are_nonzero_and_deterministic() {
    let scene = random_scene();
    let accel = EmbreeAccel::build(&scene, &COUNTING).unwrap();
    let rays = random_rays(3000);
    let first = per_ray_counts(&accel, &rays);
    assert_eq!(per_ray_counts(&accel, &rays), first, "same rays, same accel");
    let rebuilt = EmbreeAccel::build(&scene, &COUNTING).unwrap();
    assert_eq!(per_ray_counts(&rebuilt, &rays), first, "same rays, rebuilt accel");
    // Every hit took at least one test; the totals are far from zero. (A shadow ray may
    // take more tests than the closest-hit query of the same ray: Embree's occlusion
    // traversal orders children differently and stops only at an occluder.)
    let mut c = TraversalCounters::default();
    for (ray, &(hit_tests, shadow_tests)) in rays.iter().zip(&first) {
        if accel.intersect(ray, &mut c).is_some() {
            assert!(hit_tests >= 1 && shadow_tests >= 1, "{ray:?}");
        }
    }
    let total: u64 = first.iter().map(|&(h, _)| h).sum();
    assert!(total > rays.len() as u64, "{total} tests for {} rays", rays.len());

    // Per-thread counters, merged at the end, give the serial totals.
    let serial = rays.iter().fold(TraversalCounters::default(), |mut c, ray| {
        accel.intersect(ray, &mut c);
        accel.occluded(ray, &mut c);
        c
    });
    let serial_total: u64 = first.iter().map(|&(h, s)| h + s).sum();
    assert_eq!(serial.prim_tests, serial_total);
    let merged = std::thread::scope(|s| {
        let workers: Vec<_> = rays
            .chunks(rays.len() / 4 + 1)
            .map(|chunk| {
                let accel = &accel;
                s.spawn(move || {
                    let mut c = TraversalCounters::default();
                    for ray in chunk {
                        accel.intersect(ray, &mut c);
                        accel.occluded(ray, &mut c);
                    }
                    c
                })
            })
            .collect();
        workers.into_iter().fold(TraversalCounters::default(), |mut total, w| {
            total += w.join().unwrap();
            total
        })
    });
    assert_eq!(merged, serial);
}

#[test]
fn sphere_tests_are_counted() {
    // Spheres only, on a line along x, 3 apart: their boxes do not overlap.
    let shapes = (0..8)
        .map(|i| shape(&format!("ball {i}"), sphere(Vec3::new(3.0 * i as f32, 0.0, 0.0), 1.0)))
        .collect();
    let scene = render_scene(shapes);
    let accel = EmbreeAccel::build(&scene, &COUNTING).unwrap();
    for i in 0..8 {
        // Straight down through sphere `i`: it is tested (and hit); at most its leaf-mates
        // are tested besides.
        let ray = Ray::new(Vec3::new(3.0 * i as f32, 5.0, 0.0), Vec3::NEG_Y, f32::INFINITY);
        let mut c = TraversalCounters::default();
        let hit = accel.intersect(&ray, &mut c).expect("hits the sphere below");
        assert_eq!((hit.geom_id, hit.t), (i, 4.0));
        assert!((1..8).contains(&c.prim_tests), "sphere {i}: {c:?}");
        let mut shadow = TraversalCounters::default();
        assert!(accel.occluded(&ray, &mut shadow));
        assert!(shadow.prim_tests >= 1, "sphere {i}: {shadow:?}");
    }
    // Between two spheres, parallel to them: nothing is hit.
    let between = Ray::new(Vec3::new(1.5, 5.0, 0.0), Vec3::NEG_Y, f32::INFINITY);
    let mut c = TraversalCounters::default();
    assert!(accel.intersect(&between, &mut c).is_none() && !accel.occluded(&between, &mut c));
    // A mixed scene counts sphere tests too: random rays that hit a sphere were counted.
    let scene = random_scene();
    let accel = EmbreeAccel::build(&scene, &COUNTING).unwrap();
    let mut sphere_hits = 0;
    for ray in random_rays(1000) {
        let mut c = TraversalCounters::default();
        if let Some(hit) = accel.intersect(&ray, &mut c).filter(|h| is_sphere(&scene, h)) {
            assert!(c.prim_tests >= 1, "{ray:?} {hit:?}");
            sphere_hits += 1;
        }
    }
    assert!(sphere_hits > 50, "{sphere_hits}");
}

/// Whether the ray's segment `[t0, t1]` meets the box `[lo, hi]` (slab test in f64).
fn segment_meets_box(ray: &Ray, (lo, hi): (Vec3, Vec3), t0: f32, t1: f32) -> bool {
    let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
    let (mut t0, mut t1) = (f64::from(t0), f64::from(t1));
    for a in 0..3 {
        let (lo, hi) = (f64::from(lo[a]), f64::from(hi[a]));
        if d[a] == 0.0 {
            if o[a] < lo || o[a] > hi {
                return false;
            }
            continue;
        }
        let (near, far) = ((lo - o[a]) / d[a], (hi - o[a]) / d[a]);
        t0 = t0.max(near.min(far));
        t1 = t1.min(near.max(far));
    }
    t0 <= t1
}

/// What the count means: Embree puts each user primitive in a leaf of its own here, so a
/// ray tests at least every primitive whose box it enters before its closest hit (those
/// boxes are tested against a `tfar` no nearer than the hit), and at most every primitive
/// whose box it enters anywhere in `[tmin, tmax]`.
#[test]
fn counts_lie_between_boxes_before_the_hit_and_boxes_on_the_ray() {
    let scene = random_scene();
    let accel = EmbreeAccel::build(&scene, &COUNTING).unwrap();
    let boxes: Vec<(Vec3, Vec3)> = scene
        .prototypes
        .iter()
        .flat_map(|p| match &p.geometry {
            render_scene::Geometry::Triangles(m) => (0..m.indices.len() as u32)
                .map(|p| {
                    let [a, b, c] = m.triangle(p);
                    (a.min(b).min(c), a.max(b).max(c))
                })
                .collect(),
            render_scene::Geometry::Sphere(s) => vec![(s.center - s.radius, s.center + s.radius)],
        })
        .collect();
    let rays = random_rays(4000);
    let (mut outside, mut at_lower_bound) = (0, 0);
    for ray in &rays {
        let mut c = TraversalCounters::default();
        let end = accel.intersect(ray, &mut c).map_or(ray.tmax, |h| h.t);
        let count = |t1| boxes.iter().filter(|&&b| segment_meets_box(ray, b, ray.tmin, t1)).count();
        let (lower, upper) = (count(end) as u64, count(ray.tmax) as u64);
        outside += usize::from(c.prim_tests < lower || c.prim_tests > upper);
        at_lower_bound += usize::from(c.prim_tests == lower);
    }
    // Embree's box test is conservative in f32, ours exact in f64: allow a few borderline
    // boxes (none were seen with Embree 3.13.5).
    assert!(outside * 1000 <= rays.len(), "{outside} rays outside the bounds");
    println!("{at_lower_bound} of {} rays tested exactly the boxes before their hit", rays.len());
}

/// Counting mode and obvhs run the same triangle and sphere tests on the same rays: where
/// they report the same primitive, the hit is identical to the bit.
#[cfg(feature = "obvhs")]
#[test]
fn counting_mode_matches_obvhs_and_counts_comparably() {
    use crate::accel::obvhs::ObvhsAccel;
    let scene = random_scene();
    let embree = EmbreeAccel::build(&scene, &COUNTING).unwrap();
    let obvhs = ObvhsAccel::build(&scene, &COUNTING);
    let rays = random_rays(4000);
    let (mut ce, mut co) = (TraversalCounters::default(), TraversalCounters::default());
    let (mut same, mut grazes) = (0, 0);
    for (k, ray) in rays.iter().enumerate() {
        let (e, o) = (embree.intersect(ray, &mut ce), obvhs.intersect(ray, &mut co));
        match (e, o) {
            (Some(e), Some(o)) if (e.geom_id, e.prim_id) == (o.geom_id, o.prim_id) => {
                assert_eq!(e, o, "ray {k}");
                same += 1;
            }
            (None, None) => {}
            (e, o) if is_graze(&scene, ray, e, o) => grazes += 1,
            (e, o) => panic!("ray {k} {ray:?}: embree {e:?}, obvhs {o:?}"),
        }
    }
    assert!(same > 1500 && grazes * 1000 < rays.len(), "{same} same, {grazes} grazes");
    let per_ray = |c: TraversalCounters| c.prim_tests as f64 / rays.len() as f64;
    let (e, o) = (per_ray(ce), per_ray(co));
    println!(
        "primitive tests per closest-hit ray, {} triangles + 2 spheres: Embree user-geometry \
         BVH {e:.2}, obvhs {o:.2} (obvhs also {:.2} node visits)",
        count_triangles(&scene),
        co.node_visits as f64 / rays.len() as f64
    );
    assert!(e > 0.2 * o && e < 5.0 * o, "embree {e}, obvhs {o}");
}

fn count_triangles(scene: &RenderScene) -> usize {
    scene
        .prototypes
        .iter()
        .map(|p| match &p.geometry {
            render_scene::Geometry::Triangles(m) => m.indices.len(),
            render_scene::Geometry::Sphere(_) => 0,
        })
        .sum()
}

/// The mesh for the cost measurement: the 100k-triangle dragon from the shared data if it is
/// there, else a 100k-triangle height field.
fn cost_scene() -> (RenderScene, String) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data/models/dragon-100k.obj");
    let options = tobj::LoadOptions { triangulate: true, ..Default::default() };
    if let Ok((models, _)) = tobj::load_obj(path, &options) {
        let shapes = models
            .iter()
            .map(|m| {
                let p = &m.mesh.positions;
                let positions = p.chunks(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect();
                let i = &m.mesh.indices;
                let indices = i.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
                shape(&m.name, super::tests::mesh(positions, indices))
            })
            .collect();
        return (render_scene(shapes), "dragon-100k.obj".into());
    }
    (render_scene(vec![shape("grid", grid(224))]), "224x224 height field".into())
}

/// Rays from a sphere around the scene's bounds towards random points inside them.
fn cost_rays(scene: &RenderScene, count: usize) -> Vec<Ray> {
    let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    for p in &scene.prototypes {
        if let render_scene::Geometry::Triangles(m) = &p.geometry {
            for &p in &m.positions {
                (lo, hi) = (lo.min(p), hi.max(p));
            }
        }
    }
    let (center, radius) = ((lo + hi) / 2.0, (hi - lo).length());
    let mut rng = Rng(5);
    (0..count)
        .map(|_| {
            let origin = center + radius * rng.vec3(-1.0, 1.0).normalize_or(Vec3::X);
            let target = lo + (hi - lo) * rng.vec3(0.0, 1.0);
            Ray::new(origin, target - origin, f32::INFINITY)
        })
        .collect()
}

/// One pass of closest-hit queries and one of occlusion queries over `rays`.
struct Pass {
    hit_seconds: f64,
    shadow_seconds: f64,
    hit_counters: TraversalCounters,
    shadow_counters: TraversalCounters,
    hits: usize,
}

fn time_pass(accel: &dyn Accel, rays: &[Ray]) -> Pass {
    let mut hit_counters = TraversalCounters::default();
    let start = std::time::Instant::now();
    let hits = rays.iter().filter(|r| accel.intersect(r, &mut hit_counters).is_some()).count();
    let hit_seconds = start.elapsed().as_secs_f64();
    let mut shadow_counters = TraversalCounters::default();
    let start = std::time::Instant::now();
    let occluded = rays.iter().filter(|r| accel.occluded(r, &mut shadow_counters)).count();
    let shadow_seconds = start.elapsed().as_secs_f64();
    Pass { hit_seconds, shadow_seconds, hit_counters, shadow_counters, hits: hits.max(occluded) }
}

/// What counting costs: 200k random rays into a ~100k-triangle mesh, one thread, normal vs
/// counting mode alternating (the machines are noisy). Run with
/// `cargo test --release --lib counting_cost -- --ignored --nocapture`.
#[test]
#[ignore = "a measurement, not a test: run explicitly"]
fn counting_cost() {
    let (scene, name) = cost_scene();
    let rays = cost_rays(&scene, 200_000);
    type Build = Box<dyn Fn() -> Box<dyn Accel>>;
    let mut builders: Vec<(&str, Build)> = Vec::new();
    for (label, options) in [("embree normal", NORMAL), ("embree counting", COUNTING)] {
        let scene = scene.clone();
        builders.push((
            label,
            Box::new(move || Box::new(EmbreeAccel::build(&scene, &options).unwrap())),
        ));
    }
    #[cfg(feature = "obvhs")]
    for (label, options) in [("obvhs normal", NORMAL), ("obvhs counting", COUNTING)] {
        let scene = scene.clone();
        builders.push((
            label,
            Box::new(move || Box::new(crate::accel::obvhs::ObvhsAccel::build(&scene, &options))),
        ));
    }
    const ROUNDS: usize = 7;
    let mut build_seconds = vec![Vec::new(); builders.len()];
    let mut accels = Vec::new();
    for _ in 0..3 {
        accels.clear();
        for ((_, build), seconds) in builders.iter().zip(&mut build_seconds) {
            let start = std::time::Instant::now();
            accels.push(build());
            seconds.push(start.elapsed().as_secs_f64());
        }
    }
    let mut times = vec![(Vec::new(), Vec::new()); accels.len()];
    let mut passes = Vec::new();
    for _ in 0..ROUNDS {
        passes.clear();
        for (accel, (hit_times, shadow_times)) in accels.iter().zip(&mut times) {
            let pass = time_pass(accel.as_ref(), &rays);
            hit_times.push(pass.hit_seconds);
            shadow_times.push(pass.shadow_seconds);
            passes.push(pass);
        }
    }
    let n = rays.len() as f64;
    println!(
        "{name}, {} triangles, {} rays, queries on 1 thread (builds on all), median of {ROUNDS}:",
        count_triangles(&scene),
        rays.len()
    );
    let medians: Vec<(f64, f64)> = times
        .into_iter()
        .map(|(h, s)| (crate::bench::median(h), crate::bench::median(s)))
        .collect();
    for (((label, _), &(h, s)), (pass, build)) in
        builders.iter().zip(&medians).zip(passes.iter().zip(build_seconds))
    {
        println!(
            "  {label:16} build {:5.3} s; closest hit {:5.2} Mrays/s ({:.2} prim tests, {:.2} \
             node visits per ray); occlusion {:5.2} Mrays/s ({:.2} prim tests, {:.2} node \
             visits per ray); {} hits",
            crate::bench::median(build),
            n / h / 1e6,
            pass.hit_counters.prim_tests as f64 / n,
            pass.hit_counters.node_visits as f64 / n,
            n / s / 1e6,
            pass.shadow_counters.prim_tests as f64 / n,
            pass.shadow_counters.node_visits as f64 / n,
            pass.hits,
        );
    }
    let (normal, counting) = (medians[0], medians[1]);
    println!(
        "  Embree counting-mode slowdown: closest hit {:.2}x, occlusion {:.2}x",
        counting.0 / normal.0,
        counting.1 / normal.1
    );
}
