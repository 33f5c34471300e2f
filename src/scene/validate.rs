//! Range checks shared by the converters; each failure names the field, value and line.

use super::error::{Line, SceneError};
use super::source_map::{FieldPath, SourceMap};
use glam::{DVec3, Vec3};
use std::fmt::Display;
use std::path::Path;

/// What the converters need to report errors: the scene file and where its fields are.
pub(crate) struct Ctx<'a> {
    pub file: &'a Path,
    pub map: SourceMap<'a>,
}

impl Ctx<'_> {
    pub(crate) fn line(&self, path: &FieldPath) -> Line {
        self.map.line(path)
    }

    pub(crate) fn out_of_range(
        &self,
        path: &FieldPath,
        value: impl Display,
        requirement: &str,
    ) -> SceneError {
        SceneError::OutOfRange {
            file: self.file.to_path_buf(),
            field: path.to_string(),
            value: value.to_string(),
            requirement: requirement.to_owned(),
            line: self.line(path),
        }
    }

    /// `Ok(())` if `ok`, else an out-of-range error for `value` at `path`.
    pub(crate) fn require(
        &self,
        ok: bool,
        path: &FieldPath,
        value: impl Display,
        requirement: &str,
    ) -> Result<(), SceneError> {
        if ok { Ok(()) } else { Err(self.out_of_range(path, value, requirement)) }
    }

    pub(crate) fn positive(&self, path: &FieldPath, value: f64) -> Result<f64, SceneError> {
        self.require(value > 0.0, path, value, "> 0")?;
        Ok(value)
    }

    pub(crate) fn non_negative(&self, path: &FieldPath, value: f64) -> Result<f64, SceneError> {
        self.require(value >= 0.0, path, value, ">= 0")?;
        Ok(value)
    }

    /// A colour-like triple, each component >= 0 (and <= 1 when `at_most_one`), converted
    /// to f32 (which it must fit).
    pub(crate) fn color(
        &self,
        path: &FieldPath,
        value: [f64; 3],
        at_most_one: bool,
    ) -> Result<Vec3, SceneError> {
        for (i, &c) in value.iter().enumerate() {
            let component = path.index(i);
            if at_most_one {
                self.require((0.0..=1.0).contains(&c), &component, c, "in [0, 1]")?;
            } else {
                self.non_negative(&component, c)?;
                self.require((c as f32).is_finite(), &component, c, "small enough for f32")?;
            }
        }
        Ok(DVec3::from_array(value).as_vec3())
    }
}
