//! A kind's parameters as a reader found them, whatever the format: named values, each with
//! the name the user wrote and its line, so that the kind (a light, and next a BSDF or a
//! shape) reads and checks its own parameters and every error still names the file, the
//! line and the field. Readers translate their syntax into `Params`; kinds write themselves
//! back through a `ParamSink`. This is Mitsuba's `Properties` and pbrt's `ParameterDictionary`.

use glam::{DVec3, Vec3};
use std::sync::Arc;

use crate::texels::TextureImage;

/// A value as written: TOML numbers and arrays, or an XML element's numbers.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Number(f64),
    Numbers(Vec<f64>),
    Text(String),
    Bool(bool),
    /// Anything else (a table, a mixed array), kept as written for messages.
    Other(String),
}

impl Value {
    fn numbers(&self) -> Option<&[f64]> {
        match self {
            Value::Number(x) => Some(std::slice::from_ref(x)),
            Value::Numbers(v) => Some(v),
            _ => None,
        }
    }
}

/// One parameter: the kind's name for it, its value, and where it was written.
#[derive(Clone, Debug)]
pub struct Entry {
    pub name: String,
    pub value: Value,
    /// The field as the user wrote it (`lights[0].intensity`, `<Lights > PointLight id="1" >
    /// Intensity>`).
    pub field: String,
    pub line: Option<usize>,
    /// Whether a component is named by appending `[i]` to `field` (TOML arrays).
    pub indexed: bool,
}

/// What went wrong with a parameter; the scene loader turns it into its own error type.
#[derive(Debug, thiserror::Error)]
pub enum ParamError {
    #[error("{field} is {value}, but must be {requirement}")]
    OutOfRange { field: String, value: String, requirement: String, line: Option<usize> },
    #[error("{item} is missing the field `{field}`")]
    Missing { item: String, field: String, line: Option<usize> },
    #[error("{item} does not take the field `{field}` (it takes: {allowed})")]
    NotAllowed { item: String, field: String, allowed: String, line: Option<usize> },
    #[error("{item} takes `{first}` or `{second}`, not both")]
    Conflict { item: String, first: String, second: String, line: Option<usize> },
    /// An error of the reader's own (an image that cannot be read), passed through whole.
    #[error(transparent)]
    Reader(Box<dyn std::error::Error + Send + Sync>),
}

/// What a kind may need from the reader beyond values: files, resolved where the scene is.
pub trait Resources {
    /// The radiance image named by the text parameter `name`; `srgb` says how 8-bit images
    /// are decoded (ignored for EXR).
    fn radiance_image(
        &self,
        params: &Params,
        name: &str,
        srgb: bool,
    ) -> Result<Arc<TextureImage>, ParamError>;
}

/// The parameters of one item of a scene.
#[derive(Debug)]
pub struct Params {
    /// The item, as messages name it (`lights[0] (spot light)`).
    pub item: String,
    pub item_line: Option<usize>,
    entries: Vec<Entry>,
    /// (format's name, kind's name) where they differ, so that a missing field is named as
    /// the user would write it.
    renames: &'static [(&'static str, &'static str)],
}

impl Params {
    pub fn new(item: String, item_line: Option<usize>, entries: Vec<Entry>) -> Self {
        Params { item, item_line, entries, renames: &[] }
    }

    pub fn with_renames(mut self, renames: &'static [(&'static str, &'static str)]) -> Self {
        self.renames = renames;
        self
    }

    /// Adds a parameter the reader derived (a position from a placement).
    pub fn push(&mut self, entry: Entry) {
        self.entries.push(entry);
    }

    fn entry(&self, name: &str) -> Option<&Entry> {
        self.entries.iter().find(|e| e.name == name)
    }

    pub fn has(&self, name: &str) -> bool {
        self.entry(name).is_some()
    }

