//! PLY files → `MeshData`: ASCII, binary little endian and binary big endian.
//!
//! The `vertex` element gives positions (`x y z`), optionally normals (`nx ny nz`) and
//! texture coordinates (`u v`, `s t`, `texture_u texture_v` or `texture_s texture_t`); the
//! `face` element a list property `vertex_indices` (or `vertex_index`) of polygons, which are
//! fan-triangulated (polygons with fewer than 3 vertices are skipped). Other elements and
//! properties are read and ignored. Every problem is reported with what and where: the
//! element and its number, and the line in an ASCII file.
//!
//! (The `ply-rs` crate was considered: it is unmaintained since 2020 and panics on some
//! malformed input; its maintained fork needs a newer Rust than this crate's minimum. The
//! format is small enough to read here, with precise errors.)

use super::desc::MeshData;
use glam::{DVec3, Vec2};

/// What is wrong with a PLY file, and the line for an ASCII file (header or body).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct PlyProblem {
    pub line: Option<usize>,
    pub message: String,
}

fn problem(line: Option<usize>, message: impl Into<String>) -> PlyProblem {
    PlyProblem { line, message: message.into() }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Encoding {
    Ascii,
    LittleEndian,
    BigEndian,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
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
    fn parse(name: &str) -> Option<Scalar> {
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

    fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }

    /// The range of an integer type.
    fn range(self) -> (f64, f64) {
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
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Clone, Debug)]
struct Property {
    name: String,
    kind: Kind,
}

#[derive(Clone, Debug)]
struct Element {
    name: String,
    count: usize,
    properties: Vec<Property>,
    /// Header line of the `element` statement.
    line: usize,
}

impl Element {
    fn find(&self, name: &str) -> Option<usize> {
        self.properties.iter().position(|p| p.name == name)
    }
}

struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// Byte offset of the data after `end_header`.
    body_start: usize,
    /// Number of header lines (the body's first line is this + 1).
    lines: usize,
}

fn parse_header(bytes: &[u8]) -> Result<Header, PlyProblem> {
    let mut offset = 0;
    let mut line_number = 0;
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
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
                elements.push(Element {
                    name: (*name).to_owned(),
                    count,
                    properties: Vec::new(),
                    line: line_number,
                });
            }
            ["property", rest @ ..] => {
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
                element.properties.push(Property { name: (*name).to_owned(), kind });
            }
            ["end_header"] => break,
            _ => return Err(problem(at, format!("unexpected header line '{text}'"))),
        }
    }
    let encoding =
        encoding.ok_or_else(|| problem(None, "the header has no 'format' line".to_owned()))?;
    Ok(Header { encoding, elements, body_start: offset, lines: line_number })
}

/// Why a value could not be read.
enum ReadError {
    /// The data ended.
    End,
    /// An ASCII token that is not a number of the property's type.
    Bad(String),
}

/// The body: a stream of numbers, ASCII or binary.
trait Values {
    fn next(&mut self, ty: Scalar) -> Result<f64, ReadError>;
    /// The line of the value read last (ASCII only).
    fn line(&self) -> Option<usize>;
    /// Bytes left, to bound allocations by what the file can hold.
    fn remaining(&self) -> usize;
}

struct Binary<'a> {
    data: &'a [u8],
    pos: usize,
    big_endian: bool,
}

impl Binary<'_> {
    fn take<const N: usize>(&mut self) -> Result<[u8; N], ReadError> {
        let bytes = self.data.get(self.pos..self.pos + N).ok_or(ReadError::End)?;
        self.pos += N;
        let mut array: [u8; N] = bytes.try_into().expect("N bytes");
        if self.big_endian {
            array.reverse();
        }
        Ok(array)
    }
}

impl Values for Binary<'_> {
    fn next(&mut self, ty: Scalar) -> Result<f64, ReadError> {
        // `take` returns the bytes in little-endian order.
        Ok(match ty {
            Scalar::I8 => i8::from_le_bytes(self.take()?).into(),
            Scalar::U8 => u8::from_le_bytes(self.take()?).into(),
            Scalar::I16 => i16::from_le_bytes(self.take()?).into(),
            Scalar::U16 => u16::from_le_bytes(self.take()?).into(),
            Scalar::I32 => i32::from_le_bytes(self.take()?).into(),
            Scalar::U32 => u32::from_le_bytes(self.take()?).into(),
            Scalar::F32 => f32::from_le_bytes(self.take()?).into(),
            Scalar::F64 => f64::from_le_bytes(self.take()?),
        })
    }

    fn line(&self) -> Option<usize> {
        None
    }

    fn remaining(&self) -> usize {
        self.data.len().saturating_sub(self.pos)
    }
}

