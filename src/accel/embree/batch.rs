//! Batched closest-hit queries: Embree packets (`rtcIntersect4/8/16`) and streams
//! (`rtcIntersect1M`), and the bare `rtcIntersect1` loop the wrapper is measured against.

use super::compat::{self, Coherence};
use super::ffi;
use super::ray::{self, RayHitPacket};
use super::scene::{CommittedScene, embree_accepts};
use crate::ray::{Hit, Ray};
use crate::ray_columns::{BLOCK, RayBlock, RayColumns};
use glam::Vec3;

/// How a batch of rays is handed to Embree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BatchKind {
    /// One `rtcIntersect1` per ray.
    Single,
    Packet4,
    Packet8,
    Packet16,
    /// `rtcIntersect1M` with the coherent flag (Embree 3).
    StreamCoherent,
    /// `rtcIntersect1M` without it (Embree 3).
    StreamIncoherent,
}

impl CommittedScene {
    /// Closest hits of `rays` into `hits` (same length), as [`CommittedScene::intersect`]
    /// would give them one by one, through Embree's batched entry points. Rays Embree would
    /// reject are never handed to it (masked out of packets, left out of streams): a miss.
    pub fn intersect_batch(
        &self,
        kind: BatchKind,
        coherence: Coherence,
        rays: &[Ray],
        hits: &mut [Option<Hit>],
    ) {
        assert_eq!(rays.len(), hits.len(), "one hit slot per ray");
        match kind {
            BatchKind::Single => {
                for (ray, hit) in rays.iter().zip(hits) {
                    *hit = self.intersect(ray, None);
                }
            }
            BatchKind::Packet4 => {
                self.intersect_packets::<compat::Padded<ffi::RTCRayHit4, 4>>(coherence, rays, hits)
            }
            BatchKind::Packet8 => {
                self.intersect_packets::<compat::Padded<ffi::RTCRayHit8, 8>>(coherence, rays, hits)
            }
            BatchKind::Packet16 => self
                .intersect_packets::<compat::Padded<ffi::RTCRayHit16, 16>>(coherence, rays, hits),
            BatchKind::StreamCoherent => self.intersect_stream(rays, hits, true),
            BatchKind::StreamIncoherent => self.intersect_stream(rays, hits, false),
        }
    }

    /// Occlusion of `rays` into `blocked` (same length), as [`CommittedScene::occluded`]
    /// would give it one by one but with rays Embree would reject blocked (never traced),
    /// through Embree's packet entry points (streams trace packets of 8).
    pub fn occluded_batch(&self, kind: BatchKind, rays: &[Ray], blocked: &mut [bool]) {
        assert_eq!(rays.len(), blocked.len(), "one answer per ray");
        match kind {
            BatchKind::Single => {
                for (ray, blocked) in rays.iter().zip(blocked) {
                    *blocked = !embree_accepts(ray) || self.occluded(ray, None);
                }
            }
            BatchKind::Packet4 => {
                self.occluded_packets::<compat::Padded<ffi::RTCRayHit4, 4>>(rays, blocked)
            }
            BatchKind::Packet8 | BatchKind::StreamCoherent | BatchKind::StreamIncoherent => {
                self.occluded_packets::<compat::Padded<ffi::RTCRayHit8, 8>>(rays, blocked)
            }
            BatchKind::Packet16 => {
                self.occluded_packets::<compat::Padded<ffi::RTCRayHit16, 16>>(rays, blocked)
            }
        }
    }

    /// [`CommittedScene::intersect_batch`] of rays queued in columns, each packet of 8 or 16
    /// filled a column at a time (other kinds take the rays one by one into their own form).
    pub fn intersect_columns(
        &self,
        kind: BatchKind,
        coherence: Coherence,
        rays: &RayColumns,
        hits: &mut [Option<Hit>],
    ) {
        assert_eq!(rays.len(), hits.len(), "one hit slot per ray");
        match kind {
            BatchKind::Packet8 => {
                self.intersect_blocks::<compat::Padded<ffi::RTCRayHit8, 8>>(coherence, rays, hits)
            }
            BatchKind::Packet16 => {
                self.intersect_blocks::<compat::Padded<ffi::RTCRayHit16, 16>>(coherence, rays, hits)
            }
            _ => {
                let rays: Vec<Ray> = rays.iter().collect();
                self.intersect_batch(kind, coherence, &rays, hits);
            }
        }
    }

