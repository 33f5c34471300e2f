//! The PLY header: the encoding and the elements with their typed properties.

use super::{PlyProblem, problem};
use std::collections::HashSet;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Encoding {
    Ascii,
    LittleEndian,
    BigEndian,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    pub(super) fn parse(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    pub(super) fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }

    /// The range of an integer type.
    pub(super) fn range(self) -> (f64, f64) {
        match self {
            Scalar::I8 => (i8::MIN.into(), i8::MAX.into()),
            Scalar::U8 => (0.0, u8::MAX.into()),
            Scalar::I16 => (i16::MIN.into(), i16::MAX.into()),
            Scalar::U16 => (0.0, u16::MAX.into()),
            Scalar::I32 => (i32::MIN.into(), i32::MAX.into()),
            Scalar::U32 => (0.0, u32::MAX.into()),
            Scalar::F32 | Scalar::F64 => (f64::NEG_INFINITY, f64::INFINITY),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Clone, Debug)]
pub(super) struct Property {
    pub(super) name: String,
    pub(super) kind: Kind,
}

#[derive(Clone, Debug)]
pub(super) struct Element {
    pub(super) name: String,
    pub(super) count: usize,
    pub(super) properties: Vec<Property>,
    /// Header line of the `element` statement.
    pub(super) line: usize,
}

impl Element {
    pub(super) fn find(&self, name: &str) -> Option<usize> {
        self.properties.iter().position(|p| p.name == name)
    }
}

pub(super) struct Header {
    pub(super) encoding: Encoding,
    pub(super) elements: Vec<Element>,
    /// Byte offset of the data after `end_header`.
    pub(super) body_start: usize,
    /// Number of header lines (the body's first line is this + 1).
    pub(super) lines: usize,
}

pub(super) fn parse_header(bytes: &[u8]) -> Result<Header, PlyProblem> {
    let mut offset = 0;
    let mut line_number = 0;
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    // Names seen, in sets: a header may declare millions of properties.
    let (mut element_names, mut property_names) = (HashSet::new(), HashSet::new());
    loop {
        let Some(length) = bytes[offset..].iter().position(|&b| b == b'\n') else {
            let message = if line_number == 0 {
                "not a PLY file (no header)"
            } else {
                "the header has no end_header line"
            };
            return Err(problem(None, message));
        };
        line_number += 1;
        let raw = &bytes[offset..offset + length];
        offset += length + 1;
        let at = Some(line_number);
        let text = std::str::from_utf8(raw)
            .map_err(|_| problem(at, "the header contains a non-text byte"))?
            .trim_end_matches('\r');
        let words: Vec<&str> = text.split_whitespace().collect();
        if line_number == 1 {
            if text.trim() != "ply" {
                return Err(problem(at, "not a PLY file (the first line is not 'ply')"));
            }
            continue;
        }
        match words.as_slice() {
            [] | ["comment", ..] | ["obj_info", ..] => {}
            ["format", format, version] => {
                encoding = Some(match *format {
                    "ascii" => Encoding::Ascii,
                    "binary_little_endian" => Encoding::LittleEndian,
                    "binary_big_endian" => Encoding::BigEndian,
                    other => {
                        return Err(problem(at, format!("unknown PLY format '{other}'")));
                    }
                });
                if !version.starts_with('1') {
                    return Err(problem(at, format!("unsupported PLY version '{version}'")));
                }
            }
            ["element", name, count] => {
                let count = count.parse::<usize>().map_err(|_| {
                    problem(at, format!("element '{name}' has an invalid count '{count}'"))
                })?;
                // Readers find an element by its name: a second one would be skipped unread.
                if !element_names.insert(*name) {
                    return Err(problem(at, format!("element '{name}' is declared twice")));
                }
                elements.push(Element {
                    name: (*name).to_owned(),
                    count,
                    properties: Vec::new(),
                    line: line_number,
                });
            }
            ["property", rest @ ..] => {
                let element_index = elements.len();
                let Some(element) = elements.last_mut() else {
                    return Err(problem(at, "a property comes before any element"));
                };
                let scalar = |name: &str| {
                    Scalar::parse(name)
                        .ok_or_else(|| problem(at, format!("unsupported property type '{name}'")))
                };
                let (kind, name) = match rest {
                    ["list", count, item, name] => {
                        let count = scalar(count)?;
                        if !count.is_integer() {
                            return Err(problem(
                                at,
                                format!("list '{name}' has a non-integer count type"),
                            ));
                        }
                        (Kind::List { count, item: scalar(item)? }, name)
                    }
                    [ty, name] => (Kind::Scalar(scalar(ty)?), name),
                    _ => return Err(problem(at, format!("malformed property line '{text}'"))),
                };
                if !property_names.insert((element_index, *name)) {
                    let twice =
                        format!("property '{name}' of '{}' is declared twice", element.name);
                    return Err(problem(at, twice));
                }
                element.properties.push(Property { name: (*name).to_owned(), kind });
            }
            ["end_header"] => break,
            _ => return Err(problem(at, format!("unexpected header line '{text}'"))),
        }
    }
    let encoding =
        encoding.ok_or_else(|| problem(None, "the header has no 'format' line".to_owned()))?;
    // A record of no properties takes no data: nothing would bound reading a count of them.
    if let Some(empty) = elements.iter().find(|e| e.count > 0 && e.properties.is_empty()) {
        let message =
            format!("element '{}' has {} records but no properties", empty.name, empty.count);
        return Err(problem(Some(empty.line), message));
    }
    Ok(Header { encoding, elements, body_start: offset, lines: line_number })
}

pub(super) fn type_name(ty: Scalar) -> &'static str {
    match ty {
        Scalar::I8 => "char",
        Scalar::U8 => "uchar",
        Scalar::I16 => "short",
        Scalar::U16 => "ushort",
        Scalar::I32 => "int",
        Scalar::U32 => "uint",
        Scalar::F32 => "float",
        Scalar::F64 => "double",
    }
}
