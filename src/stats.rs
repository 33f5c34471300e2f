//! Counters: rays by kind, hits, and (where the backend can observe them) BVH node visits and
//! primitive tests. Each worker owns a plain struct; they are merged once at the end, so
//! counting needs no atomics and the totals do not depend on the thread count.

use crate::phase_times::PhaseTimes;
use std::ops::AddAssign;

/// `AddAssign` that adds every listed count, saturating: counts read from part files may be
/// anything, and a sum that wrapped would report a small number as the total.
macro_rules! add_fields {
    ($ty:ident { $($field:ident),+ }) => {
        impl AddAssign for $ty {
            fn add_assign(&mut self, other: Self) {
                $(self.$field = self.$field.saturating_add(other.$field);)+
            }
        }
    };
}

/// What a backend observed while traversing its acceleration structure.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct TraversalCounters {
    /// BVH nodes whose children were tested against the ray.
    pub node_visits: u64,
    /// Ray-primitive intersection tests (triangles, spheres).
    pub prim_tests: u64,
}

add_fields!(TraversalCounters { node_visits, prim_tests });

/// Rays traced and hits found, for one kind of ray.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct RayKindCounts {
    pub rays: u64,
    pub hits: u64,
}

add_fields!(RayKindCounts { rays, hits });

/// The path tracer's scattering bounces, by the code that computed them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct BounceCounts {
    /// Plain Lambertian bounces, in vector lanes (one lane at a time on scalar paths).
    pub lanes: u64,
    /// Bounces through the general BSDF code.
    pub scalar: u64,
    /// Of the `lanes`, those whose light was sampled one lane at a time (near the scene's
    /// lone emitter, by solid angle), their lane computed once more then. Absent from part
    /// files written before it was counted.
    #[serde(default)]
    pub near_lights: u64,
    /// Whitted samples whose tree reached `whitted::MAX_RAYS_PER_SAMPLE` rays and was cut
    /// there. Absent from part files written before it was counted.
    #[serde(default)]
    pub cut_trees: u64,
}

add_fields!(BounceCounts { lanes, scalar, near_lights, cut_trees });

/// All counters of a render (or of one worker's share of it).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct RenderStats {
    pub camera: RayKindCounts,
    /// Shadow rays; a "hit" means the light was occluded.
    pub shadow: RayKindCounts,
    pub indirect: RayKindCounts,
    pub traversal: TraversalCounters,
    /// Absent from part files written before it was counted.
    #[serde(default)]
    pub bounces: BounceCounts,
    /// Time by phase of the batched path tracer, summed over the threads, when timed
    /// (`--time-phases`).
    #[serde(default, skip_serializing_if = "PhaseTimes::is_empty")]
    pub phases: PhaseTimes,
    /// Samples with a colour channel beyond what a pixel's exact sums hold
    /// (`sample_sums::LARGEST_SAMPLE`), added as that largest value. Absent when none was.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub clamped_samples: u64,
}

fn is_zero(count: &u64) -> bool {
    *count == 0
}

impl RenderStats {
    pub fn total_rays(&self) -> u64 {
        self.camera.rays.saturating_add(self.shadow.rays).saturating_add(self.indirect.rays)
    }
}

impl AddAssign for RenderStats {
    fn add_assign(&mut self, other: Self) {
        self.camera += other.camera;
        self.shadow += other.shadow;
        self.indirect += other.indirect;
        self.traversal += other.traversal;
        self.bounces += other.bounces;
        self.phases += other.phases;
        self.clamped_samples = self.clamped_samples.saturating_add(other.clamped_samples);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Counts read from part files are summed without wrapping (two parts of 2⁶⁴ − 1 rays
    /// made "168 rays in all").
    #[test]
    fn sums_saturate() {
        let huge = RayKindCounts { rays: u64::MAX, hits: 3 };
        let mut stats = RenderStats { camera: huge, shadow: huge, ..Default::default() };
        stats += stats;
        assert_eq!((stats.camera.rays, stats.camera.hits), (u64::MAX, 6));
        assert_eq!(stats.total_rays(), u64::MAX);
    }
}
