//! Lanes written as a lone-emitter scene's paths write them, without the columns the loop
//! sets itself (`POINT_UNWRITTEN`, `LONE_UNWRITTEN`), over columns that all hold NaN.

use super::*;
use crate::integrator::path::lambert::LaneSink;

/// The bits of what `finish_lambert` reads of an outcome: its point and flags, and the
/// shadow ray's and the next ray's fields where it takes them.
fn read_bits(outcome: &LambertOutcome) -> Vec<u32> {
    let o = outcome;
    let mut read = vec![o.point, Vec3::new(o.shadow, o.next, o.near)];
    if o.shadow != 0.0 {
        read.extend([o.shadow_origin, o.shadow_dir, o.contribution, Vec3::splat(o.shadow_tmax)]);
    }
    if o.next != 0.0 {
        read.extend([o.next_origin, o.next_dir, o.throughput, Vec3::splat(o.pdf)]);
    }
    read.iter().flat_map(|v| v.to_array()).map(f32::to_bits).collect()
}

#[test]
fn columns_left_unwritten_reach_no_result_that_is_read() {
    let spaces = spaces();
    let mut rng = SplitMix64(23);
    let poison = LambertLane::read_at(&[[f32::NAN; CHUNK]; IN], 0);
    for two_sided in [true, false] {
        let emitter = lone_rectangle(two_sided);
        let mut queue = LambertLanes::default();
        let count = 8 * CHUNK + 5;
        for i in 0..count {
            queue.push(i as u32, &poison);
        }
        queue.clear();
        // As `points_and_lights_left_to_the_vector_loop_...`, every light left to the loop.
        let lanes: Vec<LambertLane> = (0..count)
            .map(|_| {
                let mut lane = random_lane(&mut rng);
                let center = [Vec3::ZERO, Vec3::new(0.0, 26.0, 0.0), Vec3::new(0.0, 40.0, 0.0)]
                    [(rng.next_u64() % 3) as usize];
                if rng.unit() < 0.8 {
                    lane = on_triangle_lane(&mut rng, &lane, center);
                }
                (lane.light_kind, lane.has_light) = (LONE, 0.0);
                (lane.light_point, lane.light_normal) =
                    lone_draw_fields([(); 4].map(|_| rng.unit()));
                lane
            })
            .collect();
        let unwritten = |lane: &LambertLane| {
            LONE_UNWRITTEN | if lane.on_triangle != 0.0 { POINT_UNWRITTEN } else { 0 }
        };
        for (i, lane) in lanes.iter().enumerate() {
            queue.next_lane().put(*lane, unwritten(lane));
            queue.commit(i as u32);
        }
        queue.run(&spaces, Some(&emitter), true);
        let (mut lit, mut near, mut unlit) = (0, 0, 0);
        for (i, (lane, (_, _, outcome))) in lanes.iter().zip(queue.outcomes()).enumerate() {
            let single = with_lone_light(&with_hit_point(lane), &emitter.sampler);
            if single.light_kind == NEAR {
                // `lambert_outcome` computes it again from the queued lane, setting the
                // point and bound (on a triangle) and the light's fields but for its draw
                // before it reads them: the rest must be the lane's.
                assert_eq!(outcome.near(), 1.0, "lane {i}");
                let set_again = |mut l: LambertLane| {
                    (l.has_light, l.light_pdf, l.light_visible, l.light_two_sided) =
                        (0.0, 0.0, 0.0, 0.0);
                    (l.light_error, l.emission) = (Vec3::ZERO, Vec3::ZERO);
                    if lane.on_triangle != 0.0 {
                        (l.point, l.error) = (Vec3::ZERO, Vec3::ZERO);
                    }
                    l
                };
                assert_eq!(set_again(queue.queued(i)), set_again(*lane), "lane {i}");
                near += 1;
                continue;
            }
            let outcome = outcome.record();
            assert_eq!(
                read_bits(&outcome),
                read_bits(&lambert_bounce(&single, &spaces)),
                "lane {i}"
            );
            lit += (outcome.shadow != 0.0) as u32;
            unlit += (outcome.shadow == 0.0) as u32;
        }
        // Lit lanes, unlit ones (behind a one-sided emitter, or facing away) and near ones.
        assert!(lit > 10 && near > 10 && unlit > 10, "{lit} {near} {unlit}");
    }
}
