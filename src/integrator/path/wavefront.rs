//! Many paths advanced together, a bounce at a time: the closest hits of all their rays
//! found by one batched query (Embree packets, filled a column at a time from the rays queued
//! in columns, `RayColumns`), the bounce's Sobol draws of all of them made
//! together (`sampling::draw_ahead`), each path shaded by the scalar integrator's
//! own code (`PathTracer::on_hit`) — its plain Lambertian bounces all in one vectorised
//! loop (`LambertLanes`) — then the shadow rays of all of them tested by one batched
//! occlusion query. Each path's arithmetic and random numbers are exactly those of
//! `PathTracer::trace`, so the image is the scalar one bit for bit (the backends' batched
//! queries return the single-ray answers, see `Accel::intersect_batch`).

use super::lanes::{LambertLanes, OutcomeFields};
use super::{PathState, PathTracer, ShadowSink};
use crate::accel::Coherence;
use crate::integrator::PathSample;
use crate::integrator::trace::SceneTracer;
use crate::phase_times::{Phase, PhaseClock};
use crate::ray::{Hit, Ray};
use crate::ray_columns::RayColumns;
use crate::sampling::SampleStream;
use crate::stats::RenderStats;
use glam::Vec3;

/// The paths of one batch and the buffers their queries go through, reused from batch to
/// batch by a worker.
#[derive(Default)]
pub(crate) struct Wavefront {
    states: Vec<PathState>,
    streams: Vec<SampleStream>,
    /// The paths still going, in order: during a bounce, those whose rays are in `rays`.
    live: Vec<u32>,
    rays: RayColumns,
    hits: Vec<Option<Hit>>,
    shadows: QueuedShadows,
    /// Per path, the light of its unblocked shadow rays last bounce, applied as its next ray
    /// is gathered: zero between batches (each sum is taken when it is applied).
    direct: Vec<Vec3>,
    /// The bounce's plain Lambertian hits, computed together (`lanes`).
    lambert: LambertLanes,
}

/// The shadow rays of one bounce of every path, with the path each belongs to.
#[derive(Default)]
struct QueuedShadows {
    /// The path whose bounce is being shaded.
    lane: u32,
    rays: RayColumns,
    /// Per ray, its path and the light it brings if it is not blocked (one list: one
    /// push a ray).
    lights: Vec<(u32, Vec3)>,
    blocked: Vec<bool>,
}

/// Shadow rays queued before they are traced: a bounce of many paths in a scene of many
/// point lights (a shadow ray each) would otherwise queue paths × lights of them (32,000
/// lights: 390 MB a worker). Traced in order, so each path's light sums as before.
const MAX_QUEUED_SHADOWS: usize = 4096;

impl QueuedShadows {
    /// Traces the queued rays: `blocked` says which are.
    fn trace(&mut self, path: &PathTracer, stats: &mut RenderStats) {
        self.blocked.clear();
        self.blocked.resize(self.rays.len(), true);
        path.tracer.occluded_batch(&self.rays, &mut self.blocked, stats);
    }

    /// Adds the light of the traced rays that are not blocked to their paths' `direct`, in
    /// the order they were queued, and empties the queue.
    fn accumulate(&mut self, direct: &mut [Vec3]) {
        for (&(lane, contribution), &blocked) in self.lights.iter().zip(&self.blocked) {
            if !blocked {
                direct[lane as usize] += contribution;
            }
        }
        self.rays.clear();
        self.lights.clear();
    }

    /// Traces and accumulates the queue once it holds `MAX_QUEUED_SHADOWS` rays or more.
    fn bound(&mut self, path: &PathTracer, direct: &mut [Vec3], stats: &mut RenderStats) {
        if self.rays.len() >= MAX_QUEUED_SHADOWS {
            self.trace(path, stats);
            self.accumulate(direct);
        }
    }
}

impl ShadowSink for QueuedShadows {
    #[inline]
    fn shadow(&mut self, ray: Ray, contribution: Vec3, stats: &mut RenderStats) {
        // An invalid ray is blocked and not counted (as `SceneTracer::occluded` has it):
        // its light never arrives, so it need not be queued.
        if ray.is_valid() {
            self.valid_shadow(ray, contribution, stats);
        }
    }

    #[inline]
    fn valid_shadow(&mut self, ray: Ray, contribution: Vec3, _stats: &mut RenderStats) {
        debug_assert!(ray.is_valid(), "{ray:?}");
        self.rays.push(&ray);
        self.lights.push((self.lane, contribution));
    }
}

