//! Measurements as a Markdown table and as CSV.

use super::grid::Measurement;

fn count_or_dash(value: u64, observed: bool) -> String {
    if observed { value.to_string() } else { "–".to_string() }
}

pub fn markdown(rows: &[Measurement]) -> String {
    let mut out = String::from(
        "| scene | offset | space | backend | render s | build ms | Mrays/s | rays | node visits | prim tests | rel. MSE | max abs | px off >1% | NaN/Inf |\n\
         |---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for r in rows {
        let t = r.stats.traversal;
        out += &format!(
            "| {} | {:.0e} | {} | {} | {:.3} | {:.1} | {:.2} | {} | {} | {} | {:.2e} | {:.3} | {:.2}% | {} |\n",
            r.scene,
            r.offset,
            r.render_space,
            r.backend,
            r.render_seconds,
            r.build_seconds * 1e3,
            r.mrays_per_second,
            r.stats.total_rays(),
            count_or_dash(t.node_visits, r.observes.node_visits),
            count_or_dash(t.prim_tests, r.observes.prim_tests),
            r.error.relative_mse,
            r.error.max_abs,
            r.error.fraction_off * 100.0,
            r.error.non_finite + r.error.non_finite_reference,
        );
    }
    out
}

pub fn csv(rows: &[Measurement]) -> String {
    let mut out = String::from(
        "scene,offset,render_space,backend,render_seconds,build_seconds,mrays_per_second,camera_rays,shadow_rays,indirect_rays,camera_hits,shadow_hits,indirect_hits,node_visits,prim_tests,relative_mse,max_abs,fraction_off,non_finite\n",
    );
    for r in rows {
        let s = &r.stats;
        out += &format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
            r.scene,
            r.offset,
            r.render_space,
            r.backend,
            r.render_seconds,
            r.build_seconds,
            r.mrays_per_second,
            s.camera.rays,
            s.shadow.rays,
            s.indirect.rays,
            s.camera.hits,
            s.shadow.hits,
            s.indirect.hits,
            s.traversal.node_visits,
            s.traversal.prim_tests,
            r.error.relative_mse,
            r.error.max_abs,
            r.error.fraction_off,
            r.error.non_finite + r.error.non_finite_reference,
        );
    }
    out
}