    /// The name the user writes for the kind's parameter `name`.
    pub fn spelling(&self, name: &str) -> String {
        let renamed = self.renames.iter().find(|(_, kind)| *kind == name);
        renamed.map_or(name, |(format, _)| format).to_owned()
    }

    /// Refuses a parameter the kind does not take; `fields` are all the kind takes.
    pub fn check_fields(&self, fields: &[&str]) -> Result<(), ParamError> {
        match self.entries.iter().find(|e| !fields.contains(&e.name.as_str())) {
            None => Ok(()),
            Some(entry) => Err(ParamError::NotAllowed {
                item: self.item.clone(),
                field: self.spelling(&entry.name),
                allowed: fields.iter().map(|f| self.spelling(f)).collect::<Vec<_>>().join(", "),
                line: entry.line,
            }),
        }
    }

    pub fn missing(&self, name: &str) -> ParamError {
        ParamError::Missing {
            item: self.item.clone(),
            field: self.spelling(name),
            line: self.item_line,
        }
    }

    pub fn conflict(&self, first: &str, second: &str) -> ParamError {
        let line = self.entry(second).and_then(|e| e.line);
        let (first, second) = (self.spelling(first), self.spelling(second));
        ParamError::Conflict { item: self.item.clone(), first, second, line }
    }

    /// An out-of-range error for the parameter `name` (or the item, when it is absent).
    pub fn out_of_range(&self, name: &str, value: impl ToString, requirement: &str) -> ParamError {
        let (field, line) = match self.entry(name) {
            Some(e) => (e.field.clone(), e.line),
            None => (self.spelling(name), self.item_line),
        };
        let (value, requirement) = (value.to_string(), requirement.to_owned());
        ParamError::OutOfRange { field, value, requirement, line }
    }

    pub fn require(
        &self,
        ok: bool,
        name: &str,
        value: impl ToString,
        requirement: &str,
    ) -> Result<(), ParamError> {
        if ok { Ok(()) } else { Err(self.out_of_range(name, value, requirement)) }
    }

    /// Exactly `N` numbers, or `None` when absent.
    pub fn numbers<const N: usize>(&self, name: &str) -> Result<Option<[f64; N]>, ParamError> {
        let Some(entry) = self.entry(name) else { return Ok(None) };
        let found = entry.value.numbers().and_then(|v| <[f64; N]>::try_from(v).ok());
        let requirement = match N {
            1 => "a number".to_owned(),
            n => format!("{n} numbers"),
        };
        found.map(Some).ok_or_else(|| self.out_of_range(name, show(&entry.value), &requirement))
    }

    pub fn opt_number(&self, name: &str) -> Result<Option<f64>, ParamError> {
        Ok(self.numbers::<1>(name)?.map(|[x]| x))
    }

    pub fn number(&self, name: &str) -> Result<f64, ParamError> {
        self.opt_number(name)?.ok_or_else(|| self.missing(name))
    }

    pub fn positive(&self, name: &str) -> Result<f64, ParamError> {
        let value = self.number(name)?;
        self.require(value > 0.0, name, value, "> 0")?;
        Ok(value)
    }

    pub fn opt_vec3(&self, name: &str) -> Result<Option<DVec3>, ParamError> {
        Ok(self.numbers::<3>(name)?.map(DVec3::from_array))
    }

    pub fn vec3(&self, name: &str) -> Result<DVec3, ParamError> {
        self.opt_vec3(name)?.ok_or_else(|| self.missing(name))
    }

    /// A unit vector from a non-zero one.
    pub fn direction(&self, name: &str) -> Result<DVec3, ParamError> {
        let v = self.vec3(name)?;
        v.try_normalize().ok_or_else(|| self.out_of_range(name, show_vec(v), "a non-zero vector"))
    }

