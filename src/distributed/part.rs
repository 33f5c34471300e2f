//! Which share of a render one task computes: part `index` of `count`, split by tiles or by
//! sample ranges.

use crate::film::Tile;
use serde::{Deserialize, Serialize};
use std::fmt;

/// How a render is divided among parts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Split {
    /// Every part renders all samples of some tiles: tile `t` (row-major) belongs to part
    /// `t mod count`, so each part gets tiles from all over the image and the parts take
    /// about the same time.
    #[default]
    Tiles,
    /// Every part renders a range of sample indices of every pixel.
    Samples,
}

crate::choice::named_choices!(Split, "split", { Tiles => "tiles", Samples => "samples" });

/// Part `index` (from 0) of `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Part {
    pub index: u32,
    pub count: u32,
    pub split: Split,
}

/// Most parts one render may be split into.
pub const MAX_PARTS: u32 = 100_000;

#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum PartError {
    #[error("--part '{0}' is not of the form I/N (e.g. 0/4: the first of four parts)")]
    Syntax(String),
    #[error("--part {index}/{count}: the index counts from 0, so it must be below {count}")]
    Index { index: u32, count: u32 },
    #[error("--part {index}/{count}: a render can be split into 1 to {MAX_PARTS} parts")]
    Count { index: u32, count: u32 },
    #[error(
        "a render at {spp} spp cannot be split into {count} sample ranges (each part needs at \
         least one sample): use fewer parts or --split tiles"
    )]
    TooFewSamples { spp: u32, count: u32 },
    #[error(
        "a {width}x{height} image has {tiles} tiles of {size}x{size}, too few for {count} tile \
         parts: use fewer parts or --split samples"
    )]
    TooFewTiles { width: u32, height: u32, tiles: usize, size: u32, count: u32 },
}

impl Part {
    /// The whole render as one part.
    pub const WHOLE: Part = Part { index: 0, count: 1, split: Split::Tiles };

    /// Parses `I/N`.
    pub fn parse(text: &str, split: Split) -> Result<Part, PartError> {
        let syntax = || PartError::Syntax(crate::excerpt::excerpt(text));
        let (i, n) = text.split_once('/').ok_or_else(syntax)?;
        let index: u32 = i.trim().parse().map_err(|_| syntax())?;
        let count: u32 = n.trim().parse().map_err(|_| syntax())?;
        if count == 0 || count > MAX_PARTS {
            return Err(PartError::Count { index, count });
        }
        if index >= count {
            return Err(PartError::Index { index, count });
        }
        Ok(Part { index, count, split })
    }

    /// Checks that every part of this split gets some work for an image of `tiles` tiles at
    /// `spp` samples per pixel.
    pub fn check(
        &self,
        (width, height): (u32, u32),
        tile_size: u32,
        spp: u32,
    ) -> Result<(), PartError> {
        match self.split {
            Split::Samples if spp < self.count => {
                Err(PartError::TooFewSamples { spp, count: self.count })
            }
            Split::Tiles => {
                let tiles = crate::film::tiles(width, height, tile_size).len();
                if tiles < self.count as usize {
                    return Err(PartError::TooFewTiles {
                        width,
                        height,
                        tiles,
                        size: tile_size,
                        count: self.count,
                    });
                }
                Ok(())
            }
            Split::Samples => Ok(()),
        }
    }

    /// The sample indices this part renders of each of its pixels, `spp` in all.
    pub fn samples(&self, spp: u32) -> std::ops::Range<u32> {
        match self.split {
            Split::Tiles => 0..spp,
            Split::Samples => {
                let bound = |i: u32| (u64::from(spp) * u64::from(i) / u64::from(self.count)) as u32;
                bound(self.index)..bound(self.index + 1)
            }
        }
    }

    /// Whether tile number `tile` (row-major) is this part's.
    pub fn owns_tile(&self, tile: usize) -> bool {
        match self.split {
            Split::Tiles => tile % self.count as usize == self.index as usize,
            Split::Samples => true,
        }
    }

    /// The tiles of `all` (row-major) this part renders.
    pub fn tiles(&self, all: &[Tile]) -> Vec<Tile> {
        all.iter().enumerate().filter(|(i, _)| self.owns_tile(*i)).map(|(_, t)| *t).collect()
    }
}

impl fmt::Display for Part {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_ranges_cover_every_sample_once() {
        for count in [1, 2, 3, 7] {
            let mut next = 0;
            for index in 0..count {
                let part = Part { index, count, split: Split::Samples };
                let range = part.samples(64);
                assert_eq!(range.start, next);
                assert!(!range.is_empty());
                next = range.end;
            }
            assert_eq!(next, 64);
        }
    }

    #[test]
    fn tiles_go_to_exactly_one_part() {
        let all = crate::film::tiles(100, 70, 16);
        let mut owners = vec![0; all.len()];
        for index in 0..7 {
            let part = Part { index, count: 7, split: Split::Tiles };
            for (t, owner) in owners.iter_mut().enumerate() {
                *owner += part.owns_tile(t) as u32;
            }
        }
        assert!(owners.iter().all(|&n| n == 1));
    }

    #[test]
    fn bad_part_specifications_are_refused() {
        assert_eq!(Part::parse("4/4", Split::Tiles), Err(PartError::Index { index: 4, count: 4 }));
        assert_eq!(Part::parse("0/0", Split::Tiles), Err(PartError::Count { index: 0, count: 0 }));
        assert!(matches!(Part::parse("1-4", Split::Tiles), Err(PartError::Syntax(_))));
        assert!(matches!(Part::parse("-1/4", Split::Tiles), Err(PartError::Syntax(_))));
        let part = Part::parse(" 2 / 3", Split::Samples).unwrap();
        assert_eq!(part, Part { index: 2, count: 3, split: Split::Samples });
        assert!(part.check((8, 8), 16, 2).is_err());
        assert!(Part::parse("2/3", Split::Tiles).unwrap().check((16, 16), 16, 64).is_err());
    }
}
