//! Where things are in the scene text: field paths (`objects[2].transform[0].scale`), the
//! line a path starts on, and the scan that rejects every NaN or infinite float.

use crate::scene::error::{Line, SceneError};
use crate::scene::formats::line_index::LineIndex;
use std::cell::OnceCell;
use std::fmt;
use std::path::Path;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

#[derive(Clone, Debug, PartialEq, Eq)]
enum Segment {
    Key(String),
    Index(usize),
}

/// A path to a value in the TOML document, displayed the way a user would write it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct FieldPath {
    segments: Vec<Segment>,
}

impl FieldPath {
    pub(crate) fn root(key: &str) -> Self {
        FieldPath::default().key(key)
    }

    pub(crate) fn key(&self, key: &str) -> Self {
        let mut path = self.clone();
        path.segments.push(Segment::Key(key.to_owned()));
        path
    }

    pub(crate) fn index(&self, index: usize) -> Self {
        let mut path = self.clone();
        path.segments.push(Segment::Index(index));
        path
    }
}

fn is_bare_key(key: &str) -> bool {
    !key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

impl fmt::Display for FieldPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, segment) in self.segments.iter().enumerate() {
            match segment {
                Segment::Key(key) => {
                    if i > 0 {
                        f.write_str(".")?;
                    }
                    if is_bare_key(key) {
                        f.write_str(key)?;
                    } else {
                        write!(f, "{key:?}")?;
                    }
                }
                Segment::Index(index) => write!(f, "[{index}]")?,
            }
        }
        Ok(())
    }
}

/// The scene text, and where its fields are: the document with spans (the one `read` parsed,
/// serde reading a copy), and an index of the line breaks, so that asking for the line of
/// every light's fields stays linear in the file.
pub(crate) struct SourceMap<'a> {
    text: &'a str,
    doc: OnceCell<Spanned<DeTable<'a>>>,
    lines: OnceCell<LineIndex>,
}

impl<'a> SourceMap<'a> {
    /// The map of `text`, parsed by `read` (or by the first `line` asked for).
    pub(crate) fn new(text: &'a str) -> Self {
        SourceMap { text, doc: OnceCell::new(), lines: OnceCell::new() }
    }

    /// 1-based line of byte `offset`.
    fn line_of_offset(&self, offset: usize) -> usize {
        self.lines.get_or_init(|| LineIndex::new(self.text)).line_at(offset.min(self.text.len()))
    }

    /// The line where the value at `path` starts; for a path that does not exist (a missing
    /// field), the line of its deepest existing parent other than the root.
    pub(crate) fn line(&self, path: &FieldPath) -> Line {
        let doc = match self.doc.get() {
            Some(doc) => doc,
            None => match DeTable::parse(self.text) {
                Ok(doc) => self.doc.get_or_init(|| doc),
                Err(_) => return Line(None),
            },
        };
        let mut span = doc.span();
        // `None` only before the first step: the root table.
        let mut value: Option<&DeValue<'a>> = None;
        for segment in &path.segments {
            let next = match (segment, value) {
                (Segment::Key(key), None) => doc.get_ref().get(key.as_str()),
                (Segment::Key(key), Some(DeValue::Table(t))) => t.get(key.as_str()),
                (Segment::Index(i), Some(DeValue::Array(a))) => a.get(*i),
                _ => None,
            };
            let Some(next) = next else { break };
            span = next.span();
            value = Some(next.get_ref());
        }
        if value.is_none() {
            return Line(None);
        }
        Line(Some(self.line_of_offset(span.start)))
    }

