//! A Mitsuba 3 scene file as a tree of elements, with what the format resolves before any
//! plugin sees it: `<default>` parameters (overridden by `-D name=value`), `$name` in
//! attributes, `<include>` (its children spliced in), and `<path>` folders for finding files.
//! Every element keeps its file and line for messages.

use super::params::Params;
use crate::excerpt::excerpt;
use crate::limits::{MAX_XML_BYTES, MAX_XML_ELEMENTS, MAX_XML_INCLUDES, MAX_XML_NESTING};
use crate::scene::error::{Line, SceneError};
use crate::scene::formats::line_index::LineIndex;
use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Includes deeper than this are refused (a file that includes itself would never end).
const MAX_INCLUDE_DEPTH: usize = 16;

#[derive(Clone, Debug)]
pub(super) struct Element {
    pub tag: String,
    pub attrs: Vec<(String, String)>,
    pub children: Vec<Element>,
    pub file: Arc<PathBuf>,
    pub line: usize,
}

impl Element {
    pub fn attr(&self, name: &str) -> Option<&str> {
        self.attrs.iter().find(|(n, _)| n == name).map(|(_, v)| v.as_str())
    }

    /// `<shape type="obj">`: how messages name the element.
    pub fn describe(&self) -> String {
        let mut text = format!("<{}", self.tag);
        for key in ["type", "name", "id"] {
            if let Some(value) = self.attr(key) {
                text += &format!(" {key}=\"{}\"", excerpt(value));
            }
        }
        text + ">"
    }

    pub fn error(&self, problem: impl Into<String>) -> SceneError {
        SceneError::Xml {
            file: self.file.to_path_buf(),
            element: self.describe(),
            problem: problem.into(),
            line: Line(Some(self.line)),
        }
    }

    /// The attribute `name`, which must be there.
    pub fn required(&self, name: &str) -> Result<&str, SceneError> {
        self.attr(name).ok_or_else(|| self.error(format!("the attribute `{name}` is missing")))
    }
}

/// The files a scene may name are looked up in these folders, in order: the scene's own,
/// then every `<path>` folder.
#[derive(Debug, Default)]
pub(super) struct FileResolver {
    folders: Vec<PathBuf>,
}

impl FileResolver {
    /// `name` in the first folder that has it (the first folder when none has it, so that
    /// the message names the likeliest place).
    pub fn resolve(&self, name: &str) -> PathBuf {
        let path = Path::new(name);
        if path.is_absolute() {
            return path.to_path_buf();
        }
        let found = self.folders.iter().map(|f| f.join(path)).find(|p| p.exists());
        found.unwrap_or_else(|| self.folders.first().map_or(path.to_path_buf(), |f| f.join(path)))
    }
}

/// The scene's root element (its children resolved), the folders files are found in and
/// the memory its reading takes (`SceneDesc::reading_bytes`).
pub(super) fn read(
    path: &Path,
    text: &str,
    defines: &[(String, String)],
) -> Result<(Element, FileResolver, u64), SceneError> {
    let folder = path.parent().map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    let mut reader = Reader {
        params: Params::new(defines),
        resolver: FileResolver { folders: vec![folder] },
        elements: 0,
        includes: 0,
        bytes: 0,
        substituted: 0,
        named: HashSet::new(),
    };
    let root = reader.file(path, text, (0, 0))?;
    // As Mitsuba has it: a parameter the scene never names is a mistake (a misspelt name,
    // or a value meant for another scene), not something to drop without a word.
    if let Some(define) = defines.iter().find(|(name, _)| !reader.named.contains(name)) {
        let mut known: Vec<&str> = reader.named.iter().map(String::as_str).collect();
        known.sort_unstable();
        let name = excerpt(&define.0);
        let problem = format!(
            "the scene has no parameter `{name}` (no ${name} and no <default name=\"{name}\">; \
             its parameters: {})",
            if known.is_empty() { "none".to_owned() } else { known.join(", ") }
        );
        return Err(define_error(path, define, problem));
    }
    let reading_bytes = reader.reading_bytes();
    Ok((root, reader.resolver, reading_bytes))
}

/// Why a scene whose files exceed `MAX_XML_BYTES` is refused.
fn bytes_exceeded() -> String {
    format!(
        "the scene's files, its includes and spectrum files counted each time they are read, \
         exceed {MAX_XML_BYTES} bytes"
    )
}

