//! What the effects machinery costs a scene that does not use it: the same static scene
//! rendered normally and with every effect forced on (time and lens samples drawn, every
//! object given a motion BVH), alternating runs so machine noise hits both alike.

use super::median;
use crate::accel::BackendKind;
use crate::choice::Choice;
use crate::compile::EffectsMode;
use crate::render::{RenderError, RenderOptions, render};
use crate::scene::SceneDesc;
use crate::stats::RenderStats;

#[derive(Clone, Debug, serde::Serialize)]
pub struct EffectsCostRow {
    pub backend: &'static str,
    pub normal_seconds: f64,
    pub forced_seconds: f64,
    pub normal_build_ms: f64,
    pub forced_build_ms: f64,
    pub normal_stats: RenderStats,
    pub forced_stats: RenderStats,
}

pub fn measure(
    scene: &SceneDesc,
    base: &RenderOptions,
    backends: &[BackendKind],
    runs: usize,
) -> Result<Vec<EffectsCostRow>, RenderError> {
    let mut rows = Vec::new();
    for &backend in backends {
        let mut normal = base.clone();
        normal.backend = backend;
        normal.effects_mode = EffectsMode::Auto;
        let mut forced = normal.clone();
        forced.effects_mode = EffectsMode::ForceAll;
        let (mut times, mut builds) = ([Vec::new(), Vec::new()], [Vec::new(), Vec::new()]);
        let mut stats = [RenderStats::default(); 2];
        for _ in 0..runs.max(1) {
            for (i, options) in [&normal, &forced].into_iter().enumerate() {
                let out = render(scene, options)?;
                times[i].push(out.render_time.as_secs_f64());
                builds[i].push(out.build_time.as_secs_f64() * 1e3);
                stats[i] = out.stats;
            }
        }
        let [normal_times, forced_times] = times;
        let [normal_builds, forced_builds] = builds;
        rows.push(EffectsCostRow {
            backend: backend.name(),
            normal_seconds: median(normal_times),
            forced_seconds: median(forced_times),
            normal_build_ms: median(normal_builds),
            forced_build_ms: median(forced_builds),
            normal_stats: stats[0],
            forced_stats: stats[1],
        });
    }
    Ok(rows)
}

pub fn markdown(rows: &[EffectsCostRow]) -> String {
    let mut out = String::from(
        "| backend | normal render s | all effects forced s | ratio | build ms normal / forced | rays normal | rays forced |\n|---|---:|---:|---:|---:|---:|---:|\n",
    );
    for r in rows {
        out += &format!(
            "| {} | {:.3} | {:.3} | {:.2}× | {:.1} / {:.1} | {} | {} |\n",
            r.backend,
            r.normal_seconds,
            r.forced_seconds,
            r.forced_seconds / r.normal_seconds.max(1e-9),
            r.normal_build_ms,
            r.forced_build_ms,
            r.normal_stats.total_rays(),
            r.forced_stats.total_rays()
        );
    }
    out
}