struct Ascii<'a> {
    lines: std::str::Lines<'a>,
    words: std::str::SplitWhitespace<'a>,
    /// Line of the current `words`.
    line: usize,
    remaining: usize,
}

impl Values for Ascii<'_> {
    fn next(&mut self, ty: Scalar) -> Result<f64, ReadError> {
        let word = loop {
            if let Some(word) = self.words.next() {
                break word;
            }
            let line = self.lines.next().ok_or(ReadError::End)?;
            self.remaining = self.remaining.saturating_sub(line.len() + 1);
            self.words = line.split_whitespace();
            self.line += 1;
        };
        let bad = || ReadError::Bad(format!("'{word}' is not a valid {}", type_name(ty)));
        // Rust parses "nan" and "inf" too: those are caught as non-finite values later.
        let value: f64 = word.parse().map_err(|_| bad())?;
        if ty.is_integer() {
            let (min, max) = ty.range();
            if value.fract() != 0.0 || value < min || value > max {
                return Err(bad());
            }
        }
        Ok(value)
    }

    fn line(&self) -> Option<usize> {
        Some(self.line)
    }

    fn remaining(&self) -> usize {
        self.remaining
    }
}

fn type_name(ty: Scalar) -> &'static str {
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

/// Parses a whole PLY file.
pub(crate) fn parse(bytes: &[u8]) -> Result<MeshData, PlyProblem> {
    let header = parse_header(bytes)?;
    let body = &bytes[header.body_start..];
    match header.encoding {
        Encoding::Ascii => {
            let text = std::str::from_utf8(body)
                .map_err(|e| problem(None, format!("the ASCII data is not text ({e})")))?;
            let mut values = Ascii {
                lines: text.lines(),
                words: "".split_whitespace(),
                line: header.lines,
                remaining: text.len(),
            };
            read_body(&header.elements, &mut values)
        }
        Encoding::LittleEndian | Encoding::BigEndian => {
            let big_endian = header.encoding == Encoding::BigEndian;
            let mut values = Binary { data: body, pos: 0, big_endian };
            read_body(&header.elements, &mut values)
        }
    }
}

/// Which vertex properties hold what.
struct VertexLayout {
    position: [usize; 3],
    normal: Option<[usize; 3]>,
    uv: Option<[usize; 2]>,
}

fn vertex_layout(element: &Element) -> Result<VertexLayout, PlyProblem> {
    let at = Some(element.line);
    let scalar = |name: &str| -> Result<Option<usize>, PlyProblem> {
        let Some(index) = element.find(name) else { return Ok(None) };
        match element.properties[index].kind {
            Kind::Scalar(_) => Ok(Some(index)),
            Kind::List { .. } => {
                Err(problem(at, format!("vertex property '{name}' is a list, not a number")))
            }
        }
    };
    let mut position = [0; 3];
    for (slot, name) in position.iter_mut().zip(["x", "y", "z"]) {
        *slot = scalar(name)?
            .ok_or_else(|| problem(at, format!("the vertex element has no property '{name}'")))?;
    }
    let normal = match [scalar("nx")?, scalar("ny")?, scalar("nz")?] {
        [Some(x), Some(y), Some(z)] => Some([x, y, z]),
        [None, None, None] => None,
        _ => {
            return Err(problem(at, "the vertex element has some but not all of nx, ny, nz"));
        }
    };
    let mut uv = None;
    for [u, v] in [["u", "v"], ["s", "t"], ["texture_u", "texture_v"], ["texture_s", "texture_t"]] {
        if let (Some(u), Some(v)) = (scalar(u)?, scalar(v)?) {
            uv = Some([u, v]);
            break;
        }
    }
    Ok(VertexLayout { position, normal, uv })
}

/// The face element's index list property.
fn face_indices(element: &Element) -> Result<usize, PlyProblem> {
    let at = Some(element.line);
    let index =
        element.find("vertex_indices").or_else(|| element.find("vertex_index")).ok_or_else(
            || problem(at, "the face element has no property 'vertex_indices' (or 'vertex_index')"),
        )?;
    let property = &element.properties[index];
    match property.kind {
        Kind::List { item, .. } if item.is_integer() => Ok(index),
        Kind::List { item, .. } => Err(problem(
            at,
            format!(
                "unsupported property type: face property '{}' has {} indices, not integers",
                property.name,
                type_name(item)
            ),
        )),
        Kind::Scalar(_) => {
            Err(problem(at, format!("face property '{}' is not a list", property.name)))
        }
    }
}

