//! Merging parts: check that the files belong to one render and cover it exactly once, then
//! add their exact sums, one part in memory at a time.

use super::metadata::{PartMeta, PartTiming};
use super::option_words::options_difference;
use super::part::{Part, Split};
use super::part_file::{PartFileError, read_part_meta, read_part_sums};
use crate::sample_sums::FilmSums;
use crate::stats::RenderStats;
use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    #[error(transparent)]
    File(#[from] PartFileError),
    #[error("no part files given")]
    Empty,
    #[error(
        "'{}' does not belong with '{}': {what} differs ({theirs} vs {ours})",
        .path.display(), .first.display()
    )]
    Mismatch { path: PathBuf, first: PathBuf, what: String, theirs: String, ours: String },
    #[error(
        "'{}' does not belong with '{}': the render options differ ({theirs} vs {ours})",
        .path.display(), .first.display()
    )]
    OptionMismatch { path: PathBuf, first: PathBuf, theirs: String, ours: String },
    #[error("part {part} is given twice: '{}' and '{}'", .first.display(), .second.display())]
    Duplicate { part: Part, first: PathBuf, second: PathBuf },
    #[error(
        "{} of the {count} parts {} missing: {list} (parts count from 0; `embray slurm resume` or \
         `embray render SCENE --part I/{count}` makes them; `embray merge --partial` previews the \
         parts there are)",
        .missing.len(),
        if .missing.len() == 1 { "is" } else { "are" },
        list = .missing.iter().map(|i| format!("{i}/{count}")).collect::<Vec<_>>().join(", ")
    )]
    Missing { missing: Vec<u32>, count: u32 },
    #[error(
        "part file '{}' is damaged: pixel ({x}, {y}) has {found} samples, but part {part} \
         renders {expected} there", .path.display()
    )]
    Coverage { path: PathBuf, part: Part, x: u32, y: u32, found: u32, expected: u32 },
    #[error("part file '{}' is damaged: a sum of pixel ({x}, {y}) overflows", .path.display())]
    Overflow { path: PathBuf, x: u32, y: u32 },
    #[error(
        "merging a {width}x{height} image needs about {needed} MiB, more than the {available} \
         MiB available"
    )]
    Memory { width: u32, height: u32, needed: u64, available: u64 },
}

/// A part file's path and metadata.
pub type PartFile = (PathBuf, PartMeta);

/// Reads every part's metadata and checks that they are the parts of one render, each
/// exactly once. Returns them in part order.
pub fn check_parts(paths: &[PathBuf]) -> Result<Vec<PartFile>, MergeError> {
    let (parts, missing) = check_some_parts(paths)?;
    match missing.first() {
        None => Ok(parts),
        Some(_) => Err(MergeError::Missing { missing, count: parts[0].1.part.count }),
    }
}

/// As [`check_parts`], allowing parts to be missing: the parts given, in part order, and
/// the indices of those not given.
fn check_some_parts(paths: &[PathBuf]) -> Result<(Vec<PartFile>, Vec<u32>), MergeError> {
    let Some(first_path) = paths.first() else {
        return Err(MergeError::Empty);
    };
    let first_meta = read_part_meta(first_path)?;
    let mut slots: Vec<Option<(PathBuf, PartMeta)>> = vec![None; first_meta.part.count as usize];
    for path in paths {
        let meta = read_part_meta(path)?;
        let (path, first) = (path.clone(), first_path.clone());
        match render_difference(&meta, &first_meta) {
            Some(Difference::Field { what, theirs, ours }) => {
                let what = what.to_owned();
                return Err(MergeError::Mismatch { path, first, what, theirs, ours });
            }
            Some(Difference::Options { theirs, ours }) => {
                return Err(MergeError::OptionMismatch { path, first, theirs, ours });
            }
            None => {}
        }
        let slot = &mut slots[meta.part.index as usize];
        if let Some((earlier, _)) = slot {
            return Err(MergeError::Duplicate {
                part: meta.part,
                first: earlier.clone(),
                second: path.clone(),
            });
        }
        *slot = Some((path.clone(), meta));
    }
    let missing: Vec<u32> =
        slots.iter().enumerate().filter(|(_, s)| s.is_none()).map(|(i, _)| i as u32).collect();
    Ok((slots.into_iter().flatten().collect(), missing))
}