impl Wavefront {
    /// Starts a new batch, of the paths that go on with `streams`, in order: returns the
    /// streams where they stay, to be drawn from for the camera rays, and then the paths
    /// are added by `start_paths`, in the order of their streams.
    pub fn begin(
        &mut self,
        streams: impl IntoIterator<Item = SampleStream>,
    ) -> &mut [SampleStream] {
        self.states.clear();
        self.streams.clear();
        self.live.clear();
        self.streams.extend(streams);
        &mut self.streams
    }

    /// Adds the paths of the batch, their first rays in `states`: one for each stream the
    /// batch began with, in order. (All at once, so that each is built where it stays.)
    pub fn start_paths(&mut self, states: impl IntoIterator<Item = PathState>) {
        self.states.extend(states);
        debug_assert_eq!(self.states.len(), self.streams.len(), "one path per stream");
        self.live.extend(0..self.states.len() as u32);
    }

    /// The samples of the paths, in the order they were started (after `run`).
    pub fn results(&self) -> impl Iterator<Item = &PathSample> {
        self.states.iter().map(|s| &s.result)
    }

    /// Traces every path of the batch to its end, its phases' times charged on `clock`.
    pub fn run(&mut self, path: &PathTracer, stats: &mut RenderStats, clock: &mut PhaseClock) {
        assert_eq!(self.states.len(), self.streams.len(), "one stream per path");
        self.direct.resize(self.states.len(), Vec3::ZERO);
        loop {
            self.rays.clear();
            let mut at_camera = false;
            // A path that ended stays ended: only the paths live last bounce are asked, each
            // given the light of last bounce's unblocked shadow rays first.
            let (states, rays, direct) = (&mut self.states, &mut self.rays, &mut self.direct);
            self.live.retain(|&lane| {
                let state = &mut states[lane as usize];
                state.finish_direct(std::mem::take(&mut direct[lane as usize]));
                let Some(ray) = state.pending_ray() else { return false };
                rays.push(ray);
                at_camera = state.at_camera();
                true
            });
            let lanes = &self.live;
            if lanes.is_empty() {
                return;
            }
            self.hits.clear();
            self.hits.resize(self.rays.len(), None);
            let coherence = if at_camera { Coherence::Coherent } else { Coherence::Incoherent };
            path.accel().intersect_columns(
                &self.rays,
                &mut self.hits,
                coherence,
                &mut stats.traversal,
            );
            clock.lap(Phase::ClosestHits, &mut stats.phases);
            let shadows = &mut self.shadows;
            self.lambert.clear();
            // A ray that found nothing ends its path without drawing.
            let hit_lanes = lanes.iter().zip(&self.hits).filter(|(_, hit)| hit.is_some());
            crate::sampling::draw_ahead(&mut self.streams, hit_lanes.map(|(&lane, _)| lane));
            clock.lap(Phase::Draws, &mut stats.phases);
            SceneTracer::count_closest_hits(&self.hits, at_camera, stats);
            for (&lane, &hit) in lanes.iter().zip(&self.hits) {
                shadows.lane = lane;
                let (state, stream) =
                    (&mut self.states[lane as usize], &mut self.streams[lane as usize]);
                if path.on_hit(state, hit, stream, stats, shadows, &mut self.lambert.next_lane()) {
                    self.lambert.commit(lane);
                }
                shadows.bound(path, &mut self.direct, stats);
            }
            clock.lap(Phase::Shading, &mut stats.phases);
            let plain = path.plain_surfaces.any();
            self.lambert.run(&path.spaces, path.lone_emitter.as_deref(), plain);
            clock.lap(Phase::Lanes, &mut stats.phases);
            for (i, lane, outcome) in self.lambert.outcomes() {
                shadows.lane = lane;
                let state = &mut self.states[lane as usize];
                if outcome.near() != 0.0 {
                    // Its light is sampled by solid angle, one lane at a time.
                    let outcome = path.lambert_outcome(&self.lambert.queued(i), stats);
                    path.finish_lambert(state, &outcome, shadows, stats);
                } else {
                    path.finish_lambert(state, &outcome, shadows, stats);
                }
                shadows.bound(path, &mut self.direct, stats);
            }
            clock.lap(Phase::Outcomes, &mut stats.phases);
            shadows.trace(path, stats);
            clock.lap(Phase::ShadowRays, &mut stats.phases);
            shadows.accumulate(&mut self.direct);
            clock.lap(Phase::Accumulate, &mut stats.phases);
        }
    }
}
