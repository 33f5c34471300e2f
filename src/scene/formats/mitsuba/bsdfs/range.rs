//! The range a BSDF's number must lie in, whether it is given as a `<float>` or as the
//! colours of a checkerboard read as numbers.

/// What a number must be: the bounds of its range, which is closed unless `open_start`.
#[derive(Clone, Copy)]
pub(super) struct Range {
    pub start: f64,
    pub end: f64,
    pub open_start: bool,
}

pub(super) const UNIT: Range = Range { start: 0.0, end: 1.0, open_start: false };
pub(super) const POSITIVE: Range = Range { start: 0.0, end: f64::INFINITY, open_start: true };
pub(super) const NON_NEGATIVE: Range = Range { start: 0.0, end: f64::INFINITY, open_start: false };
/// Any finite number (a bump map's height).
pub(super) const ANY: Range =
    Range { start: f64::NEG_INFINITY, end: f64::INFINITY, open_start: false };

impl Range {
    pub fn contains(&self, value: f64) -> bool {
        let above = if self.open_start { value > self.start } else { value >= self.start };
        above && value <= self.end && value.is_finite()
    }

    pub fn describe(&self) -> String {
        match (self.open_start, self.end.is_finite()) {
            (true, false) => format!("above {}", self.start),
            (false, false) => format!("at least {}", self.start),
            _ => format!("in [{}, {}]", self.start, self.end),
        }
    }
}
