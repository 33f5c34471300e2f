//! PNG charts of the accuracy report (plotters, text drawn with a system TrueType font).

use super::grid::Measurement;
use plotters::prelude::*;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Fonts tried, in order (Debian's fonts-dejavu-core, which `scripts/setup.sh` installs).
const FONT_PATHS: &[&str] = &[
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
];

/// Registers a sans-serif font once; false if none is available.
fn font_available() -> bool {
    static REGISTERED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *REGISTERED.get_or_init(|| {
        FONT_PATHS.iter().any(|path| match std::fs::read(path) {
            Ok(bytes) => {
                let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
                plotters::style::register_font("sans-serif", FontStyle::Normal, bytes).is_ok()
            }
            Err(_) => false,
        })
    })
}

type PlotResult = Result<(), Box<dyn std::error::Error>>;
type Area<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;

/// A chart on a white `root` with the report's caption style and margins.
fn chart_on<'a, 'b>(
    root: &'a Area<'b>,
    caption: &str,
    y_labels: u32,
) -> ChartBuilder<'a, 'b, BitMapBackend<'b>> {
    let mut builder = ChartBuilder::on(root);
    builder
        .caption(caption, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(y_labels);
    builder
}

/// Draws one chart with `draw` into a PNG of `size` at `path`.
fn write_chart(
    path: &Path,
    size: (u32, u32),
    rows: &[Measurement],
    draw: fn(&Area, &[Measurement]) -> PlotResult,
) -> Result<(), String> {
    let run = || -> PlotResult {
        let root = BitMapBackend::new(path, size).into_drawing_area();
        root.fill(&WHITE)?;
        draw(&root, rows)?;
        root.present()?;
        Ok(())
    };
    run().map_err(|e| format!("{}: {e}", path.display()))
}

/// Mean relative MSE over scenes, per (render space, backend) and offset.
fn error_series(rows: &[Measurement]) -> BTreeMap<String, Vec<(f64, f64)>> {
    let mut sums: BTreeMap<(String, u64), (f64, usize)> = BTreeMap::new();
    for r in rows {
        let key = (format!("{} / {}", r.render_space, r.backend), r.offset.to_bits());
        let entry = sums.entry(key).or_default();
        entry.0 += r.error.relative_mse;
        entry.1 += 1;
    }
    let mut series: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    for ((name, offset_bits), (sum, n)) in sums {
        let offset = f64::from_bits(offset_bits).max(1.0);
        series.entry(name).or_default().push((offset, (sum / n as f64).max(1e-16)));
    }
    for points in series.values_mut() {
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    series
}

fn draw_error_chart(root: &Area, rows: &[Measurement]) -> PlotResult {
    let series = error_series(rows);
    let max_offset = rows.iter().map(|r| r.offset).fold(10.0f64, f64::max);
    let max_error = series.values().flatten().map(|p| p.1).fold(1e-12f64, f64::max) * 10.0;
    let mut chart =
        chart_on(root, "Image error vs distance from the origin (mean over scenes)", 70)
            .build_cartesian_2d(
                (1.0..max_offset * 2.0).log_scale(),
                (1e-16..max_error).log_scale(),
            )?;
    chart
        .configure_mesh()
        .x_desc("offset (0 drawn at 1)")
        .y_desc("relative MSE vs cameraworld @ 0")
        .x_label_formatter(&|x| format!("{x:.0e}"))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .draw()?;
    for (i, (name, points)) in series.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        chart
            .draw_series(LineSeries::new(points.iter().copied(), color.stroke_width(2)))?
            .label(name.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
            });
        chart.draw_series(points.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
    }
    chart.configure_series_labels().background_style(WHITE.mix(0.8)).border_style(BLACK).draw()?;
    Ok(())
}

fn draw_time_chart(root: &Area, rows: &[Measurement]) -> PlotResult {
    let spaces = ["world", "camera", "cameraworld"];
    let mut backends: Vec<&str> = rows.iter().map(|r| r.backend).collect();
    backends.dedup();
    backends.sort();
    backends.dedup();
    let total = |space: &str, backend: &str| -> f64 {
        rows.iter()
            .filter(|r| r.render_space == space && r.backend == backend && r.offset == 0.0)
            .map(|r| r.render_seconds)
            .sum()
    };
    let max_time = spaces
        .iter()
        .flat_map(|s| backends.iter().map(move |b| total(s, b)))
        .fold(1e-6f64, f64::max)
        * 1.2;
    let groups = spaces.len() as f64;
    let mut chart = chart_on(root, "Render time by render space (offset 0, all scenes)", 60)
        .build_cartesian_2d(0.0..groups, 0.0..max_time)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(spaces.len() * 2 + 1)
        .x_label_formatter(&|x| {
            let i = x.floor() as usize;
            if (x - x.floor() - 0.5).abs() < 1e-6 && i < spaces.len() {
                spaces[i].to_string()
            } else {
                String::new()
            }
        })
        .y_desc("seconds (median run, summed over scenes)")
        .draw()?;
    let width = 0.8 / backends.len().max(1) as f64;
    for (b, backend) in backends.iter().enumerate() {
        let color = Palette99::pick(b).to_rgba();
        chart
            .draw_series(spaces.iter().enumerate().map(|(s, space)| {
                let x0 = s as f64 + 0.1 + b as f64 * width;
                Rectangle::new(
                    [(x0, 0.0), (x0 + width * 0.9, total(space, backend))],
                    color.filled(),
                )
            }))?
            .label(backend.to_string())
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 12, y + 5)], color.filled()));
    }
    chart.configure_series_labels().background_style(WHITE.mix(0.8)).border_style(BLACK).draw()?;
    Ok(())
}

/// Writes the two charts into `dir` as PNG; returns the files written.
pub fn write_charts(dir: &Path, rows: &[Measurement]) -> Result<Vec<PathBuf>, String> {
    if !font_available() {
        return Err(format!(
            "no TrueType font found (looked for {}); install fonts-dejavu-core for the charts",
            FONT_PATHS.join(", ")
        ));
    }
    let size = (900, 560);
    let error_path = dir.join("error_vs_offset.png");
    write_chart(&error_path, size, rows, draw_error_chart)?;
    let time_path = dir.join("time_vs_space.png");
    write_chart(&time_path, size, rows, draw_time_chart)?;
    Ok(vec![error_path, time_path])
}
