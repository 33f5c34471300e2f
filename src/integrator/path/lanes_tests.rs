//! The vectorised loop against the lane function it runs, and its directions against their
//! density, lane position by lane position.

use super::*;
use crate::float_error::{TrianglePlane, triangle_hit_point, triangle_point};
use crate::integrator::path::lambert::{AREA, DISTANT, LONE, NEAR, POINT};
use crate::integrator::path::lane_light::{lone_draw_fields, with_hit_point, with_lone_light};
use crate::light::{Emitter, EmitterShape, InstanceEmitters, LightSet};
use crate::sampling::chi_square;
use crate::splitmix::SplitMix64;
use glam::{Mat3, Quat};

fn spaces() -> FrameSpaces {
    let sampling_from_render =
        Mat3::from_quat(Quat::from_rotation_arc(Vec3::new(0.3, -0.5, 0.8).normalize(), Vec3::Z));
    let render_from_sampling = sampling_from_render.transpose();
    FrameSpaces { sampling_from_render, render_from_sampling, shading_sides: false }
}

/// A lane whose view is above its surface, lit or not, rouletted or not.
fn random_lane(rng: &mut SplitMix64) -> LambertLane {
    let normal = rng.vec3(-1.0, 1.0).normalize();
    let point = rng.vec3(-10.0, 10.0);
    let dir = -(normal + 0.9 * rng.vec3(-1.0, 1.0)).normalize();
    let light_kind = [AREA, POINT, DISTANT][(rng.next_u64() % 3) as usize];
    let light_point = if light_kind == DISTANT {
        rng.vec3(-1.0, 1.0).normalize()
    } else {
        point + rng.vec3(-3.0, 3.0)
    };
    LambertLane {
        dir,
        point,
        error: rng.vec3(0.0, 1e-6),
        normal,
        // Off unit length now and then, as a rotated normal can be.
        shading_normal: (normal + 0.05 * rng.vec3(-1.0, 1.0)).normalize()
            * rng.range(0.9999, 1.0001),
        diffuse: rng.vec3(0.0, 1.0),
        throughput: rng.vec3(0.0, 2.0),
        eta_scale: 1.0,
        has_light: if rng.unit() < 0.8 { 1.0 } else { 0.0 },
        light_kind,
        light_point,
        light_error: rng.vec3(0.0, 1e-6),
        light_normal: rng.vec3(-1.0, 1.0).normalize(),
        emission: rng.vec3(0.0, 20.0),
        light_pdf: rng.range(0.01, 5.0),
        light_visible: if rng.unit() < 0.5 { 1.0 } else { 0.0 },
        light_two_sided: if rng.unit() < 0.5 { 1.0 } else { 0.0 },
        u0: rng.unit(),
        u1: rng.unit(),
        u_survive: rng.unit(),
        roulette: if rng.unit() < 0.5 { 1.0 } else { 0.0 },
        // A triangle hit that is not to be used (see `on_triangle_lane`).
        hit_v0: rng.vec3(-1.0, 1.0),
        hit_v1: rng.vec3(-1.0, 1.0),
        hit_v2: rng.vec3(-1.0, 1.0),
        hit_origin: rng.vec3(-1.0, 1.0),
        on_triangle: 0.0,
        hit_b1: rng.unit(),
        hit_b2: rng.unit(),
        hit_t: rng.unit(),
        hit_tilt: rng.unit(),
        hit_edge_tilt: rng.unit(),
    }
}

/// `lane` moved onto a random triangle around `center`, hit by a ray along its direction,
/// its point and bound left to be computed from the hit; the triangle's normal faces the ray.
fn on_triangle_lane(rng: &mut SplitMix64, lane: &LambertLane, center: Vec3) -> LambertLane {
    let triangle = [(); 3].map(|_| center + rng.vec3(-2.0, 2.0));
    lane_on(triangle, rng, lane)
}

/// `lane` moved onto `triangle` (see `on_triangle_lane`).
fn lane_on(triangle: [Vec3; 3], rng: &mut SplitMix64, lane: &LambertLane) -> LambertLane {
    let plane = TrianglePlane::new(&triangle);
    let (b1, b2) = (rng.unit() * 0.5, rng.unit() * 0.5);
    let on_plane = triangle[0] * (1.0 - b1 - b2) + triangle[1] * b1 + triangle[2] * b2;
    let t = rng.range(0.1, 20.0);
    let front_face = plane.normal.dot(lane.dir) < 0.0;
    let normal = if front_face { plane.normal } else { -plane.normal };
    LambertLane {
        point: Vec3::ZERO,
        error: Vec3::ZERO,
        normal,
        shading_normal: normal,
        hit_v0: triangle[0],
        hit_v1: triangle[1],
        hit_v2: triangle[2],
        hit_origin: on_plane - lane.dir * t,
        on_triangle: if front_face { 1.0 } else { -1.0 },
        hit_b1: b1,
        hit_b2: b2,
        hit_t: t,
        hit_tilt: plane.tilt,
        hit_edge_tilt: plane.edge_tilt,
        ..*lane
    }
}