    fn intersect_blocks<P: RayHitPacket>(
        &self,
        coherence: Coherence,
        rays: &RayColumns,
        hits: &mut [Option<Hit>],
    ) {
        let blocks = rays.blocks();
        self.intersect_each_packet::<P>(coherence, hits, |packet, k, n| {
            load_blocks(packet, &blocks[k * P::WIDTH / BLOCK..][..n.div_ceil(BLOCK)], n)
        });
    }

    /// [`CommittedScene::occluded_batch`] of rays queued in columns, each packet of 8 or 16
    /// filled a column at a time (other kinds take the rays one by one into their own form).
    pub fn occluded_columns(&self, kind: BatchKind, rays: &RayColumns, blocked: &mut [bool]) {
        assert_eq!(rays.len(), blocked.len(), "one answer per ray");
        match kind {
            BatchKind::Packet8 => {
                self.occluded_blocks::<compat::Padded<ffi::RTCRayHit8, 8>>(rays, blocked)
            }
            BatchKind::Packet16 => {
                self.occluded_blocks::<compat::Padded<ffi::RTCRayHit16, 16>>(rays, blocked)
            }
            _ => {
                let rays: Vec<Ray> = rays.iter().collect();
                self.occluded_batch(kind, &rays, blocked);
            }
        }
    }

    fn occluded_blocks<P: RayHitPacket>(&self, rays: &RayColumns, blocked: &mut [bool]) {
        let blocks = rays.blocks();
        self.occluded_each_packet::<P>(blocked, |packet, k, n| {
            load_blocks(packet, &blocks[k * P::WIDTH / BLOCK..][..n.div_ceil(BLOCK)], n)
        });
    }

    fn occluded_packets<P: RayHitPacket>(&self, rays: &[Ray], blocked: &mut [bool]) {
        self.occluded_each_packet::<P>(blocked, |packet, k, n| {
            load_packet(packet, &rays[k * P::WIDTH..][..n])
        });
    }

    /// Occlusion into `blocked` through packets of `P`: `load(packet, k, n)` sets packet `k`
    /// (of `n` rays: those of `blocked[k * WIDTH..][..n]`) and returns the lanes to trace.
    fn occluded_each_packet<P: RayHitPacket>(
        &self,
        blocked: &mut [bool],
        mut load: impl FnMut(&mut P, usize, usize) -> compat::ValidMask,
    ) {
        let mut packet = P::empty();
        for (k, blocked) in blocked.chunks_mut(P::WIDTH).enumerate() {
            let valid = load(&mut packet, k, blocked.len());
            if valid.any() {
                // SAFETY: the scene is live and committed; `load` marks valid exactly the
                // lanes it set from rays that passed `embree_accepts`.
                unsafe { packet.occluded(self.handle(), &valid) };
            }
            for (lane, blocked) in blocked.iter_mut().enumerate() {
                *blocked = valid.0[lane] == 0 || packet.blocked(lane);
            }
        }
    }

    /// Closest hits into `hits` through packets of `P`, set by `load` as for
    /// `occluded_each_packet`, with no hit yet.
    fn intersect_each_packet<P: RayHitPacket>(
        &self,
        coherence: Coherence,
        hits: &mut [Option<Hit>],
        mut load: impl FnMut(&mut P, usize, usize) -> compat::ValidMask,
    ) {
        let mut packet = P::empty();
        for (k, hits) in hits.chunks_mut(P::WIDTH).enumerate() {
            let valid = load(&mut packet, k, hits.len());
            packet.clear_hits();
            if valid.any() {
                // SAFETY: the scene is live and committed; `load` marks valid exactly the
                // lanes it set from rays that passed `embree_accepts`.
                unsafe { packet.intersect(self.handle(), &valid, coherence) };
            }
            for (lane, hit) in hits.iter_mut().enumerate() {
                *hit = if valid.0[lane] != 0 { packet.hit(lane) } else { None };
            }
        }
    }

    fn intersect_packets<P: RayHitPacket>(
        &self,
        coherence: Coherence,
        rays: &[Ray],
        hits: &mut [Option<Hit>],
    ) {
        self.intersect_each_packet::<P>(coherence, hits, |packet, k, n| {
            load_packet(packet, &rays[k * P::WIDTH..][..n])
        });
    }

