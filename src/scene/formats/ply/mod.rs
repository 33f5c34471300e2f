//! PLY files → `MeshData`: ASCII, binary little endian and binary big endian.
//!
//! The `vertex` element gives positions (`x y z`), optionally normals (`nx ny nz`) and
//! texture coordinates (`u v`, `s t`, `texture_u texture_v` or `texture_s texture_t`); the
//! `face` element a list property `vertex_indices` (or `vertex_index`) of polygons, which are
//! fan-triangulated (polygons with fewer than 3 vertices are skipped, with a warning). Other elements and
//! properties are read and ignored. Every problem is reported with what and where: the
//! element and its number, and the line in an ASCII file.
//!
//! (The `ply-rs` crate was considered: it is unmaintained since 2020 and panics on some
//! malformed input; its maintained fork needs a newer Rust than this crate's minimum. The
//! format is small enough to read here, with precise errors.)

mod attributes;
mod header;
mod memory;
mod values;

use crate::scene::desc::{MeshAttribute, MeshData};
use glam::{DVec3, Vec2};
use header::{Element, Encoding, Kind, parse_header, type_name};
use memory::MeshMemory;
use values::{Ascii, Binary, ReadError, Values};

/// What is wrong with a PLY file, and the line for an ASCII file (header or body).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct PlyProblem {
    pub line: Option<usize>,
    pub message: String,
}

fn problem(line: Option<usize>, message: impl Into<String>) -> PlyProblem {
    PlyProblem { line, message: message.into() }
}

/// Parses a whole PLY file: its mesh, and a warning if faces were skipped. The mesh may take
/// `available` bytes (`None`: no limit is known), checked before they are spent.
pub(crate) fn parse(
    bytes: &[u8],
    available: Option<u64>,
) -> Result<(MeshData, Option<PlyProblem>), PlyProblem> {
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
                in_record: false,
            };
            read_body(&header.elements, &mut values, available)
        }
        Encoding::LittleEndian | Encoding::BigEndian => {
            let big_endian = header.encoding == Encoding::BigEndian;
            let mut values = Binary { data: body, pos: 0, big_endian };
            read_body(&header.elements, &mut values, available)
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

fn read_body(
    elements: &[Element],
    values: &mut dyn Values,
    available: Option<u64>,
) -> Result<(MeshData, Option<PlyProblem>), PlyProblem> {
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
    let vertex_reserved = ["x", "y", "z", "nx", "ny", "nz", "u", "v", "s", "t"];
    let vertex_reserved =
        [&vertex_reserved[..], &["texture_u", "texture_v", "texture_s", "texture_t"]].concat();
    let vertex_attributes =
        attributes::attribute_layouts(vertex_element, "vertex", &vertex_reserved);
    let face_element = elements.iter().find(|e| e.name == "face");
    let face_attributes = match face_element {
        Some(face) => {
            attributes::attribute_layouts(face, "face", &["vertex_indices", "vertex_index"])
        }
        None => Vec::new(),
    };
    let channels = |layouts: &[attributes::AttributeLayout]| -> usize {
        layouts.iter().map(|a| a.properties.len()).sum()
    };
    let (normals, uvs) = (layout.normal.is_some(), layout.uv.is_some());
    let per_vertex = MeshMemory::vertex_bytes(normals, uvs, channels(&vertex_attributes));
    let per_triangle = MeshMemory::triangle_bytes(channels(&face_attributes));
    // Counts bounded by what the body can hold (a vertex takes 3 bytes at least, a face 1),
    // so that a file cut short is reported as cut short.
    let body = values.remaining() as u64;
    let vertices = (vertex_count as u64).min(body / 3);
    let faces = face_element.map_or(0, |face| face.count as u64).min(body);
    let memory = MeshMemory::new(available, (vertices, per_vertex), (faces, per_triangle))?;
    mesh.attributes = vertex_attributes
        .iter()
        .chain(&face_attributes)
        .map(|a| MeshAttribute {
            name: a.name.clone(),
            channels: a.properties.len(),
            values: Vec::new(),
        })
        .collect();
    let mut has_face_element = false;
    // Property values of one element (scalars; lists are read separately).
    let mut row: Vec<f64> = Vec::new();
    let mut polygon: Vec<u32> = Vec::new();
    // Faces of fewer than 3 vertices: how many, and where the first is.
    let (mut short_faces, mut first_short) = (0usize, None);
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
            let triangles_before = mesh.indices.len();
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
                            let triangles = mesh.indices.len() + polygon.len() - 2;
                            if triangles > mesh.indices.capacity() {
                                memory.check_growth(triangles, values.line())?;
                            }
                            for i in 1..polygon.len() - 1 {
                                mesh.indices.push([polygon[0], polygon[i], polygon[i + 1]]);
                            }
                        } else if is_polygon {
                            short_faces += 1;
                            first_short.get_or_insert((number, polygon.len(), values.line()));
                        }
                        row.push(f64::NAN); // keeps `row` indexed by property
                    }
                }
            }
            values
                .end_record()
                .map_err(|m| problem(values.line(), format!("{m} ({} {number})", element.name)))?;
            if is_vertex || face_list.is_some() {
                let (layouts, first, copies) = if is_vertex {
                    (&vertex_attributes, 0, 1)
                } else {
                    (
                        &face_attributes,
                        vertex_attributes.len(),
                        mesh.indices.len() - triangles_before,
                    )
                };
                for (layout, attribute) in layouts.iter().zip(&mut mesh.attributes[first..]) {
                    if let Some(&p) = layout.properties.iter().find(|&&p| !row[p].is_finite()) {
                        let property = &element.properties[p].name;
                        return Err(problem(
                            values.line(),
                            format!("{} {number} has a non-finite {property}", element.name),
                        ));
                    }
                    for _ in 0..copies {
                        attribute.values.extend(layout.properties.iter().map(|&p| row[p] as f32));
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
    values.finish().map_err(|(line, m)| problem(line, m))?;
    if mesh.indices.is_empty() {
        let message = if has_face_element {
            "the PLY file has no faces (no polygon with 3 or more vertices)"
        } else {
            "the PLY file has no faces (no face element)"
        };
        return Err(problem(None, message));
    }
    let warning = first_short.map(|(number, vertices, line)| {
        let message = match short_faces {
            1 => format!(
                "face {number} has {vertices} {} and is ignored (a face needs at least 3)",
                if vertices == 1 { "vertex" } else { "vertices" }
            ),
            n => format!(
                "{n} faces of fewer than 3 vertices are ignored (the first: face {number}, with \
                 {vertices})"
            ),
        };
        problem(line, message)
    });
    Ok((mesh, warning))
}

#[cfg(test)]
mod tests;