/// The bits of every value of `outcome`, for comparisons that NaNs do not defeat.
fn bits(outcome: LambertOutcome) -> [u32; OUT] {
    let mut block = [[0.0; CHUNK]; OUT];
    outcome.write_at(&mut block, 0, 0);
    std::array::from_fn(|k| block[k][0].to_bits())
}

#[test]
fn a_lane_survives_its_columns() {
    let lane = random_lane(&mut SplitMix64(7));
    let mut block = [[f32::NAN; CHUNK]; IN];
    for j in [0, 5, CHUNK - 1] {
        lane.write_at(&mut block, j, 0);
        assert_eq!(LambertLane::read_at(&block, j), lane);
    }
    let filled = block.iter().flatten().filter(|v| !v.is_nan()).count();
    assert_eq!(filled, 3 * IN, "each lane writes one value per column");
    assert_eq!(LambertLane::COLUMNS, 15 * 3 + 16);
}

/// The bits of every field of `outcome` as its getters read them, in column order.
fn field_bits(outcome: &impl OutcomeFields) -> [u32; OUT] {
    let vectors = [
        outcome.shadow_origin(),
        outcome.shadow_dir(),
        outcome.contribution(),
        outcome.next_origin(),
        outcome.next_dir(),
        outcome.throughput(),
        outcome.point(),
    ];
    let scalars =
        [outcome.shadow(), outcome.next(), outcome.pdf(), outcome.shadow_tmax(), outcome.near()];
    let values: Vec<f32> = vectors.iter().flat_map(|v| v.to_array()).chain(scalars).collect();
    std::array::from_fn(|k| values[k].to_bits())
}

#[test]
fn an_outcome_s_view_reads_each_field_from_its_own_columns() {
    let mut rng = SplitMix64(13);
    let mut block = [[f32::NAN; CHUNK]; OUT];
    // Random values in every column (a bounce's own outcome often has equal ones: its shadow
    // ray and next ray may leave from the same point), so that a field read from another's
    // column shows.
    let outcomes: Vec<LambertOutcome> = (0..CHUNK)
        .map(|_| LambertOutcome {
            shadow: rng.unit(),
            shadow_origin: rng.vec3(-1.0, 1.0),
            shadow_dir: rng.vec3(-1.0, 1.0),
            shadow_tmax: rng.unit(),
            contribution: rng.vec3(-1.0, 1.0),
            next: rng.unit(),
            next_origin: rng.vec3(-1.0, 1.0),
            next_dir: rng.vec3(-1.0, 1.0),
            throughput: rng.vec3(-1.0, 1.0),
            pdf: rng.unit(),
            point: rng.vec3(-1.0, 1.0),
            near: rng.unit(),
        })
        .collect();
    for (j, outcome) in outcomes.iter().enumerate() {
        let mut values = bits(*outcome).to_vec();
        values.sort_unstable();
        values.dedup();
        assert_eq!(values.len(), OUT, "a value in two columns at position {j}");
        outcome.write_at(&mut block, j, 0);
    }
    for j in [0, 5, CHUNK - 1] {
        let view = OutcomeAt { block: &block, j };
        assert_eq!(field_bits(&view), bits(outcomes[j]), "position {j}");
        assert_eq!(field_bits(&outcomes[j]), bits(outcomes[j]), "position {j}");
    }
}

#[test]
fn the_vector_loop_gives_each_lane_s_own_result_bit_for_bit() {
    let spaces = spaces();
    let mut rng = SplitMix64(11);
    let mut queue = LambertLanes::default();
    // Two batches, the second shorter, each with a partial last chunk.
    for n in [3 * CHUNK + 5, CHUNK - 3] {
        queue.clear();
        let lanes: Vec<LambertLane> = (0..n).map(|_| random_lane(&mut rng)).collect();
        for (i, lane) in lanes.iter().enumerate() {
            queue.push(i as u32 * 2, lane);
        }
        queue.run(&spaces, None, true);
        let outcomes: Vec<_> = queue.outcomes().map(|(_, p, o)| (p, o.record())).collect();
        assert_eq!(outcomes.len(), n);
        let (mut shadows, mut nexts) = (0, 0);
        for (i, (lane, (path, outcome))) in lanes.iter().zip(outcomes).enumerate() {
            assert_eq!(path, i as u32 * 2);
            let single = lambert_bounce(lane, &spaces);
            assert_eq!(bits(outcome), bits(single), "lane {i} of {n}");
            shadows += (outcome.shadow != 0.0) as u32;
            nexts += (outcome.next != 0.0) as u32;
        }
        // Both kinds of outcome occur, so the comparison covers them.
        assert!(shadows > 0 && nexts > 0 && nexts < n as u32, "{shadows} {nexts} of {n}");
    }
}

