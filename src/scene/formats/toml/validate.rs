//! Range checks shared by the converters; each failure names the field, value and line.

use crate::excerpt::short_number;
use crate::scene::error::{Line, SceneError};
use crate::scene::formats::toml::source_map::{FieldPath, SourceMap};
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
            value: short_number(value.to_string()),
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

    /// A sphere's radius that render space holds in f32 with its square (the ray–sphere
    /// test and the area take r²: below about 1.08e-19 it is subnormal or 0 in f32, and the
    /// sphere, or the light it is, vanishes without a word).
    pub(crate) fn positive_radius(&self, path: &FieldPath, value: f64) -> Result<f64, SceneError> {
        let least = f64::from(f32::MIN_POSITIVE).sqrt();
        let requirement =
            format!("> 0 and at least {least:e} (its square is f32's smallest normal number)");
        // (Too large a radius is the coordinate limit's to refuse, with its own message.)
        self.require(value >= least, path, value, &requirement)?;
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

    /// A scalar that the renderer keeps in f32: checked to fit.
    pub(crate) fn f32(&self, path: &FieldPath, value: f64) -> Result<f32, SceneError> {
        self.require((value as f32).is_finite(), path, value, "small enough for f32")?;
        Ok(value as f32)
    }

    /// Rejects fields the type does not take; `present` lists every optional field with
    /// whether it is set, `allowed` the fields this type takes.
    pub(crate) fn check_fields(
        &self,
        path: &FieldPath,
        item: &str,
        present: &[(&str, bool)],
        allowed: &[&str],
    ) -> Result<(), SceneError> {
        let Some((field, _)) = present.iter().find(|(name, set)| *set && !allowed.contains(name))
        else {
            return Ok(());
        };
        Err(SceneError::FieldNotAllowed {
            file: self.file.to_path_buf(),
            item: item.to_owned(),
            field: (*field).to_owned(),
            allowed: allowed.join(", "),
            line: self.line(&path.key(field)),
        })
    }

    /// `value`, or a missing-field error for `item` (at the line of `path`, the item).
    pub(crate) fn required<T>(
        &self,
        path: &FieldPath,
        item: &str,
        field: &str,
        value: Option<T>,
    ) -> Result<T, SceneError> {
        value.ok_or_else(|| self.missing(path, item, field))
    }

    pub(crate) fn missing(&self, path: &FieldPath, item: &str, field: &str) -> SceneError {
        SceneError::MissingField {
            file: self.file.to_path_buf(),
            item: item.to_owned(),
            field: field.to_owned(),
            line: self.line(path),
        }
    }

    /// `first` and `second` were both given; the line is that of `second`.
    pub(crate) fn conflict(
        &self,
        path: &FieldPath,
        item: &str,
        first: &str,
        second: &str,
    ) -> SceneError {
        SceneError::Conflict {
            file: self.file.to_path_buf(),
            item: item.to_owned(),
            first: first.to_owned(),
            second: second.to_owned(),
            line: self.line(&path.key(second)),
        }
    }
}
