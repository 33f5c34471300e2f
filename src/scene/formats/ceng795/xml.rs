//! Reading the course's XML with `roxmltree`: child lookup, numbers with the line they are on,
//! and errors that name the element (`Objects > Mesh id="3" > Faces`) and the line.

use crate::scene::error::{Line, SceneError};
use glam::{DVec3, Vec3};
use roxmltree::{Document, Node};
use std::path::Path;

/// The document being read and the file it came from, for messages.
pub(super) struct Xml<'a, 'input> {
    pub file: &'a Path,
    pub doc: &'a Document<'input>,
}

/// `Cameras > Camera id="1" > Position`: the element and its ancestors below `<Scene>`.
pub(super) fn describe(node: Node) -> String {
    let mut parts: Vec<String> = node
        .ancestors()
        .filter(|n| n.is_element() && n.parent().is_some_and(|p| p.is_element()))
        .map(|n| match n.attribute("id") {
            Some(id) => format!("{} id=\"{}\"", n.tag_name().name(), id.trim()),
            None => n.tag_name().name().to_owned(),
        })
        .collect();
    if parts.is_empty() {
        parts.push(node.tag_name().name().to_owned());
    }
    parts.reverse();
    format!("<{}>", parts.join(" > "))
}

/// The ids in `ids` for a message: numbers first in numeric order, then the rest, joined by
/// ", "; "(none)" when there are none.
pub(super) fn id_list<'a>(ids: impl Iterator<Item = &'a String>) -> String {
    let mut ids: Vec<&str> = ids.map(String::as_str).collect();
    ids.sort_by_key(|id| (id.parse::<u64>().unwrap_or(u64::MAX), *id));
    if ids.is_empty() { "(none)".to_owned() } else { ids.join(", ") }
}

/// The element's text split at whitespace, each token with its byte offset in the document.
/// Text split by comments is read as one.
pub(super) fn tokens<'a, 'input>(node: Node<'a, 'input>) -> impl Iterator<Item = (&'a str, usize)> {
    node.children().filter(|c| c.is_text()).flat_map(|t| {
        let text: &'a str = t.text().unwrap_or("");
        let start = t.range().start;
        text.split_ascii_whitespace()
            .map(move |token| (token, start + (token.as_ptr() as usize - text.as_ptr() as usize)))
    })
}

impl Xml<'_, '_> {
    pub fn line_at(&self, pos: usize) -> Line {
        Line(Some(self.doc.text_pos_at(pos).row as usize))
    }

    pub fn line(&self, node: Node) -> Line {
        self.line_at(node.range().start)
    }

    /// A problem with `node` (its structure or its value).
    pub fn error(&self, node: Node, problem: impl Into<String>) -> SceneError {
        SceneError::Xml {
            file: self.file.to_path_buf(),
            element: describe(node),
            problem: problem.into(),
            line: self.line(node),
        }
    }

    /// A problem with the token at byte `pos` inside `node`'s text.
    pub fn token_error(&self, node: Node, pos: usize, problem: impl Into<String>) -> SceneError {
        SceneError::Xml {
            file: self.file.to_path_buf(),
            element: describe(node),
            problem: problem.into(),
            line: self.line_at(pos),
        }
    }

    /// A value outside its allowed range.
    pub fn out_of_range(
        &self,
        node: Node,
        value: impl std::fmt::Display,
        requirement: &str,
    ) -> SceneError {
        SceneError::OutOfRange {
            file: self.file.to_path_buf(),
            field: describe(node),
            value: value.to_string(),
            requirement: requirement.to_owned(),
            line: self.line(node),
        }
    }

    /// The child element `name` of `node`, if there is one; an error if there are several.
    pub fn child<'a, 'input>(
        &self,
        node: Node<'a, 'input>,
        name: &str,
    ) -> Result<Option<Node<'a, 'input>>, SceneError> {
        let mut found = node.children().filter(|c| c.has_tag_name(name));
        let first = found.next();
        if let Some(second) = found.next() {
            return Err(self.error(second, format!("<{name}> is given more than once")));
        }
        Ok(first)
    }