    /// A colour-like triple, each component >= 0 and small enough for f32.
    pub fn opt_color(&self, name: &str) -> Result<Option<Vec3>, ParamError> {
        let Some(v) = self.numbers::<3>(name)? else { return Ok(None) };
        let entry = self.entry(name).expect("a value read has an entry");
        for (i, &c) in v.iter().enumerate() {
            if !(c >= 0.0 && (c as f32).is_finite()) {
                let field = if entry.indexed {
                    format!("{}[{i}]", entry.field)
                } else {
                    entry.field.clone()
                };
                let requirement = if c >= 0.0 { "small enough for f32" } else { ">= 0" };
                let (value, requirement) = (show_large(c), requirement.to_owned());
                return Err(ParamError::OutOfRange { field, value, requirement, line: entry.line });
            }
        }
        Ok(Some(DVec3::from_array(v).as_vec3()))
    }

    pub fn color(&self, name: &str) -> Result<Vec3, ParamError> {
        self.opt_color(name)?.ok_or_else(|| self.missing(name))
    }

    pub fn opt_text(&self, name: &str) -> Result<Option<&str>, ParamError> {
        match self.entry(name) {
            None => Ok(None),
            Some(Entry { value: Value::Text(text), .. }) => Ok(Some(text)),
            Some(e) => Err(self.out_of_range(name, show(&e.value), "a string")),
        }
    }

    /// One of `choices` (the text parameter `name`), or `None` when absent.
    pub fn opt_choice<T: Copy>(
        &self,
        name: &str,
        choices: &[(&str, T)],
    ) -> Result<Option<T>, ParamError> {
        let Some(text) = self.opt_text(name)? else { return Ok(None) };
        match choices.iter().find(|(spelled, _)| *spelled == text) {
            Some((_, choice)) => Ok(Some(*choice)),
            None => {
                let names: Vec<&str> = choices.iter().map(|(spelled, _)| *spelled).collect();
                let requirement = format!("one of {}", names.join(", "));
                Err(self.out_of_range(name, format!("{text:?}"), &requirement))
            }
        }
    }

    /// The line of parameter `name`.
    pub fn line(&self, name: &str) -> Option<usize> {
        self.entry(name).and_then(|e| e.line).or(self.item_line)
    }

    /// The field parameter `name` is written as.
    pub fn field(&self, name: &str) -> String {
        self.entry(name).map_or_else(|| self.spelling(name), |e| e.field.clone())
    }
}

fn show(value: &Value) -> String {
    match value {
        Value::Number(x) => x.to_string(),
        Value::Numbers(v) => {
            format!("[{}]", v.iter().map(f64::to_string).collect::<Vec<_>>().join(", "))
        }
        Value::Text(text) => format!("{text:?}"),
        Value::Bool(b) => b.to_string(),
        Value::Other(text) => text.clone(),
    }
}

/// `v` as `[x, y, z]`, each component as `show_large` shows it.
pub fn show_large_vec(v: Vec3) -> String {
    format!("[{}, {}, {}]", show_large(v.x), show_large(v.y), show_large(v.z))
}

/// `x` in scientific notation from 1e16 up, where the positional form runs to dozens of
/// digits (1e300 to 301), else as written.
pub fn show_large<T>(x: T) -> String
where
    T: Copy + std::fmt::Display + std::fmt::LowerExp + Into<f64>,
{
    if x.into().abs() >= 1e16 { format!("{x:e}") } else { x.to_string() }
}

pub fn show_vec(v: DVec3) -> String {
    format!("[{}, {}, {}]", v.x, v.y, v.z)
}

/// Where a kind writes its parameters back (the TOML writer of `embray convert`).
pub trait ParamSink {
    fn text(&mut self, name: &str, value: &str);
    fn number(&mut self, name: &str, value: f64);
    fn vec3(&mut self, name: &str, value: DVec3);
    /// A colour, kept in f32: written as the shortest text that reads back to it.
    fn color(&mut self, name: &str, value: Vec3);
    fn path(&mut self, name: &str, value: &std::path::Path);
    fn numbers(&mut self, name: &str, values: &[f64]);
}
