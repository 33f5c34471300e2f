//! A render in passes over the whole image: each pass adds a range of sample indices of
//! every pixel, so that a stop (`render_stop`) or a checkpoint has an image of every pixel
//! (at most one pass apart after a stop). The sums are exact (`sample_sums`), so the passes
//! add up to the same image bit for bit as one pass would.

use crate::film::Tile;
use crate::limits::EnvError;
use crate::render_stop::StopReason;
use crate::sample_sums::FilmSums;
use crate::stats::RenderStats;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::ops::Range;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// The sample ranges of the passes over `samples`: 1, 1, 2, 4, … samples per pixel, none
/// longer than an eighth of the whole (nor shorter than one sample), so a stop loses at most
/// about an eighth of the render, and the first image comes after one sample per pixel.
pub fn pass_ranges(samples: Range<u32>) -> Vec<Range<u32>> {
    let total = samples.end.saturating_sub(samples.start);
    let longest = total.div_ceil(8).max(1);
    let mut passes = Vec::new();
    let (mut start, mut length) = (samples.start, 1u32);
    while start < samples.end {
        let end = start + length.min(longest).min(samples.end - start);
        passes.push(start..end);
        if passes.len() > 1 {
            length = length.saturating_mul(2);
        }
        start = end;
    }
    passes
}

/// What a render in passes gave.
pub struct Passes {
    pub sums: FilmSums,
    pub stats: RenderStats,
    /// Samples per pixel in `sums` (all of them unless stopped).
    pub spp_done: u32,
    pub stopped: Option<StopReason>,
}

/// Adds the sums of one of this render's tiles into the film, unchecked
/// (`PixelSums::add`): part files from outside are added by `checked_add`.
pub(crate) fn add_tile(film: &mut FilmSums, tile: Tile, sums: &[crate::sample_sums::PixelSums]) {
    for ((x, y), sums) in tile.pixels().zip(sums) {
        let idx = film.index(x, y);
        film.pixels[idx].add(sums);
    }
}

/// Progress as the user sees it: a bar on a terminal; into a pipe or a log, a line at most
/// every few seconds with the samples done, the ray rate and the time left.
pub struct Progress {
    bar: Option<ProgressBar>,
    lines: Option<Mutex<Instant>>,
    line_every: Duration,
    start: Instant,
    units_total: u64,
    units_done: AtomicU64,
    rays: AtomicU64,
    spp_total: u32,
}

/// The longest `EMBRAY_PROGRESS_SECONDS`: past it a log would have no line for days.
const MAX_PROGRESS_SECONDS: f64 = 1e6;

/// How often a progress line is printed into a pipe: `EMBRAY_PROGRESS_SECONDS` (seconds,
/// fractions allowed), or 5 s when unset; any other value is an error naming it.
pub fn progress_interval() -> Result<Duration, EnvError> {
    let name = "EMBRAY_PROGRESS_SECONDS";
    let Some(text) = crate::limits::env_text(name) else { return Ok(Duration::from_secs(5)) };
    match text.parse::<f64>() {
        Ok(seconds) if (0.0..=MAX_PROGRESS_SECONDS).contains(&seconds) => {
            Ok(Duration::from_secs_f64(seconds))
        }
        _ => Err(EnvError {
            name,
            value: crate::excerpt::excerpt(&text),
            expected: "a number of seconds from 0 to 1000000",
        }),
    }
}

impl Progress {
    /// `units`: tiles × passes; `spp`: samples per pixel of the whole render.
    pub fn new(shown: bool, units: u64, spp: u32) -> Self {
        let terminal = std::io::stderr().is_terminal();
        let bar = (shown && terminal).then(|| {
            let bar = ProgressBar::with_draw_target(Some(units), ProgressDrawTarget::stderr());
            if let Ok(style) =
                ProgressStyle::with_template("{bar:40} {percent:>3}% {elapsed}<{eta} {msg}")
            {
                bar.set_style(style);
            }
            bar
        });
        Progress {
            bar,
            lines: (shown && !terminal).then(|| Mutex::new(Instant::now())),
            // The command line refuses a bad value before any work; a library caller gets
            // the default rather than a render stopped over its progress lines.
            line_every: progress_interval().unwrap_or(Duration::from_secs(5)),
            start: Instant::now(),
            units_total: units.max(1),
            units_done: AtomicU64::new(0),
            rays: AtomicU64::new(0),
            spp_total: spp,
        }
    }

    /// One tile of one pass done, having traced `rays`.
    pub fn tile_done(&self, rays: u64) {
        let done = self.units_done.fetch_add(1, Ordering::Relaxed) + 1;
        let rays = self.rays.fetch_add(rays, Ordering::Relaxed) + rays;
        if let Some(bar) = &self.bar {
            bar.inc(1);
        }
        let Some(last) = &self.lines else { return };
        let Ok(mut last) = last.try_lock() else { return };
        if last.elapsed() < self.line_every {
            return;
        }
        *last = Instant::now();
        let elapsed = self.start.elapsed().as_secs_f64();
        let fraction = done as f64 / self.units_total as f64;
        let left = elapsed * (1.0 - fraction) / fraction.max(1e-9);
        let line = format!(
            "rendering: {:3.0} % (about {} of {} spp), {:.2} M rays/s, {:.0} s elapsed, about {:.0} s left\n",
            100.0 * fraction,
            (fraction * f64::from(self.spp_total)) as u32,
            self.spp_total,
            rays as f64 / elapsed.max(1e-9) / 1e6,
            elapsed,
            left
        );
        let _ = std::io::Write::write_all(&mut std::io::stderr(), line.as_bytes());
    }

    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::pass_ranges;

    #[test]
    fn passes_cover_the_samples_once_in_order() {
        for samples in [0..1, 0..2, 0..7, 0..64, 5..300, 0..1_000_000, 3..3] {
            let passes = pass_ranges(samples.clone());
            let flat: Vec<u32> = passes.iter().flat_map(|r| r.clone()).collect();
            assert_eq!(flat, samples.clone().collect::<Vec<_>>(), "{samples:?}");
            let total = samples.len() as u32;
            assert!(passes.iter().all(|p| p.len() as u32 <= total.div_ceil(8).max(1)));
        }
        assert_eq!(
            pass_ranges(0..64),
            [0..1, 1..2, 2..4, 4..8, 8..16, 16..24, 24..32, 32..40, 40..48, 48..56, 56..64]
        );
    }
}
