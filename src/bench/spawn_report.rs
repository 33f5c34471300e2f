//! Robust spawning against a fixed epsilon: time and the artefacts each causes.

use crate::accel::BackendKind;
use crate::choice::Choice;
use crate::render::{RenderError, RenderOptions, render};
use crate::render_space::RenderSpace;
use crate::scene::SceneDesc;
use crate::shading::spawn::SpawnMode;
use glam::DVec3;

#[derive(Clone, Debug, serde::Serialize)]
pub struct SpawnRow {
    pub method: String,
    pub backend: &'static str,
    /// Median render time of both scenes together, seconds.
    pub seconds: f64,
    /// Grazing plane at offset 1e6 in `world` space: fraction of shadow rays that hit the
    /// plane they left (the only geometry in the scene).
    pub self_shadowed_world: f64,
    /// The same in `cameraworld`.
    pub self_shadowed_cameraworld: f64,
    /// Thin-wall scene: fraction of the shadow rays the robust method finds blocked that
    /// this method lets through (light leaking past the 1 mm sheet).
    pub leaked: f64,
}

/// Compares spawn `methods` on the grazing-plane and thin-wall scenes.
pub fn compare(
    grazing: &SceneDesc,
    thin_walls: &SceneDesc,
    base: &RenderOptions,
    backends: &[BackendKind],
    methods: &[SpawnMode],
    runs: usize,
) -> Result<Vec<SpawnRow>, RenderError> {
    let mut rows = Vec::new();
    for &backend in backends {
        // What leaks is measured against robust spawning, whatever the methods' order.
        let mut robust = base.clone();
        robust.backend = backend;
        robust.spawn = SpawnMode::Robust;
        let reference = render(thin_walls, &robust)?.stats.shadow.hits;
        for &method in methods {
            let mut o = base.clone();
            o.backend = backend;
            o.spawn = method;
            let mut seconds = Vec::new();
            let mut self_shadowed = [0.0; 2];
            let mut blocked = 0;
            for _ in 0..runs.max(1) {
                let mut total = 0.0;
                for (i, space) in
                    [RenderSpace::World, RenderSpace::Cameraworld].into_iter().enumerate()
                {
                    let mut g = o.clone();
                    g.render_space = space;
                    g.offset = DVec3::splat(1e6);
                    let out = render(grazing, &g)?;
                    total += out.render_time.as_secs_f64();
                    self_shadowed[i] =
                        out.stats.shadow.hits as f64 / out.stats.shadow.rays.max(1) as f64;
                }
                let out = render(thin_walls, &o)?;
                total += out.render_time.as_secs_f64();
                blocked = out.stats.shadow.hits;
                seconds.push(total);
            }
            seconds.sort_by(f64::total_cmp);
            let leaked = if reference > 0 {
                reference.saturating_sub(blocked) as f64 / reference as f64
            } else {
                0.0
            };
            rows.push(SpawnRow {
                method: method.name(),
                backend: backend.name(),
                seconds: seconds[seconds.len() / 2],
                self_shadowed_world: self_shadowed[0],
                self_shadowed_cameraworld: self_shadowed[1],
                leaked,
            });
        }
    }
    Ok(rows)
}

pub fn markdown(rows: &[SpawnRow]) -> String {
    let mut out = String::from(
        "| spawn | backend | time s | self-shadowed (grazing, world @1e6) | self-shadowed (grazing, cameraworld @1e6) | leaked (thin walls) |\n|---|---|---:|---:|---:|---:|\n",
    );
    for r in rows {
        out += &format!(
            "| {} | {} | {:.3} | {:.2}% | {:.2}% | {:.2}% |\n",
            r.method,
            r.backend,
            r.seconds,
            r.self_shadowed_world * 100.0,
            r.self_shadowed_cameraworld * 100.0,
            r.leaked * 100.0
        );
    }
    out
}