#[test]
fn lane_directions_follow_the_cosine_density_at_every_lane_position() {
    const PER_POSITION: usize = 6400;
    const BINS: usize = 8;
    let spaces = spaces();
    let mut rng = SplitMix64(3);
    let mut queue = LambertLanes::default();
    let mut frames = Vec::new();
    for i in 0..PER_POSITION * CHUNK {
        let mut lane = random_lane(&mut rng);
        (lane.roulette, lane.diffuse) = (0.0, Vec3::splat(0.5));
        lane.normal = lane.shading_normal.normalize();
        // Seen from well above: every lane samples a direction.
        lane.dir = -(lane.normal + 0.3 * rng.vec3(-1.0, 1.0)).normalize();
        frames.push(crate::integrator::path::shading_frame_in(&spaces, lane.shading_normal));
        queue.push(i as u32, &lane);
    }
    queue.run(&spaces, None, true);
    // cos²θ and φ are uniform under the cosine density: equal cells.
    let mut counts = vec![[0u64; BINS * BINS]; CHUNK];
    let mut taken = [0u64; CHUNK];
    for (path, outcome) in queue.outcomes().map(|(_, p, o)| (p, o.record())) {
        let local = frames[path as usize].transpose() * outcome.next_dir;
        assert!((outcome.pdf - local.z * std::f32::consts::FRAC_1_PI).abs() < 1e-5);
        if outcome.next == 0.0 {
            continue;
        }
        let position = path as usize % CHUNK;
        let cos2 = (local.z * local.z).clamp(0.0, 0.999_999);
        let phi = (local.y.atan2(local.x) / std::f32::consts::TAU + 1.0).fract().min(0.999_999);
        let cell = (cos2 * BINS as f32) as usize * BINS + (phi * BINS as f32) as usize;
        counts[position][cell] += 1;
        taken[position] += 1;
    }
    let expected = vec![1.0 / (BINS * BINS) as f64; BINS * BINS];
    for position in 0..CHUNK {
        assert!(taken[position] as usize > PER_POSITION * 99 / 100, "{}", taken[position]);
        let name = format!("cosine lanes, position {position}");
        chi_square::assert_fits(&name, &counts[position], &expected, taken[position]);
    }
}

/// A rectangle emitter above the random lanes' points, as `LightSet` copies it.
fn lone_rectangle(two_sided: bool) -> LoneEmitter {
    let corners = [(-2.0, -1.5), (2.0, -1.5), (2.0, 1.5), (-2.0, 1.5)];
    let shape = EmitterShape::quad(corners.map(|(x, z)| Vec3::new(x, 30.0, z))).expect("a quad");
    let emitters = vec![Emitter::new(0, shape, Vec3::splat(10.0), two_sided)];
    let instance = InstanceEmitters { emitters, by_instance: vec![Some(vec![0])] };
    let lights = LightSet::new(Vec::new(), Vec::new(), instance, Vec::new());
    lights.lone_emitter().expect("one flat emitter")
}

/// A random lane, most on triangles, near the emitter of `lone_rectangle` (within its three
/// bounding radii), far from it or above it (behind, if it is one-sided); its light left to
/// the loop (`LONE`, with a random draw) at odds `left`.
fn lane_under_emitter(rng: &mut SplitMix64, left: f32) -> LambertLane {
    let mut lane = random_lane(rng);
    let center = [Vec3::ZERO, Vec3::new(0.0, 26.0, 0.0), Vec3::new(0.0, 40.0, 0.0)]
        [(rng.next_u64() % 3) as usize];
    if rng.unit() < 0.8 {
        lane = on_triangle_lane(rng, &lane, center);
    }
    if rng.unit() < left {
        (lane.light_kind, lane.has_light) = (LONE, 0.0);
        let draw = [(); 4].map(|_| rng.unit());
        (lane.light_point, lane.light_normal) = lone_draw_fields(draw);
    }
    lane
}