    /// The scene file's text read into `T` (serde): parsed once, every NaN or infinite float
    /// refused with its path and line before serde sees the document.
    pub(crate) fn read<T: serde::de::DeserializeOwned>(
        &self,
        file: &Path,
    ) -> Result<T, SceneError> {
        let doc = DeTable::parse(self.text).map_err(|e| toml_error(file, &e))?;
        self.check_table(doc.get_ref(), &FieldPath::default(), file)?;
        let doc = self.doc.get_or_init(|| doc);
        T::deserialize(toml::de::Deserializer::from(doc.clone())).map_err(|error| {
            // A document handed to serde has lost its text, and toml's message its line and
            // excerpt: they come from reading the text again (errors are rare).
            let error = toml::from_str::<T>(self.text).err().unwrap_or(error);
            toml_error(file, &error)
        })
    }

    fn check_table(
        &self,
        table: &DeTable<'a>,
        path: &FieldPath,
        file: &Path,
    ) -> Result<(), SceneError> {
        for (key, value) in table.iter() {
            self.check_value(value, &path.key(key.get_ref()), file)?;
        }
        Ok(())
    }

    fn check_value(
        &self,
        value: &Spanned<DeValue<'a>>,
        path: &FieldPath,
        file: &Path,
    ) -> Result<(), SceneError> {
        match value.get_ref() {
            DeValue::Float(float) => {
                if let Some(name) = non_finite_name(float.as_str()) {
                    return Err(SceneError::NonFinite {
                        file: file.to_path_buf(),
                        field: path.to_string(),
                        value: name.to_owned(),
                        line: Line(Some(self.line_of_offset(value.span().start))),
                    });
                }
                Ok(())
            }
            DeValue::Array(array) => {
                for (i, item) in array.iter().enumerate() {
                    self.check_value(item, &path.index(i), file)?;
                }
                Ok(())
            }
            DeValue::Table(table) => self.check_table(table, path, file),
            _ => Ok(()),
        }
    }
}

/// `Some("NaN" | "inf" | "-inf")` for TOML's special float literals.
fn non_finite_name(literal: &str) -> Option<&'static str> {
    let (negative, magnitude) = match literal.as_bytes().first() {
        Some(b'-') => (true, &literal[1..]),
        Some(b'+') => (false, &literal[1..]),
        _ => (false, literal),
    };
    match (magnitude, negative) {
        ("nan", _) => Some("NaN"),
        ("inf", false) => Some("inf"),
        ("inf", true) => Some("-inf"),
        _ => None,
    }
}

/// toml's error report (line, column, quoted text, message) prefixed by the file name.
pub(crate) fn toml_error(file: &Path, error: &toml::de::Error) -> SceneError {
    // toml quotes the offending line, which may be megabytes long.
    let message = crate::excerpt::shorten_message(error.to_string().trim_end(), 200);
    SceneError::Toml { file: file.to_path_buf(), message }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_display_like_toml() {
        let path = FieldPath::root("objects").index(2).key("transform").index(0).key("scale");
        assert_eq!(path.to_string(), "objects[2].transform[0].scale");
        assert_eq!(FieldPath::root("materials").key("a b").to_string(), "materials.\"a b\"");
    }

    #[test]
    fn line_of_nested_fields() {
        let text = "[camera]\nlookfrom = [1, 2, 3]\n\n[[objects]]\ntype = 'sphere'\nradius = 2\n";
        let map = SourceMap::new(text);
        assert_eq!(map.line(&FieldPath::root("camera").key("lookfrom")), Line(Some(2)));
        assert_eq!(map.line(&FieldPath::root("camera").key("lookfrom").index(2)), Line(Some(2)));
        assert_eq!(map.line(&FieldPath::root("objects").index(0).key("radius")), Line(Some(6)));
        assert_eq!(map.line(&FieldPath::root("objects").index(0)), Line(Some(4)));
        assert_eq!(map.line(&FieldPath::root("nothing")), Line(None));
    }

    #[test]
    fn special_floats_are_named() {
        assert_eq!(non_finite_name("nan"), Some("NaN"));
        assert_eq!(non_finite_name("-nan"), Some("NaN"));
        assert_eq!(non_finite_name("+inf"), Some("inf"));
        assert_eq!(non_finite_name("-inf"), Some("-inf"));
        assert_eq!(non_finite_name("1e300"), None);
    }
}
