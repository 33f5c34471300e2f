//! Where an object goes (at shutter open and close) and the `repeat` grids of copies.

use glam::{DAffine3, DVec3};

/// Where an object goes: at shutter open, and at shutter close if it moves.
#[derive(Clone, Copy)]
pub(crate) struct Placement {
    pub(crate) start: DAffine3,
    pub(crate) end: Option<DAffine3>,
}

impl Placement {
    pub(crate) fn fixed(start: DAffine3) -> Self {
        Placement { start, end: None }
    }

    /// Both placements moved by `offset` in world space (exactly: only the translations
    /// change).
    pub(crate) fn shifted(&self, offset: DVec3) -> Placement {
        let shift =
            |t: DAffine3| DAffine3 { matrix3: t.matrix3, translation: t.translation + offset };
        Placement { start: shift(self.start), end: self.end.map(shift) }
    }
}

/// A validated `repeat`: `count` copies along each axis, `spacing` apart.
#[derive(Clone, Copy)]
pub(crate) struct Grid {
    pub(crate) count: [u32; 3],
    pub(crate) spacing: DVec3,
}

impl Grid {
    pub(crate) fn offsets(&self) -> impl Iterator<Item = ([u32; 3], DVec3)> + use<> {
        let Grid { count: [nx, ny, nz], spacing } = *self;
        (0..nx).flat_map(move |i| {
            (0..ny).flat_map(move |j| {
                (0..nz).map(move |k| {
                    let offset = DVec3::new(i as f64, j as f64, k as f64) * spacing;
                    ([i, j, k], offset)
                })
            })
        })
    }

    pub(crate) fn total(&self) -> usize {
        self.count.iter().map(|&n| n as usize).product()
    }
}