/// How a part differs from another in what makes them one render.
enum Difference {
    /// A field of `PartMeta::shared_fields` (named there), with both values.
    Field { what: &'static str, theirs: String, ours: String },
    /// The render options, each as the command line writes it.
    Options { theirs: String, ours: String },
}

/// The first way `meta` differs from `first` in what makes them one render, if any.
fn render_difference(meta: &PartMeta, first: &PartMeta) -> Option<Difference> {
    let shared = meta.shared_fields().into_iter().zip(first.shared_fields());
    for ((what, theirs), (_, ours)) in shared {
        if theirs != ours {
            return Some(Difference::Field { what, theirs, ours });
        }
    }
    let (theirs, ours) = options_difference(&meta.options, &first.options)?;
    Some(Difference::Options { theirs, ours })
}

/// What a part must record to be a part of the render a new part would make now: the
/// scene's contents and the render options (`embray slurm status` and `resume` check each
/// part file of a job against them).
#[derive(Clone, Debug, PartialEq)]
pub struct PartIdentity {
    pub scene_hash: String,
    pub options: String,
}

/// How `meta` differs from `identity` (checked as `merge` checks two parts), worded for a
/// status line; `None` when it is a part of that render.
pub fn identity_difference(meta: &PartMeta, identity: &PartIdentity) -> Option<String> {
    let scene_hash = identity.scene_hash.clone();
    let expected = PartMeta { scene_hash, options: identity.options.clone(), ..meta.clone() };
    Some(match render_difference(meta, &expected)? {
        Difference::Field { what, theirs, ours } => {
            format!("{what} differs (the part's {theirs} vs {ours} now)")
        }
        Difference::Options { theirs, ours } => {
            format!("rendered with {theirs}, the job's options now give {ours}")
        }
    })
}

/// What merging gave.
pub struct Merged {
    pub sums: FilmSums,
    /// The first part's metadata (all share what matters).
    pub meta: PartMeta,
    /// The counters of all parts added.
    pub stats: RenderStats,
    /// Each part's times, in part order.
    pub timings: Vec<PartTiming>,
    /// The parts not given (only a partial merge has any).
    pub missing: Vec<u32>,
}

impl Merged {
    /// Samples per pixel the merged image holds where its parts rendered: all of them,
    /// but for missing sample ranges.
    pub fn spp_reached(&self) -> u32 {
        let meta = &self.meta;
        let lost = |&index| Part { index, ..meta.part }.samples(meta.spp).len() as u32;
        match meta.part.split {
            Split::Samples => meta.spp - self.missing.iter().map(lost).sum::<u32>(),
            Split::Tiles => meta.spp,
        }
    }
}

/// The merged sums of the parts `paths`, checked by [`check_parts`] first.
pub fn merge_parts(paths: &[PathBuf]) -> Result<Merged, MergeError> {
    let parts = check_parts(paths)?;
    merge_checked(parts, Vec::new())
}

/// A preview from the parts that exist: as [`merge_parts`], but parts may be missing (their
/// tiles stay black with alpha 0, or their sample ranges are left out of every mean).
pub fn merge_some_parts(paths: &[PathBuf]) -> Result<Merged, MergeError> {
    let (parts, missing) = check_some_parts(paths)?;
    merge_checked(parts, missing)
}

fn merge_checked(parts: Vec<(PathBuf, PartMeta)>, missing: Vec<u32>) -> Result<Merged, MergeError> {
    let (_, first) = &parts[0];
    check_merge_memory(first.width, first.height)?;
    let mut total = FilmSums::new(first.width, first.height);
    let mut stats = RenderStats::default();
    for (path, meta) in &parts {
        // The file's layout places exactly the part's pixels; each must hold its samples.
        let expected = meta.part.samples(meta.spp).len() as u32;
        for (i, sums) in read_part_sums(path, meta)? {
            let (x, y) = ((i % first.width as usize) as u32, (i / first.width as usize) as u32);
            if sums.samples != expected || sums.depth_samples > sums.samples {
                let found = sums.samples;
                let part = meta.part;
                return Err(MergeError::Coverage {
                    path: path.clone(),
                    part,
                    x,
                    y,
                    found,
                    expected,
                });
            }
            total.pixels[i] = total.pixels[i]
                .checked_add(&sums)
                .ok_or_else(|| MergeError::Overflow { path: path.clone(), x, y })?;
        }
        stats += meta.stats;
    }
    // Each part exactly once and each part's layout exact: every pixel has every sample.
    if let Some(i) =
        total.pixels.iter().position(|p| p.samples != first.spp).filter(|_| missing.is_empty())
    {
        let (x, y) = ((i % first.width as usize) as u32, (i / first.width as usize) as u32);
        let (path, meta) = &parts[0];
        let found = total.pixels[i].samples;
        return Err(MergeError::Coverage {
            path: path.clone(),
            part: meta.part,
            x,
            y,
            found,
            expected: first.spp,
        });
    }
    let timings = parts.iter().map(|(_, m)| m.timing.clone()).collect();
    Ok(Merged { sums: total, meta: first.clone(), stats, timings, missing })
}

/// The merge holds the merged sums and one part's: refused before allocating when that
/// would not fit.
fn check_merge_memory(width: u32, height: u32) -> Result<(), MergeError> {
    let pixels = width as u64 * height as u64;
    let per_pixel = 2 * std::mem::size_of::<crate::sample_sums::PixelSums>() as u64
        + super::part_file::BYTES_PER_PIXEL * 2
        + crate::limits::BYTES_PER_PIXEL;
    let needed = pixels.saturating_mul(per_pixel);
    if let Some(available) = crate::limits::memory_available()
        && needed > available
    {
        return Err(MergeError::Memory {
            width,
            height,
            needed: needed >> 20,
            available: available >> 20,
        });
    }
    Ok(())
}
