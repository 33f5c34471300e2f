//! Batched queries against single-ray ones.

use super::{BatchKind, EmbreeAccel};
use crate::accel::{Accel, AccelOptions, Hit, Ray};
use crate::bench::{procedural, speed};
use crate::render::{RenderOptions, prepare_scene};
use crate::render_scene::RenderScene;
use std::time::Instant;

fn scene_of(desc: &crate::scene::SceneDesc) -> RenderScene {
    prepare_scene(desc, &RenderOptions::for_scene(desc)).unwrap()
}

fn differences(a: &[Option<Hit>], b: &[Option<Hit>]) -> usize {
    a.iter().zip(b).filter(|(x, y)| x.map(bits) != y.map(bits)).count()
}

fn bits(h: Hit) -> (u32, u32, u32, u32, u32) {
    (h.t.to_bits(), h.geom_id, h.prim_id, h.u.to_bits(), h.v.to_bits())
}

const KINDS: [BatchKind; 6] = [
    BatchKind::Single,
    BatchKind::Packet4,
    BatchKind::Packet8,
    BatchKind::Packet16,
    BatchKind::StreamCoherent,
    BatchKind::StreamIncoherent,
];

#[test]
#[ignore = "measurement; run with --release --ignored --nocapture"]
fn batch_kinds_experiment() {
    let cornell = crate::scene::load(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cornell.toml").as_path(),
    )
    .unwrap();
    let moving = crate::scene::load(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/moving_boxes.toml").as_path(),
    )
    .unwrap();
    let scenes = [
        ("moving", moving),
        ("cornell", cornell),
        ("sphere_100k", procedural::displaced_sphere_scene(100_000, 512, 512)),
        ("sphere_1M", procedural::displaced_sphere_scene(1_000_000, 512, 512)),
    ];
    for (name, desc) in scenes {
        let mut desc = desc;
        desc.camera.width = 512;
        desc.camera.height = 512;
        let scene = scene_of(&desc);
        let accel = EmbreeAccel::build(&scene, &AccelOptions::default()).unwrap();
        let mut primary = speed::primary_rays(&scene);
        for (i, r) in primary.iter_mut().enumerate() {
            r.time = (i % 17) as f32 / 16.0;
        }
        let diffuse = speed::diffuse_rays(&scene, &accel, &primary);
        for (kind_name, rays) in [("primary", &primary), ("diffuse", &diffuse)] {
            // Tile order: 16x16 tiles of the image for primary rays.
            let reference = speed::single_hits(&accel, rays);
            let mut hits = vec![None; rays.len()];
            for round in 0..3 {
                let mut line = format!("{name} {kind_name} round {round}:");
                let start = Instant::now();
                let n = accel.raw_intersect_loop(rays);
                std::hint::black_box(n);
                line +=
                    &format!(" raw {:.2}", rays.len() as f64 / start.elapsed().as_secs_f64() / 1e6);
                let start = Instant::now();
                let mut c = Default::default();
                let n = rays.iter().filter(|r| accel.intersect(r, &mut c).is_some()).count();
                std::hint::black_box(n);
                line += &format!(
                    " wrapper {:.2}",
                    rays.len() as f64 / start.elapsed().as_secs_f64() / 1e6
                );
                for kind in KINDS {
                    let start = Instant::now();
                    for chunk in (0..rays.len()).step_by(1024) {
                        let end = (chunk + 1024).min(rays.len());
                        accel.intersect_batch_with(kind, &rays[chunk..end], &mut hits[chunk..end]);
                    }
                    let rate = rays.len() as f64 / start.elapsed().as_secs_f64() / 1e6;
                    line +=
                        &format!(" {kind:?} {rate:.2} ({} diff)", differences(&hits, &reference));
                    if round == 0 {
                        for (i, (a, b)) in hits.iter().zip(&reference).enumerate() {
                            if a.map(bits) != b.map(bits) {
                                println!(
                                    "  {kind:?} ray {i} {:?}: batch {a:?} single {b:?}",
                                    rays[i]
                                );
                            }
                        }
                    }
                }
                println!("{line}");
            }
        }
    }
}

#[allow(dead_code)]
fn unused(_: &dyn Accel, _: &Ray) {}