struct Reader {
    /// `$name` values: `-D` first, then `<default>`s.
    params: Params,
    resolver: FileResolver,
    /// Elements read so far, every file's (`limits::MAX_XML_ELEMENTS`).
    elements: usize,
    /// `<include>`s read so far (`limits::MAX_XML_INCLUDES`).
    includes: usize,
    /// Bytes of the scene's files read so far, each include each time (`limits::MAX_XML_BYTES`).
    bytes: u64,
    /// Bytes the `$name`s added to values, held as the values are (a 1,000-byte default
    /// doubled ten times, named 1,500 times, held 1.5 GB read from 91 KB).
    substituted: u64,
    /// The parameters the scene names: in a `$name` or a `<default>`.
    named: HashSet<String>,
}

impl Reader {
    /// The file at `path`, `depth` includes deep, its root at nesting `level` (where the
    /// `<include>` that reads it is: the bound on nesting is the whole scene's).
    fn file(
        &mut self,
        path: &Path,
        text: &str,
        (depth, level): (usize, usize),
    ) -> Result<Element, SceneError> {
        if !self.count_bytes(text.len() as u64) {
            return Err(SceneError::Xml {
                file: path.to_path_buf(),
                element: "the document".to_owned(),
                problem: bytes_exceeded(),
                line: Line(None),
            });
        }
        let what = || format!("{} bytes of XML with its includes read so far", self.bytes);
        crate::scene::reading_budget::check_reading(path, self.reading_bytes(), what)?;
        let options = roxmltree::ParsingOptions {
            allow_dtd: false,
            nodes_limit: MAX_XML_ELEMENTS as u32,
            ..Default::default()
        };
        let doc = roxmltree::Document::parse_with_options(text, options).map_err(|e| {
            SceneError::Xml {
                file: path.to_path_buf(),
                element: "the document".to_owned(),
                problem: format!("malformed XML: {e}"),
                line: Line(Some(e.pos().row as usize)),
            }
        })?;
        let file = Arc::new(path.to_path_buf());
        let root = doc.root_element();
        let lines = LineIndex::new(text);
        let mut element = self.element(root, &file, &lines, (depth, level))?;
        if element.tag != "scene" {
            return Err(element.error("the root element of a Mitsuba 3 file must be <scene>"));
        }
        if depth == 0 && element.attr("version").is_none() {
            return Err(element.error("the attribute `version` is missing"));
        }
        if let Some(version) = element.attr("version") {
            // Mitsuba parses it (three numbers: 3.0.0) and refuses what it cannot parse; each
            // number is read as `stoul` reads it, so a suffix (3.0.0-dev) is let through.
            let parts: Vec<&str> =
                version.split([' ', '.']).filter(|part| !part.is_empty()).collect();
            let number = |part: &&str| part.bytes().next().is_some_and(|b| b.is_ascii_digit());
            if parts.len() != 3 || !parts.iter().all(number) {
                let version = excerpt(version);
                return Err(element.error(format!(
                    "the version '{version}' is not a version number (three numbers: 3.0.0)"
                )));
            }
        }
        element.attrs.retain(|(name, _)| name != "version");
        Ok(element)
    }

    fn element(
        &mut self,
        node: roxmltree::Node,
        file: &Arc<PathBuf>,
        lines: &LineIndex,
        (depth, level): (usize, usize),
    ) -> Result<Element, SceneError> {
        let line = lines.line_at(node.range().start);
        let raw = Element {
            tag: node.tag_name().name().to_owned(),
            attrs: node.attributes().map(|a| (a.name().to_owned(), a.value().to_owned())).collect(),
            children: Vec::new(),
            file: file.clone(),
            line,
        };
        let attrs = raw
            .attrs
            .iter()
            .map(|(name, value)| Ok((name.clone(), self.substitute(&raw, value)?)))
            .collect::<Result<Vec<_>, SceneError>>()?;
        let mut element = Element { attrs, ..raw };
        let names = element.attrs.iter().map(|(name, _)| name.as_str());
        if let Some(refusal) = super::attributes::unread(&element.tag, names) {
            return Err(element.error(refusal));
        }
        self.elements += 1;
        if self.elements > MAX_XML_ELEMENTS {
            let limit = format!(
                "the scene has more than {MAX_XML_ELEMENTS} elements, its included files' counted"
            );
            return Err(element.error(limit));
        }
        if element.tag == "spectrum" {
            self.read_spectrum_file(&mut element)?;
        }
        for child in node.children().filter(roxmltree::Node::is_element) {
            if level + 1 > MAX_XML_NESTING {
                return Err(element.error(format!("elements nest deeper than {MAX_XML_NESTING}")));
            }
            let child = self.element(child, file, lines, (depth, level + 1))?;
            match child.tag.as_str() {
                "default" => {
                    let name = child.required("name")?.to_owned();
                    if name.is_empty() {
                        return Err(child.error("a <default> needs a name (it is empty)"));
                    }
                    let value = child.required("value")?.to_owned();
                    self.named.insert(name.clone());
                    // A `-D` value stays, and so does the first `<default>`, as in Mitsuba.
                    self.params.add(name, value);
                }
                "path" => {
                    let folder = self.relative_to(&child, child.required("value")?);
                    self.resolver.folders.push(folder);
                }
                "include" => {
                    if depth + 1 > MAX_INCLUDE_DEPTH {
                        let limit = format!("includes nest deeper than {MAX_INCLUDE_DEPTH}");
                        return Err(child.error(limit));
                    }
                    self.includes += 1;
                    if self.includes > MAX_XML_INCLUDES {
                        let limit =
                            format!("the scene reads more than {MAX_XML_INCLUDES} includes");
                        return Err(child.error(limit));
                    }
                    let name = child.required("filename")?;
                    let path = self.resolver.resolve(name);
                    let text = crate::input_file::read_text(&path).map_err(|e| {
                        child.error(format!("cannot read '{}': {e}", path.display()))
                    })?;
                    let included = self.file(&path, &text, (depth + 1, level))?;
                    element.children.extend(included.children);
                }
                _ => element.children.push(child),
            }
        }
        // Each named child is a property of its plugin, given once (as Mitsuba has it),
        // those an `<include>` spliced in too.
        let mut names = HashSet::new();
        for child in &element.children {
            if let Some(name) = child.attr("name")
                && !names.insert(name)
            {
                return Err(child.error(format!("the property `{name}` is given twice")));
            }
        }
        Ok(element)
    }