/// A triangle hit's point computed in a lane is `triangle_hit_point`'s with the triangle's
/// own plane, bit for bit, whichever side was hit; both of its candidates are taken, and a
/// degenerate triangle's is the barycentric one.
#[test]
fn a_lane_s_hit_point_is_the_triangle_s() {
    let mut rng = SplitMix64(17);
    let bits = |v: Vec3| v.to_array().map(f32::to_bits);
    let (mut from_ray, mut backs, mut degenerate) = (0, 0, 0);
    for i in 0..4000 {
        // Far from the origin too, where the barycentric sum's bound grows.
        let (lane, center) = (random_lane(&mut rng), rng.vec3(-50.0, 50.0) * rng.range(1.0, 1e4));
        let mut lane = on_triangle_lane(&mut rng, &lane, center);
        if i % 100 == 0 {
            // Degenerate: the third vertex is the first again (a zero normal).
            let (v0, v1) = (lane.hit_v0, lane.hit_v1);
            lane = lane_on([v0, v1, v0], &mut rng, &lane);
        }
        let triangle = [lane.hit_v0, lane.hit_v1, lane.hit_v2];
        let hit = ((lane.hit_b1, lane.hit_b2), (lane.hit_origin, lane.dir, lane.hit_t));
        let plane = TrianglePlane::new(&triangle);
        let (point, error) = triangle_hit_point(&triangle, &plane, hit.0, hit.1);
        let computed = with_hit_point(&lane);
        assert_eq!(bits(computed.point), bits(point), "lane {i}");
        assert_eq!(bits(computed.error), bits(error), "lane {i}");
        let barycentric = triangle_point(&triangle, &plane, hit.0.0, hit.0.1);
        from_ray += (bits(point) != bits(barycentric.0)) as u32;
        backs += (lane.on_triangle < 0.0) as u32;
        if plane.normal == Vec3::ZERO {
            degenerate += 1;
            assert_eq!(bits(point), bits(barycentric.0), "degenerate lane {i}");
        }
        // A point already known stays.
        let known = with_hit_point(&LambertLane { on_triangle: 0.0, ..lane });
        assert_eq!((known.point, known.error), (lane.point, lane.error));
    }
    assert!(from_ray > 100 && from_ray < 3900 && backs > 100, "{from_ray} {backs}");
    assert_eq!(degenerate, 40);
}

#[test]
fn points_left_to_the_vector_loop_are_those_of_one_lane_bit_for_bit() {
    let spaces = spaces();
    let mut rng = SplitMix64(19);
    let mut queue = LambertLanes::default();
    // Most lanes' points left to the loop, the rest known; the lights all known already.
    let lanes: Vec<LambertLane> = (0..4 * CHUNK + 9)
        .map(|_| {
            let (lane, center) = (random_lane(&mut rng), rng.vec3(-10.0, 10.0));
            match rng.unit() < 0.7 {
                true => on_triangle_lane(&mut rng, &lane, center),
                false => lane,
            }
        })
        .collect();
    for (i, lane) in lanes.iter().enumerate() {
        queue.push(i as u32, lane);
    }
    queue.run(&spaces, None, true);
    let mut found = 0;
    for (i, (lane, (_, _, outcome))) in lanes.iter().zip(queue.outcomes()).enumerate() {
        let single = lambert_bounce(&with_hit_point(lane), &spaces);
        assert_eq!(bits(outcome.record()), bits(single), "lane {i}");
        found += (lane.on_triangle != 0.0 && single.next != 0.0) as u32;
    }
    // Lanes whose points the loop found go on, so the comparison covers them.
    assert!(found > 10, "{found}");
}

#[test]
fn points_and_lights_left_to_the_vector_loop_are_those_of_one_lane_bit_for_bit() {
    let spaces = spaces();
    let mut rng = SplitMix64(5);
    for two_sided in [true, false] {
        let emitter = lone_rectangle(two_sided);
        let mut queue = LambertLanes::default();
        // Most with their light left.
        let lanes: Vec<LambertLane> =
            (0..8 * CHUNK + 7).map(|_| lane_under_emitter(&mut rng, 0.7)).collect();
        for (i, lane) in lanes.iter().enumerate() {
            queue.push(i as u32, lane);
        }
        queue.run(&spaces, Some(&emitter), true);
        let (mut lit, mut near, mut behind) = (0, 0, 0);
        for (i, (lane, (_, _, outcome))) in lanes.iter().zip(queue.outcomes()).enumerate() {
            let outcome = outcome.record();
            let single = with_lone_light(&with_hit_point(lane), &emitter.sampler);
            assert_eq!(bits(outcome), bits(lambert_bounce(&single, &spaces)), "lane {i}");
            assert_eq!(outcome.near != 0.0, single.light_kind == NEAR, "lane {i}");
            let left = lane.light_kind == LONE;
            lit += (left && outcome.shadow != 0.0) as u32;
            near += (single.light_kind == NEAR) as u32;
            if left && emitter.sampler.behind(single.point) {
                behind += 1;
                assert_eq!((single.has_light, outcome.shadow), (0.0, 0.0), "lane {i}");
            }
        }
        // Light points sampled in the loop do light their lanes, some are left to one lane
        // at a time, and (one-sided) some lanes are behind: the comparison covers all three.
        assert!(lit > 10 && near > 10, "{lit} {near}");
        assert!(two_sided == (behind == 0) && (two_sided || behind > 10), "{behind}");
    }
}

#[path = "lanes_unwritten_tests.rs"]
mod unwritten;
