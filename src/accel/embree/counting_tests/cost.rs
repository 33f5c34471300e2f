//! What counting mode costs in time (an ignored test, run by hand with `--ignored`).

use super::*;

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
                shape(&m.name, crate::accel::embree::test_scenes::mesh(positions, indices))
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