fn read_body(elements: &[Element], values: &mut dyn Values) -> Result<MeshData, PlyProblem> {
    let vertex_element = elements
        .iter()
        .find(|e| e.name == "vertex")
        .ok_or_else(|| problem(None, "the PLY file has no vertex element"))?;
    let vertex_count = vertex_element.count;
    let layout = vertex_layout(vertex_element)?;
    let mut mesh = MeshData {
        normals: layout.normal.map(|_| Vec::new()),
        uvs: layout.uv.map(|_| Vec::new()),
        ..MeshData::default()
    };
    let mut has_face_element = false;
    // Property values of one element (scalars; lists are read separately).
    let mut row: Vec<f64> = Vec::new();
    let mut polygon: Vec<u32> = Vec::new();
    for element in elements {
        let is_vertex = element.name == "vertex";
        let face_list = if element.name == "face" {
            has_face_element = true;
            Some(face_indices(element)?)
        } else {
            None
        };
        if is_vertex {
            // Each vertex takes at least 3 bytes in any encoding.
            let capacity = element.count.min(values.remaining() / 3);
            mesh.positions.reserve(capacity);
        }
        for number in 0..element.count {
            let context = |error: ReadError, property: &str, line: Option<usize>| match error {
                ReadError::End => problem(
                    line,
                    format!(
                        "the data ends in {} {number} of {} (truncated file?)",
                        element.name, element.count
                    ),
                ),
                ReadError::Bad(message) => problem(
                    line,
                    format!("{message} ({} {number}, property '{property}')", element.name),
                ),
            };
            row.clear();
            for (p, property) in element.properties.iter().enumerate() {
                match property.kind {
                    Kind::Scalar(ty) => {
                        let value = values
                            .next(ty)
                            .map_err(|e| context(e, &property.name, values.line()))?;
                        row.push(value);
                    }
                    Kind::List { count, item } => {
                        let n = values
                            .next(count)
                            .map_err(|e| context(e, &property.name, values.line()))?;
                        if n < 0.0 {
                            return Err(problem(
                                values.line(),
                                format!("{} {number} has a negative list length {n}", element.name),
                            ));
                        }
                        let is_polygon = face_list == Some(p);
                        polygon.clear();
                        for _ in 0..n as usize {
                            let value = values
                                .next(item)
                                .map_err(|e| context(e, &property.name, values.line()))?;
                            if is_polygon {
                                if value < 0.0 || value >= vertex_count as f64 {
                                    return Err(problem(
                                        values.line(),
                                        format!(
                                            "face {number} refers to vertex {value}, but the \
                                             file has {vertex_count} vertices"
                                        ),
                                    ));
                                }
                                polygon.push(value as u32);
                            }
                        }
                        if is_polygon && polygon.len() >= 3 {
                            for i in 1..polygon.len() - 1 {
                                mesh.indices.push([polygon[0], polygon[i], polygon[i + 1]]);
                            }
                        }
                        row.push(f64::NAN); // keeps `row` indexed by property
                    }
                }
            }
            if is_vertex {
                let [x, y, z] = layout.position.map(|i| row[i]);
                let position = DVec3::new(x, y, z);
                if !position.is_finite() {
                    return Err(problem(
                        values.line(),
                        format!("vertex {number} has a non-finite coordinate {position}"),
                    ));
                }
                mesh.positions.push(position);
                if let (Some(normals), Some(indices)) = (&mut mesh.normals, layout.normal) {
                    let [x, y, z] = indices.map(|i| row[i]);
                    let normal = DVec3::new(x, y, z);
                    if !normal.is_finite() {
                        return Err(problem(
                            values.line(),
                            format!("vertex {number} has a non-finite normal {normal}"),
                        ));
                    }
                    normals.push(normal);
                }
                if let (Some(uvs), Some([u, v])) = (&mut mesh.uvs, layout.uv) {
                    let uv = Vec2::new(row[u] as f32, row[v] as f32);
                    if !uv.is_finite() {
                        return Err(problem(
                            values.line(),
                            format!("vertex {number} has a non-finite texture coordinate"),
                        ));
                    }
                    uvs.push(uv);
                }
            }
        }
    }
    if mesh.indices.is_empty() {
        let message = if has_face_element {
            "the PLY file has no faces (no polygon with 3 or more vertices)"
        } else {
            "the PLY file has no faces (no face element)"
        };
        return Err(problem(None, message));
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests;