    #[cfg(not(embree4))]
    fn intersect_stream(&self, rays: &[Ray], hits: &mut [Option<Hit>], coherent: bool) {
        let mut stream = Vec::with_capacity(rays.len());
        let mut slots = Vec::with_capacity(rays.len());
        for (slot, ray) in rays.iter().enumerate() {
            hits[slot] = None;
            if embree_accepts(ray) {
                stream.push(ray::to_rtc_ray_hit(ray).inner);
                slots.push(slot);
            }
        }
        // SAFETY: the scene is live and committed; every ray passed `embree_accepts`.
        unsafe { compat::intersect_stream(self.handle(), &mut stream, coherent) };
        for (rayhit, slot) in stream.iter().zip(slots) {
            hits[slot] = ray::from_rtc_ray_hit(rayhit);
        }
    }

    #[cfg(embree4)]
    fn intersect_stream(&self, rays: &[Ray], hits: &mut [Option<Hit>], _coherent: bool) {
        self.intersect_packets::<compat::Padded<ffi::RTCRayHit8, 8>>(
            Coherence::Incoherent,
            rays,
            hits,
        );
    }

    /// A bare `rtcIntersect1` loop over `rays` (one query context for all, no `Hit`
    /// conversion): how many hit something. The baseline the wrapper is measured against.
    ///
    /// # Panics
    /// If a ray is one Embree would reject (it would abort the process): checked for all
    /// rays before the loop.
    pub fn raw_intersect_loop(&self, rays: &[Ray]) -> usize {
        assert!(rays.iter().all(embree_accepts), "raw_intersect_loop: a ray Embree rejects");
        let mut query = compat::SingleRayLoop::new();
        let scene = self.handle();
        let mut hits = 0;
        for r in rays {
            let mut rayhit = ray::to_rtc_ray_hit(r);
            // SAFETY: the scene is live and committed; every ray passed `embree_accepts`.
            unsafe { query.intersect1(scene, &mut rayhit) };
            hits += usize::from(rayhit.hit.geomID != ffi::RTC_INVALID_GEOMETRY_ID);
        }
        hits
    }
}

/// A ray Embree accepts, set in the lanes of a packet that are not traced.
const HARMLESS: Ray = Ray { origin: Vec3::ZERO, dir: Vec3::Z, tmin: 0.0, tmax: 0.0, time: 0.0 };

/// Sets the lanes of `packet` (a whole number of blocks wide) from `blocks`, their first
/// `count` rays queued, a column at a time, and returns the mask marking (-1) exactly the
/// queued rays Embree accepts. The other lanes get a harmless ray (never traced).
fn load_blocks<P: RayHitPacket>(
    packet: &mut P,
    blocks: &[RayBlock],
    count: usize,
) -> compat::ValidMask {
    let mut valid = compat::ValidMask([0; 16]);
    for (k, block) in blocks.iter().enumerate() {
        packet.set_block(k * BLOCK, block);
        let accepted = block.valid();
        for (j, &accepted) in accepted.iter().enumerate() {
            valid.0[k * BLOCK + j] = -i32::from(accepted & (k * BLOCK + j < count));
        }
    }
    for lane in 0..P::WIDTH {
        if valid.0[lane] == 0 {
            packet.set_lane(lane, &HARMLESS);
        }
    }
    valid
}

/// Sets the lanes of `packet` from `rays` (no more than its width) and returns the mask
/// marking (-1) exactly those whose rays Embree accepts, without a branch per ray on its
/// validity. The other lanes are never traced, and hold a harmless ray: a refused ray's lane,
/// and the lanes past the end of `rays` (which an earlier occlusion query may have left with
/// `tfar` = -∞).
fn load_packet<P: RayHitPacket>(packet: &mut P, rays: &[Ray]) -> compat::ValidMask {
    let mut valid = compat::ValidMask([0; 16]);
    for (lane, ray) in rays.iter().enumerate() {
        let accepted = embree_accepts(ray);
        packet.set_lane(lane, if accepted { ray } else { &HARMLESS });
        valid.0[lane] = -i32::from(accepted);
    }
    for lane in rays.len()..P::WIDTH {
        packet.set_lane(lane, &HARMLESS);
    }
    valid
}
