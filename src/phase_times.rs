//! Where a batched path-traced render spends its time (`--time-phases`): the time each
//! worker thread spends in each phase of its tiles' batches, summed over the threads (their
//! CPU time, unless the system takes a core away from them). Off by default; when on, a
//! clock is read once per phase per batch of paths (a tile's), not per path.

use std::ops::AddAssign;
use std::time::Instant;

/// The phases of a batch (`render_tile`, `Wavefront::run`), in the order they run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// Random streams, pixel positions and camera rays of a batch.
    CameraRays,
    /// Gathering the live paths' rays (each path given the light of its last bounce's
    /// unblocked shadow rays first) and the backend's closest-hit query (Embree's packets
    /// and their wrapper).
    ClosestHits,
    /// The bounce's Sobol draws, made ahead for all paths that hit.
    Draws,
    /// Each path's hit shaded by the scalar code, plain Lambertian bounces written to lanes.
    Shading,
    /// The plain Lambertian bounces computed in vector lanes.
    Lanes,
    /// The lanes' outcomes applied to their paths, shadow rays queued.
    Outcomes,
    /// The backend's occlusion query of the shadow rays.
    ShadowRays,
    /// Unblocked light summed per path, and the finished samples added to the pixels' sums.
    Accumulate,
}

impl Phase {
    pub const ALL: [Phase; 8] = [
        Phase::CameraRays,
        Phase::ClosestHits,
        Phase::Draws,
        Phase::Shading,
        Phase::Lanes,
        Phase::Outcomes,
        Phase::ShadowRays,
        Phase::Accumulate,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Phase::CameraRays => "camera rays",
            Phase::ClosestHits => "closest hits",
            Phase::Draws => "Sobol draws",
            Phase::Shading => "shading",
            Phase::Lanes => "vector lanes",
            Phase::Outcomes => "lane outcomes",
            Phase::ShadowRays => "shadow rays",
            Phase::Accumulate => "accumulate",
        }
    }
}

/// Nanoseconds per phase, summed over the threads (`Phase::ALL`'s order); all zero unless timed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct PhaseTimes {
    pub nanos: [u64; Phase::ALL.len()],
}

impl PhaseTimes {
    pub fn is_empty(&self) -> bool {
        self.nanos.iter().all(|&n| n == 0)
    }

    pub fn seconds(&self, phase: Phase) -> f64 {
        self.nanos[phase as usize] as f64 * 1e-9
    }

    pub fn total_seconds(&self) -> f64 {
        self.nanos.iter().sum::<u64>() as f64 * 1e-9
    }
}

impl AddAssign for PhaseTimes {
    fn add_assign(&mut self, other: Self) {
        for (sum, n) in self.nanos.iter_mut().zip(other.nanos) {
            *sum = sum.saturating_add(n);
        }
    }
}

/// Charges the time since its last lap to a phase; does nothing when not timing.
#[derive(Clone, Copy, Debug, Default)]
pub struct PhaseClock {
    last: Option<Instant>,
}

impl PhaseClock {
    /// A clock that times (`on`) or does nothing.
    pub fn new(on: bool) -> Self {
        PhaseClock { last: on.then(Instant::now) }
    }

    /// Adds the time since the last lap (or `new`) to `phase` in `times`.
    #[inline]
    pub fn lap(&mut self, phase: Phase, times: &mut PhaseTimes) {
        if let Some(last) = &mut self.last {
            let now = Instant::now();
            times.nanos[phase as usize] += now.duration_since(*last).as_nanos() as u64;
            *last = now;
        }
    }
}

/// The times as a table: seconds and share of the timed total per phase, or nothing when
/// none was timed.
pub fn phase_table(times: &PhaseTimes) -> String {
    if times.is_empty() {
        return String::new();
    }
    let total = times.total_seconds();
    let mut out = format!(
        "phase            seconds   share (threads' time in batched paths: {total:.3} s)\n"
    );
    for phase in Phase::ALL {
        let seconds = times.seconds(phase);
        out += &format!("{:<16} {seconds:<9.3} {:.1} %\n", phase.name(), 100.0 * seconds / total);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_idle_clock_charges_nothing_and_a_running_one_charges_the_phase_it_is_told() {
        assert!(Phase::ALL.iter().enumerate().all(|(i, &p)| p as usize == i));
        let mut times = PhaseTimes::default();
        let mut idle = PhaseClock::new(false);
        std::thread::sleep(std::time::Duration::from_millis(2));
        idle.lap(Phase::Shading, &mut times);
        assert!(times.is_empty() && phase_table(&times).is_empty());

        let mut clock = PhaseClock::new(true);
        std::thread::sleep(std::time::Duration::from_millis(2));
        clock.lap(Phase::Lanes, &mut times);
        clock.lap(Phase::Draws, &mut times);
        assert!(times.seconds(Phase::Lanes) >= 0.002, "{times:?}");
        // The second lap charges only the time since the first.
        assert!(times.seconds(Phase::Draws) < times.seconds(Phase::Lanes), "{times:?}");
        let charged = [Phase::Lanes, Phase::Draws];
        assert!(Phase::ALL.iter().all(|p| charged.contains(p) || times.seconds(*p) == 0.0));

        let mut sum = times;
        sum += times;
        assert_eq!(sum.nanos[Phase::Lanes as usize], 2 * times.nanos[Phase::Lanes as usize]);
        let table = phase_table(&times);
        assert_eq!(table.lines().count(), 1 + Phase::ALL.len(), "{table}");
        assert!(table.contains("vector lanes"), "{table}");
    }
}
