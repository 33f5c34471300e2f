//! Measurements behind `embray bench`: repeated renders of one scene over a grid of
//! configurations, with times, counters and image error against a reference render.

pub mod grid;
pub mod table;
