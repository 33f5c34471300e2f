//! Measurements behind `embray bench`: repeated renders of scenes over a grid of
//! configurations, with times, counters and image error against a reference render, plus
//! the charts, image strip and spawn comparison of the accuracy report.

pub mod accuracy;
pub mod convergence;
pub mod effects_cost;
pub mod grid;
pub mod memory;
pub mod plots;
pub mod procedural;
pub mod queries;
pub mod spawn_report;
pub mod speed;
pub mod strip;
pub mod table;

/// The median of `values` (the upper one for an even count); `NaN` for none.
pub fn median(mut values: Vec<f64>) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}
