//! A render's counters: as a plain-text table for the terminal, and as the JSON report of
//! `--stats-json` (its schema is the `StatsReport` type).

use super::{OutputError, WriteSeek, write_one};
use crate::accel::{BatchMode, BuildQuality, Intersection, Observes};
use crate::render::{RenderOptions, RenderOutput};
use crate::stats::RenderStats;
use std::path::Path;

/// What `--stats-json` writes (keys in alphabetical order).
#[derive(Debug, serde::Serialize)]
pub struct StatsReport {
    pub backend: &'static str,
    pub batch: BatchMode,
    pub build_quality: BuildQuality,
    pub build_seconds: f64,
    pub compact: bool,
    /// The Embree library and kernels that traced the rays (absent for obvhs): different
    /// versions and ISAs may return different hits for the same ray.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub embree: Option<crate::accel::EmbreeLibrary>,
    pub intersection: Intersection,
    pub observes: Observes,
    pub render_seconds: f64,
    pub render_space: &'static str,
    pub sampler: &'static str,
    pub spp: u32,
    pub stats: RenderStats,
}

impl StatsReport {
    pub fn new(output: &RenderOutput, options: &RenderOptions) -> Self {
        StatsReport {
            backend: output.backend,
            batch: options.accel.batch,
            build_quality: options.accel.build_quality,
            build_seconds: output.build_time.as_secs_f64(),
            compact: options.accel.compact,
            embree: (output.backend == "embree").then(crate::accel::embree_library).flatten(),
            intersection: options.accel.intersection,
            observes: output.observes,
            render_seconds: output.render_time.as_secs_f64(),
            render_space: crate::choice::Choice::name(options.render_space),
            sampler: crate::choice::Choice::name(options.sampler),
            spp: options.spp,
            stats: output.stats,
        }
    }

    /// Writes the report as pretty JSON to `path` on its own.
    pub fn write(&self, path: &Path) -> Result<(), OutputError> {
        write_one(path, |w| self.encode(w))
    }

    /// Encodes the report as pretty JSON (and a newline) into `sink`.
    pub fn encode(&self, sink: &mut dyn WriteSeek) -> std::io::Result<()> {
        serde_json::to_writer_pretty(&mut *sink, self)?;
        sink.write_all(b"\n")
    }
}

/// Counters as a plain-text table, with the phases' times if they were to be timed
/// (`timed`: `RenderOptions::time_phases`).
pub fn stats_table(stats: &RenderStats, observes: Observes, timed: bool) -> String {
    let mut out = String::from("ray kind   rays          hits\n");
    for (name, c) in
        [("camera", stats.camera), ("shadow", stats.shadow), ("indirect", stats.indirect)]
    {
        out += &format!("{name:<10} {:<13} {}\n", c.rays, c.hits);
    }
    let shown = |value: u64, observed: bool| {
        if observed { value.to_string() } else { "not observable".to_string() }
    };
    out += &format!(
        "node visits      {}\nprimitive tests  {}\n",
        shown(stats.traversal.node_visits, observes.node_visits),
        shown(stats.traversal.prim_tests, observes.prim_tests)
    );
    let bounces = stats.bounces;
    let total = bounces.lanes + bounces.scalar;
    if total > 0 {
        // Lights sampled one lane at a time are named only where there are some.
        let near = match bounces.near_lights {
            0 => String::new(),
            n => format!(" ({n} of them lit one lane at a time)"),
        };
        out += &format!(
            "bounces          {total}: {} in vector lanes{near}, {} scalar ({:.1} %)\n",
            bounces.lanes,
            bounces.scalar,
            100.0 * bounces.scalar as f64 / total as f64
        );
    }
    if bounces.cut_trees > 0 {
        out += &format!(
            "cut trees        {} (Whitted samples ended at their ray limit)\n",
            bounces.cut_trees
        );
    }
    if timed && stats.phases.is_empty() {
        out += "phases           not timed: only the path tracer's batched paths have them \
                (--paths batched)\n";
    }
    out + &crate::phase_times::phase_table(&stats.phases)
}
