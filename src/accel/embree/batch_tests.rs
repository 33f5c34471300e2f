//! Embree's batched entry points against its single-ray one, and the raw loop.
//! (`tests/batch_queries.rs` checks `Accel::intersect_batch` itself, for every backend.)

use super::{BatchKind, EmbreeAccel};
use crate::accel::{Accel, AccelOptions};
use crate::bench::{procedural, speed};
use crate::ray::{Hit, Ray};
use crate::render::{RenderOptions, prepare_scene};
use crate::render_scene::RenderScene;
use crate::scene::SceneDesc;
use crate::stats::TraversalCounters;
use std::time::Instant;

fn render_scene(desc: &SceneDesc) -> RenderScene {
    prepare_scene(desc, &RenderOptions::for_scene(desc)).expect("scene converts")
}

fn bundled(name: &str) -> SceneDesc {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes").join(name);
    crate::scene::load(&path).expect("bundled scene loads")
}

fn bits(h: Hit) -> (u32, u32, u32, u32, u32) {
    (h.t.to_bits(), h.geom_id, h.prim_id, h.u.to_bits(), h.v.to_bits())
}

fn differences(a: &[Option<Hit>], b: &[Option<Hit>]) -> usize {
    a.iter().zip(b).filter(|(x, y)| x.map(bits) != y.map(bits)).count()
}

#[test]
fn raw_loop_counts_the_hits_of_intersect() {
    let scene = render_scene(&procedural::displaced_sphere_scene(2000, 24, 16));
    let accel = EmbreeAccel::build(&scene, &AccelOptions::default()).unwrap();
    let rays = speed::primary_rays(&scene);
    let hits = speed::single_hits(&accel, &rays).iter().filter(|h| h.is_some()).count();
    assert!(hits > 0 && hits < rays.len());
    assert_eq!(accel.raw_intersect_loop(&rays), hits);
}

#[test]
#[should_panic(expected = "a ray Embree rejects")]
fn raw_loop_refuses_rays_embree_would_abort_on() {
    let scene = render_scene(&procedural::displaced_sphere_scene(12, 4, 4));
    let accel = EmbreeAccel::build(&scene, &AccelOptions::default()).unwrap();
    accel.raw_intersect_loop(&[Ray::new(glam::Vec3::ZERO, glam::Vec3::NAN, 1.0)]);
}

/// How each of Embree's batched entry points compares with `rtcIntersect1`, in speed (one
/// thread, Mrays/s) and in hits (how many differ from the single-ray ones), on 512×512
/// camera rays (with shutter times, for the moving scene) and the bounces from their hits.
/// The measurements behind `BatchMode` (see `EmbreeAccel::intersect_batch`).
#[test]
#[ignore = "measurement: cargo test --release --lib batch_kinds -- --ignored --nocapture"]
fn batch_kinds_speed_and_differences() {
    const KINDS: [BatchKind; 6] = [
        BatchKind::Single,
        BatchKind::Packet4,
        BatchKind::Packet8,
        BatchKind::Packet16,
        BatchKind::StreamCoherent,
        BatchKind::StreamIncoherent,
    ];
    let scenes = [
        ("moving_boxes", bundled("moving_boxes.toml")),
        ("cornell", bundled("cornell.toml")),
        ("sphere_100k", procedural::displaced_sphere_scene(100_000, 512, 512)),
        ("sphere_1m", procedural::displaced_sphere_scene(1_000_000, 512, 512)),
    ];
    for (name, mut desc) in scenes {
        desc.camera.width = 512;
        desc.camera.height = 512;
        let scene = render_scene(&desc);
        let accel = EmbreeAccel::build(&scene, &AccelOptions::default()).unwrap();
        let mut primary = speed::primary_rays(&scene);
        for (i, r) in primary.iter_mut().enumerate() {
            r.time = (i % 17) as f32 / 16.0;
        }
        let diffuse = speed::diffuse_rays(&scene, &accel, &primary);
        for (kind_name, rays) in [("primary", &primary), ("diffuse", &diffuse)] {
            let reference = speed::single_hits(&accel, rays);
            let mut hits = vec![None; rays.len()];
            let rate = |start: Instant| rays.len() as f64 / start.elapsed().as_secs_f64() / 1e6;
            for round in 0..3 {
                let mut line = format!("{name} {kind_name} round {round}:");
                let start = Instant::now();
                std::hint::black_box(accel.raw_intersect_loop(rays));
                line += &format!(" raw {:.2}", rate(start));
                let start = Instant::now();
                let mut counters = TraversalCounters::default();
                let n = rays.iter().filter(|r| accel.intersect(r, &mut counters).is_some());
                std::hint::black_box(n.count());
                line += &format!(" intersect {:.2}", rate(start));
                for kind in KINDS {
                    let start = Instant::now();
                    for (r, h) in rays.chunks(1024).zip(hits.chunks_mut(1024)) {
                        accel.intersect_batch_with(kind, r, h);
                    }
                    let speed = rate(start);
                    let diff = differences(&hits, &reference);
                    line += &format!(" {kind:?} {speed:.2} ({diff} differ)");
                }
                println!("{line}");
            }
        }
    }
}
