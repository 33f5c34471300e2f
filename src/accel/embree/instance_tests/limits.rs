//! Instances the backend refuses, shutter times it clamps, and the memory instancing saves.

use super::*;

fn build_error(scene: &RenderScene) -> String {
    match EmbreeAccel::build(scene, &NORMAL) {
        Err(AccelError::Embree(msg)) => msg,
        Err(e) => panic!("unexpected error {e}"),
        Ok(_) => panic!("bad input was accepted"),
    }
}

#[test]
fn bad_instances_are_errors_naming_them() {
    let ball = || sphere(Vec3::ZERO, 1.0);
    let singular = Affine3A::from_scale(Vec3::new(1.0, 0.0, 1.0));
    let placement =
        Placement::Static { render_from_object: singular, object_from_render: singular };
    let msg = build_error(&one_instance(ball(), placement));
    assert!(msg.contains("instance 0 ('instance 0')") && msg.contains("singular"), "{msg}");
    let start = Trs { translation: Vec3::ZERO, rotation: Quat::IDENTITY, scale: Vec3::ONE };
    let flipped = Trs { scale: Vec3::new(-1.0, 1.0, 1.0), ..start };
    let msg = build_error(&one_instance(ball(), Placement::Moving { start, end: flipped }));
    assert!(msg.contains("changes sign"), "{msg}");
    let nan = Trs { translation: Vec3::new(f32::NAN, 0.0, 0.0), ..start };
    let msg = build_error(&one_instance(ball(), Placement::Moving { start, end: nan }));
    assert!(msg.contains("not finite"), "{msg}");
    // A broken shared prototype is named as well as the instance that needed it.
    let broken = mesh(vec![Vec3::ZERO, Vec3::X, Vec3::Y], vec![[0, 1, 7]]);
    let msg = build_error(&one_instance(broken, static_placement(&start)));
    assert!(msg.contains("prototype 0 ('thing')") && msg.contains("vertex 7"), "{msg}");
    let mut scene = one_instance(ball(), static_placement(&start));
    scene.instances[0].prototype = 5;
    assert!(build_error(&scene).contains("prototype 5 does not exist"));
}

/// Times outside the shutter interval are clamped to it: Debian's Embree would abort the
/// process on them (an assertion in its motion-BVH traversal).
#[test]
fn times_outside_the_shutter_are_clamped() {
    let (scene, _) = instanced_scene(true);
    let accel = EmbreeAccel::build(&scene, &NORMAL).unwrap();
    let mut c = TraversalCounters::default();
    let mut hits = 0;
    for (k, ray) in instanced_rays(2000).into_iter().enumerate() {
        let (outside, clamped) = [(-1.0, 0.0), (2.0, 1.0), (1e30, 1.0), (-1e30, 0.0)][k % 4];
        let inside = Ray { time: clamped, ..ray };
        let ray = Ray { time: outside, ..ray };
        let hit = accel.intersect(&ray, &mut c);
        assert_eq!(hit, accel.intersect(&inside, &mut c), "{ray:?}");
        assert_eq!(accel.occluded(&ray, &mut c), accel.occluded(&inside, &mut c), "{ray:?}");
        hits += usize::from(hit.is_some());
    }
    assert!(hits > 200, "{hits}");
}

/// 10,000 static instances of one 10k-triangle mesh cost a small fraction of 10,000 copies:
/// the prototype is built once and each instance adds a transform and a top-level entry.
#[test]
fn instances_share_their_prototype() {
    const INSTANCES: usize = 10_000;
    const COPIES_MEASURED: usize = 20;
    let terrain = grid(71); // 10,082 triangles
    let triangles = match &terrain {
        render_scene::Geometry::Triangles(m) => m.indices.len(),
        render_scene::Geometry::Sphere(_) | render_scene::Geometry::SdfGrid(_) => unreachable!(),
    };
    // Warm up: Embree's thread pool and first allocations are not the instances' cost.
    drop(EmbreeAccel::build(&crate::accel::embree::test_scenes::random_scene(), &NORMAL).unwrap());
    // What one copy costs: a scene of baked copies.
    let copies = crate::accel::embree::test_scenes::render_scene(
        (0..COPIES_MEASURED).map(|i| shape(&format!("copy {i}"), terrain.clone())).collect(),
    );
    // Bytes as Embree's memory monitor counts them for each build's own device: exact, and
    // untouched by what other tests running alongside allocate.
    let accel = EmbreeAccel::build(&copies, &NORMAL).unwrap();
    let per_copy_measured = accel.memory_bytes().unwrap() as u64 / COPIES_MEASURED as u64;
    drop(accel);
    drop(copies);
    // At least the vertex and index buffers Embree copies.
    assert!(per_copy_measured >= 24 * triangles as u64, "{per_copy_measured} bytes per copy");
    let per_copy = per_copy_measured;

    let mut rng = Rng(5);
    let mut scene = crate::accel::embree::test_scenes::render_scene(Vec::new());
    let p = add_prototype(&mut scene, "terrain", terrain);
    for _ in 0..INSTANCES {
        add_instance(&mut scene, p, static_placement(&random_trs(&mut rng, 500.0)));
    }
    let accel = EmbreeAccel::build(&scene, &NORMAL).unwrap();
    let growth = accel.memory_bytes().unwrap() as u64;
    let copies_would_take = per_copy * INSTANCES as u64;
    let mib = |b: u64| b as f64 / (1024.0 * 1024.0);
    println!(
        "{INSTANCES} instances of a {triangles}-triangle mesh take {:.1} MiB ({} bytes per \
         instance); one copy costs {:.2} MiB (measured over {COPIES_MEASURED} copies), so \
         {INSTANCES} copies would take {:.0} MiB: instancing needs {:.2} % of that",
        mib(growth),
        growth / INSTANCES as u64,
        mib(per_copy_measured),
        mib(copies_would_take),
        100.0 * growth as f64 / copies_would_take as f64
    );
    // Measured 0.02 %.
    assert!(growth * 1000 < copies_would_take, "{growth} bytes vs {copies_would_take}");
    // And the instances are really there: a ray at instance `i`'s centre hits instance `i`
    // or one overlapping it.
    let mut c = TraversalCounters::default();
    let mut hits = 0;
    for (i, instance) in scene.instances.iter().enumerate().step_by(97) {
        let centre = instance
            .placement
            .render_from_object(0.0)
            .unwrap()
            .transform_point3(Vec3::new(0.0, 0.0, 0.3));
        let ray = Ray::new(centre + Vec3::new(0.0, 0.0, 50.0), Vec3::NEG_Z, f32::INFINITY);
        if let Some(Hit { geom_id, .. }) = accel.intersect(&ray, &mut c) {
            hits += usize::from(geom_id as usize == i);
        }
    }
    assert!(hits > 50, "{hits} of {} probes hit their instance", INSTANCES / 97 + 1);
}