    /// The memory the files read so far take (`limits::BYTES_PER_XML_BYTE`).
    fn reading_bytes(&self) -> u64 {
        self.bytes
            .saturating_mul(crate::limits::BYTES_PER_XML_BYTE)
            .saturating_add(self.substituted)
    }

    /// Counts `bytes` more read: whether the scene's total is still within
    /// `MAX_XML_BYTES`.
    fn count_bytes(&mut self, bytes: u64) -> bool {
        self.bytes = self.bytes.saturating_add(bytes);
        self.bytes <= MAX_XML_BYTES
    }

    /// A `<spectrum filename="…">` given its file's pairs as its `value` (the file found
    /// as Mitsuba finds it, through the `<path>` folders), its size counted before it is
    /// read.
    fn read_spectrum_file(&mut self, element: &mut Element) -> Result<(), SceneError> {
        let Some(name) = element.attr("filename").map(str::to_owned) else { return Ok(()) };
        if element.attr("value").is_some() {
            return Err(element.error("a <spectrum> takes a value or a filename, not both"));
        }
        let path = self.resolver.resolve(&name);
        // A file that cannot be read is reported by the reader below.
        let size = std::fs::metadata(&path).map_or(0, |m| m.len());
        if !self.count_bytes(size) {
            return Err(element.error(bytes_exceeded()));
        }
        let what = || format!("{} bytes of XML and spectrum files read so far", self.bytes);
        crate::scene::reading_budget::check_reading(&path, self.reading_bytes(), what)?;
        let list =
            super::spd::spectrum_file_as_list(&path).map_err(|problem| element.error(problem))?;
        element.attrs.retain(|(attr, _)| attr != "filename");
        element.attrs.push(("value".to_owned(), list));
        Ok(())
    }

    /// `value` with its `$name`s replaced (`Params::substitute`).
    fn substitute(&mut self, element: &Element, value: &str) -> Result<String, SceneError> {
        let replaced = self
            .params
            .substitute(value, &mut self.named)
            .map_err(|problem| element.error(problem))?;
        let grown = replaced.len().saturating_sub(value.len()) as u64;
        if grown > 0 {
            self.substituted = self.substituted.saturating_add(grown);
            if self.substituted > MAX_XML_BYTES {
                let problem = format!(
                    "the scene's `$name`s add more than {MAX_XML_BYTES} bytes to its values"
                );
                return Err(element.error(problem));
            }
            let what = || {
                let line = element.line;
                format!(
                    "{} bytes added to values by `$name`s, the last at line {line}",
                    self.substituted
                )
            };
            crate::scene::reading_budget::check_reading(&element.file, self.reading_bytes(), what)?;
        }
        Ok(replaced)
    }

    /// A folder named in `element`'s file, relative to that file's folder.
    fn relative_to(&self, element: &Element, value: &str) -> PathBuf {
        let base = element.file.parent().map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        base.join(value)
    }
}

/// The error `problem` with the `-D` parameter `define` of the scene at `path`.
pub(in crate::scene::formats) fn define_error(
    path: &Path,
    (name, value): &(String, String),
    problem: String,
) -> SceneError {
    use crate::excerpt::excerpt;
    SceneError::Xml {
        file: path.to_path_buf(),
        element: format!("-D {}={}", excerpt(name), excerpt(value)),
        problem,
        line: crate::scene::error::Line(None),
    }
}