    /// The child element `name`, which must be there.
    pub fn required<'a, 'input>(
        &self,
        node: Node<'a, 'input>,
        name: &str,
    ) -> Result<Node<'a, 'input>, SceneError> {
        self.child(node, name)?.ok_or_else(|| self.missing(node, name))
    }

    /// `node` lacks the child element `name`.
    pub fn missing(&self, node: Node, name: &str) -> SceneError {
        SceneError::MissingField {
            file: self.file.to_path_buf(),
            item: describe(node),
            field: name.to_owned(),
            line: self.line(node),
        }
    }

    /// The boolean attribute `name` of `node`: `"true"` or `"false"` (false when absent).
    pub fn flag(&self, node: Node, name: &str) -> Result<bool, SceneError> {
        match node.attribute(name).map(str::trim) {
            None | Some("false") => Ok(false),
            Some("true") => Ok(true),
            Some(other) => Err(self.error(
                node,
                format!(
                    "attribute {name}=\"{}\" must be \"true\" or \"false\"",
                    crate::excerpt::excerpt(other)
                ),
            )),
        }
    }

    /// Rejects child elements of `node` that are not in `allowed`.
    pub fn check_children(&self, node: Node, allowed: &[&str]) -> Result<(), SceneError> {
        for child in node.children().filter(Node::is_element) {
            let name = child.tag_name().name();
            if !allowed.contains(&name) {
                return Err(self.error(
                    child,
                    format!(
                        "unsupported element <{name}> (supported here: {})",
                        allowed.join(", ")
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Every number in `node`'s text.
    pub fn floats(&self, node: Node) -> Result<Vec<f64>, SceneError> {
        tokens(node).map(|(token, pos)| self.float_token(node, token, pos)).collect()
    }

    pub fn float_token(&self, node: Node, token: &str, pos: usize) -> Result<f64, SceneError> {
        match token.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(self.token_error(node, pos, format!("'{token}' is not a finite number"))),
        }
    }

    /// Exactly `N` numbers (`at_least`: `N` or more, the rest ignored).
    pub fn numbers<const N: usize>(
        &self,
        node: Node,
        at_least: bool,
    ) -> Result<[f64; N], SceneError> {
        let values = self.floats(node)?;
        if values.len() < N || (!at_least && values.len() > N) {
            let expected = if at_least { format!("at least {N}") } else { N.to_string() };
            return Err(
                self.error(node, format!("expected {expected} numbers, found {}", values.len()))
            );
        }
        let mut out = [0.0; N];
        out.copy_from_slice(&values[..N]);
        Ok(out)
    }

    pub fn vec3(&self, node: Node) -> Result<DVec3, SceneError> {
        Ok(DVec3::from_array(self.numbers::<3>(node, false)?))
    }

    pub fn scalar(&self, node: Node) -> Result<f64, SceneError> {
        Ok(self.numbers::<1>(node, false)?[0])
    }

    /// Three non-negative numbers that fit in f32 (colours, intensities, coefficients).
    pub fn color(&self, node: Node) -> Result<Vec3, SceneError> {
        let v = self.numbers::<3>(node, false)?;
        if let Some(bad) = v.iter().find(|&&c| !(c >= 0.0) || !(c as f32).is_finite()) {
            return Err(self.out_of_range(node, bad, ">= 0 (and small enough for f32)"));
        }
        Ok(DVec3::from_array(v).as_vec3())
    }

    /// One non-negative whole number.
    pub fn count(&self, node: Node) -> Result<u64, SceneError> {
        let mut all = tokens(node);
        let (Some((token, pos)), None) = (all.next(), all.next()) else {
            return Err(self.error(node, "expected one whole number"));
        };
        token.parse::<u64>().map_err(|_| {
            self.token_error(node, pos, format!("'{token}' is not a non-negative whole number"))
        })
    }

    /// The element's text, trimmed.
    pub fn text<'a>(&self, node: Node<'a, '_>) -> &'a str {
        node.text().unwrap_or("").trim()
    }
}
