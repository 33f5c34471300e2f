//! Lanes written as a scene's paths write them, without the columns the loop sets itself
//! (`POINT_UNWRITTEN`, `LONE_UNWRITTEN`), over columns that all hold a poison value.

use super::*;
use crate::integrator::path::lambert::LaneSink;

/// What the columns hold before the lanes are written: NaN, which fails every comparison,
/// and values that pass some.
const POISONS: [f32; 3] = [f32::NAN, f32::INFINITY, -3.0e38];

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

/// A queue of `lanes`, each written without the columns `unwritten` names for it, over
/// blocks whose every column holds `poison`.
fn queue_over(
    poison: f32,
    lanes: &[LambertLane],
    unwritten: impl Fn(&LambertLane) -> u64,
) -> LambertLanes {
    let mut queue = LambertLanes::default();
    let poisoned = LambertLane::read_at(&[[poison; CHUNK]; IN], 0);
    for i in 0..lanes.len() {
        queue.push(i as u32, &poisoned);
    }
    queue.clear();
    for (i, lane) in lanes.iter().enumerate() {
        queue.next_lane().put(*lane, unwritten(lane));
        queue.commit(i as u32);
    }
    queue
}

/// The point's columns, where the loop computes the point.
fn point_unwritten(lane: &LambertLane) -> u64 {
    if lane.on_triangle != 0.0 { POINT_UNWRITTEN } else { 0 }
}

#[test]
fn exactly_the_columns_named_are_left_unwritten() {
    let lane = random_lane(&mut SplitMix64(3));
    let mut block = [[f32::NAN; CHUNK]; IN];
    lane.write_at(&mut block, 2, POINT_UNWRITTEN | LONE_UNWRITTEN);
    let left = block.iter().filter(|column| column[2].is_nan()).count();
    assert_eq!(left, 6 + 10, "the point and bound, and six light fields (10 columns)");
    let read = LambertLane::read_at(&block, 2);
    assert!(read.point.is_nan() && read.light_error.is_nan() && read.has_light.is_nan());
    assert_eq!(
        (read.light_point, read.light_normal, read.u0),
        (lane.light_point, lane.light_normal, lane.u0)
    );
}

/// Without a lone emitter only the points are left to the loop.
#[test]
fn unwritten_points_reach_no_result_that_is_read() {
    let spaces = spaces();
    let mut rng = SplitMix64(29);
    let lanes: Vec<LambertLane> = (0..6 * CHUNK + 3)
        .map(|_| {
            let (lane, center) = (random_lane(&mut rng), rng.vec3(-10.0, 10.0));
            if rng.unit() < 0.7 { on_triangle_lane(&mut rng, &lane, center) } else { lane }
        })
        .collect();
    for poison in POISONS {
        let mut queue = queue_over(poison, &lanes, point_unwritten);
        queue.run(&spaces, None, true);
        let mut lit = 0;
        for (i, (lane, (_, _, outcome))) in lanes.iter().zip(queue.outcomes()).enumerate() {
            let single = lambert_bounce(&with_hit_point(lane), &spaces);
            assert_eq!(read_bits(&outcome.record()), read_bits(&single), "lane {i}, {poison}");
            lit += (lane.on_triangle != 0.0 && single.shadow != 0.0) as u32;
        }
        assert!(lit > 10, "{lit}");
    }
}

#[test]
fn unwritten_points_and_lights_reach_no_result_that_is_read() {
    let spaces = spaces();
    let mut rng = SplitMix64(23);
    for (two_sided, poison) in [true, false].into_iter().flat_map(|t| POISONS.map(|p| (t, p))) {
        let emitter = lone_rectangle(two_sided);
        // Every light left to the loop, as a lone emitter's scene leaves them.
        let lanes: Vec<LambertLane> =
            (0..8 * CHUNK + 5).map(|_| lane_under_emitter(&mut rng, 1.0)).collect();
        let mut queue = queue_over(poison, &lanes, |lane| LONE_UNWRITTEN | point_unwritten(lane));
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
            let expected = read_bits(&lambert_bounce(&single, &spaces));
            assert_eq!(read_bits(&outcome), expected, "lane {i}, {poison}");
            lit += (outcome.shadow != 0.0) as u32;
            unlit += (outcome.shadow == 0.0) as u32;
        }
        // Lit lanes, unlit ones (behind a one-sided emitter, or facing away) and near ones.
        assert!(lit > 10 && near > 10 && unlit > 10, "{lit} {near} {unlit}");
    }
}
