//! Mitsuba's `.serialized` meshes (versions 3 and 4): a little-endian header (magic 0x041C,
//! version), then each mesh as a zlib stream of flags, (v4) a name, vertex and face counts,
//! positions, optional normals, texture coordinates and colours (single or double
//! precision) and u32 triangle indices; the meshes are indexed by a table of offsets at
//! the end of the file. Every count is checked against what the stream can hold before
//! anything is allocated, and every index against the vertex count. As the PLY reader
//! refuses data after its elements, a stream holding more than it declares, flags no
//! mesh defines, and bytes between a mesh and the next (or the table) are refused.

use crate::scene::desc::MeshData;
use flate2::bufread::ZlibDecoder;
use glam::{DVec3, Vec2};
use std::io::Read;

const MAGIC: u16 = 0x041C;
const HAS_NORMALS: u32 = 0x0001;
const HAS_TEXCOORDS: u32 = 0x0002;
const HAS_COLORS: u32 = 0x0008;
/// A hint only (no data): the mesh is to be shaded flat.
const FACE_NORMALS: u32 = 0x0010;
const SINGLE_PRECISION: u32 = 0x1000;
const DOUBLE_PRECISION: u32 = 0x2000;
const KNOWN_FLAGS: u32 =
    HAS_NORMALS | HAS_TEXCOORDS | HAS_COLORS | FACE_NORMALS | SINGLE_PRECISION | DOUBLE_PRECISION;
/// The most data one mesh may declare, decoded (the PLY and OBJ readers' input cap).
const MAX_DECODED_BYTES: u64 = 2 << 30;
/// Records (vertices, or triangles) decoded at a time.
const DECODE_BLOCK: usize = 1 << 16;

fn u16_at(bytes: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_le_bytes(bytes.get(at..at + 2)?.try_into().ok()?))
}

fn u32_at(bytes: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?))
}

fn u64_at(bytes: &[u8], at: usize) -> Option<u64> {
    Some(u64::from_le_bytes(bytes.get(at..at + 8)?.try_into().ok()?))
}

/// Mesh `shape_index` of the file `bytes`, with normals unless `face_normals`.
pub(crate) fn parse(
    bytes: &[u8],
    shape_index: u32,
    face_normals: bool,
) -> Result<MeshData, String> {
    if u16_at(bytes, 0) != Some(MAGIC) {
        return Err("not a Mitsuba serialized mesh (the file does not start with 0x041C)".into());
    }
    let version = u16_at(bytes, 2).unwrap_or(0);
    if !(version == 3 || version == 4) {
        return Err(format!("serialized version {version} is not supported (3 and 4 are)"));
    }
    // Mesh 0 is read even where the table is broken, so that what its stream declares is
    // checked first; the table is then checked as for any other mesh.
    let table = mesh_table(bytes, version);
    let start = match shape_index {
        0 => 4,
        _ => mesh_start(table.as_ref()?, shape_index)?,
    };
    let stream = bytes.get(start..).ok_or("the offset of the mesh is past the end of the file")?;
    let mut z = ZlibDecoder::new(stream);
    let mut read = |n: usize, what: &str| -> Result<Vec<u8>, String> {
        let mut buffer = Vec::new();
        (&mut z).take(n as u64).read_to_end(&mut buffer).map_err(|e| format!("{what}: {e}"))?;
        if buffer.len() < n {
            return Err(format!("the data ends inside the {what}"));
        }
        Ok(buffer)
    };
    let flags = u32_at(&read(4, "flags")?, 0).unwrap_or(0);
    if flags & !KNOWN_FLAGS != 0 {
        return Err(format!(
            "flags 0x{flags:04x} set bits (0x{:04x}) that no serialized mesh defines",
            flags & !KNOWN_FLAGS
        ));
    }
    if flags & SINGLE_PRECISION != 0 && flags & DOUBLE_PRECISION != 0 {
        return Err(format!("flags 0x{flags:04x} ask for both single and double precision"));
    }
    if version == 4 {
        // The mesh's name, NUL-terminated.
        let mut length = 0;
        while read(1, "name")?[0] != 0 {
            length += 1;
            if length > 4096 {
                return Err("the mesh's name runs past 4096 bytes".into());
            }
        }
    }
    let counts = read(16, "vertex and face counts")?;
    let (vertices, faces) = (u64_at(&counts, 0).unwrap_or(0), u64_at(&counts, 8).unwrap_or(0));
    if vertices == 0 || faces == 0 {
        return Err(format!("the mesh has {vertices} vertices and {faces} triangles"));
    }
    let width: u64 = if flags & DOUBLE_PRECISION != 0 { 8 } else { 4 };
    let floats_per_vertex = 3
        + 3 * u64::from(flags & HAS_NORMALS != 0)
        + 2 * u64::from(flags & HAS_TEXCOORDS != 0)
        + 3 * u64::from(flags & HAS_COLORS != 0);
    // A small stream may inflate to any size: what the counts ask for is bounded as the
    // other mesh readers bound their files, before anything is decoded.
    let declared = vertices
        .checked_mul(floats_per_vertex * width)
        .and_then(|v| faces.checked_mul(12).and_then(|f| v.checked_add(f)));
    if declared.is_none_or(|bytes| bytes > MAX_DECODED_BYTES) {
        return Err(format!(
            "{vertices} vertices and {faces} triangles declared: more than the {} GiB of data a \
             mesh may hold",
            MAX_DECODED_BYTES >> 30
        ));
    }
    // What the decoded mesh holds (f64 positions and normals, f32 texture coordinates, u32
    // corners), against what the machine has.
    let kept = vertices * (24 + 24 * u64::from(flags & HAS_NORMALS != 0))
        + vertices * 8 * u64::from(flags & HAS_TEXCOORDS != 0)
        + faces * 12;
    if let Some(available) = crate::limits::memory_available().filter(|&a| kept > a) {
        return Err(format!(
            "{vertices} vertices and {faces} triangles need {} MiB decoded, but only {} MiB \
             are available",
            kept >> 20,
            available >> 20
        ));
    }
    let (vertices, faces, width) = (vertices as usize, faces as usize, width as usize);
    let mut decode = |count: usize, arity: usize, what: &str, keep: &mut dyn FnMut(&[f64])| {
        decode_floats(&mut read, (count, arity, width), what, keep)
    };
    let mut triples = |what: &str| -> Result<Vec<DVec3>, String> {
        let mut kept = Vec::new();
        let keep = &mut |block: &[f64]| {
            kept.extend(block.chunks_exact(3).map(|v| DVec3::new(v[0], v[1], v[2])));
        };
        decode(vertices, 3, what, keep)?;
        Ok(kept)
    };
    let positions = triples("positions")?;
    let normals = match flags & HAS_NORMALS != 0 {
        false => None,
        true => Some(triples("normals")?),
    };
    let uvs = match flags & HAS_TEXCOORDS != 0 {
        false => None,
        true => {
            let mut kept = Vec::new();
            let keep = &mut |block: &[f64]| {
                kept.extend(block.chunks_exact(2).map(|t| Vec2::new(t[0] as f32, t[1] as f32)));
            };
            decode(vertices, 2, "texture coordinates", keep)?;
            Some(kept)
        }
    };
    if flags & HAS_COLORS != 0 {
        decode(vertices, 3, "vertex colours", &mut |_| {})?;
    }
    let mut indices = Vec::new();
    let mut left = faces;
    while left > 0 {
        let take = left.min(DECODE_BLOCK);
        for t in read(12 * take, "triangles")?.chunks_exact(12) {
            let corner = |k: usize| u32_at(t, 4 * k).unwrap_or(u32::MAX);
            let triangle = [corner(0), corner(1), corner(2)];
            if let Some(bad) = triangle.iter().find(|&&v| v as usize >= vertices) {
                let i = indices.len();
                return Err(format!("triangle {i} uses vertex {bad}, but there are {vertices}"));
            }
            indices.push(triangle);
        }
        left -= take;
    }
    let mut beyond = [0u8; 1];
    if z.read(&mut beyond).map_err(|e| format!("after the triangles: {e}"))? != 0 {
        return Err(format!(
            "the mesh's compressed stream holds more than its {vertices} vertices and {faces} \
             triangles (data follows the last triangle)"
        ));
    }
    let end = start + (stream.len() - z.into_inner().len());
    let table = table?;
    let index = shape_index as usize;
    let next = table.offsets.get(index + 1).map_or(table.start, |&o| o as usize);
    if end != next {
        let what = if index + 1 < table.offsets.len() { "the next mesh" } else { "the table" };
        return Err(format!(
            "mesh {index} ends at byte {end}, but {what} starts at byte {next} (the table of \
             meshes at the end of the file does not match the file)"
        ));
    }
    let normals = if face_normals { None } else { normals };
    Ok(MeshData { positions, indices, normals, uvs, attributes: Vec::new() })
}

/// Decodes `count` records of `arity` floats of `width` bytes from `read`, a block at a
/// time, handing each block to `keep`: what is allocated grows with the data actually
/// there, however large the count declared.
fn decode_floats(
    read: &mut impl FnMut(usize, &str) -> Result<Vec<u8>, String>,
    (count, arity, width): (usize, usize, usize),
    what: &str,
    keep: &mut dyn FnMut(&[f64]),
) -> Result<(), String> {
    let (mut done, mut block) = (0, Vec::new());
    while done < count {
        let take = (count - done).min(DECODE_BLOCK);
        let data = read(take * arity * width, what)?;
        block.clear();
        block.extend(data.chunks_exact(width).map(|c| match width {
            8 => f64::from_le_bytes(c.try_into().unwrap()),
            _ => f32::from_le_bytes(c.try_into().unwrap()) as f64,
        }));
        if let Some(i) = block.iter().position(|v| !v.is_finite()) {
            return Err(format!("{what}: value {} is not finite", done * arity + i));
        }
        keep(&block);
        done += take;
    }
    Ok(())
}

/// The table of meshes at the end of the file: where each mesh starts (at its own 4-byte
/// header, which repeats the file's), and where the table starts.
struct MeshTable {
    offsets: Vec<u64>,
    start: usize,
}

/// Reads and checks the table: mesh 0 starts at byte 0, each mesh after the one before,
/// each at a header, and the table holds nothing else.
fn mesh_table(bytes: &[u8], version: u16) -> Result<MeshTable, String> {
    let count = bytes.len().checked_sub(4).and_then(|at| u32_at(bytes, at));
    let count = count.ok_or("the file is too short for its table of meshes")?;
    if count == 0 {
        return Err("the table of meshes at the end of the file counts 0 meshes".into());
    }
    let entry = if version == 4 { 8 } else { 4 };
    let start = (count as usize)
        .checked_mul(entry)
        .and_then(|table| bytes.len().checked_sub(table + 4))
        .filter(|&start| start >= 4)
        .ok_or_else(|| format!("the table of {count} meshes is longer than the file"))?;
    let offsets: Vec<u64> =
        bytes[start..bytes.len() - 4]
            .chunks_exact(entry)
            .map(|e| {
                if entry == 8 {
                    u64_at(e, 0).unwrap_or(0)
                } else {
                    u32_at(e, 0).unwrap_or(0).into()
                }
            })
            .collect();
    for (i, &offset) in offsets.iter().enumerate() {
        let after = if i == 0 { 0 } else { offsets[i - 1] + 1 };
        let fits = usize::try_from(offset).is_ok_and(|o| o.saturating_add(4) < start);
        let at_header = fits && bytes[offset as usize..offset as usize + 4] == bytes[..4];
        if (i == 0 && offset != 0) || offset < after || !at_header {
            return Err(format!(
                "the table of meshes at the end of the file puts mesh {i} at byte {offset}, \
                 where no mesh starts"
            ));
        }
    }
    Ok(MeshTable { offsets, start })
}

/// Where the zlib stream of mesh `index` starts.
fn mesh_start(table: &MeshTable, index: u32) -> Result<usize, String> {
    let count = table.offsets.len();
    let offset = table.offsets.get(index as usize).ok_or_else(|| {
        format!("shape_index {index} is out of range: the file has {count} meshes")
    })?;
    Ok(*offset as usize + 4)
}

#[cfg(test)]
mod tests {
    use super::*;
    use flate2::{Compression, write::ZlibEncoder};
    use std::io::Write;

    /// A v4 file of one mesh: a triangle with texture coordinates.
    fn triangle_file(vertices: u64, index: u32) -> Vec<u8> {
        triangle_file_with(vertices, index, HAS_TEXCOORDS, &[])
    }

    /// The same with `flags` (texture coordinates among them) and `extra` after the
    /// triangle, inside the zlib stream.
    fn triangle_file_with(vertices: u64, index: u32, flags: u32, extra: &[u8]) -> Vec<u8> {
        let mut body = Vec::new();
        body.extend(flags.to_le_bytes());
        body.extend(b"tri\0");
        body.extend(vertices.to_le_bytes());
        body.extend(1u64.to_le_bytes());
        for p in [[0f32, 0., 0.], [1., 0., 0.], [0., 1., 0.]] {
            for c in p {
                body.extend(c.to_le_bytes());
            }
        }
        for t in [[0f32, 0.], [1., 0.], [0., 1.]] {
            for c in t {
                body.extend(c.to_le_bytes());
            }
        }
        for i in [0u32, 1, index] {
            body.extend(i.to_le_bytes());
        }
        body.extend(extra);
        let mut z = ZlibEncoder::new(Vec::new(), Compression::default());
        z.write_all(&body).unwrap();
        let mut file = vec![0x1C, 0x04, 0x04, 0x00];
        file.extend(z.finish().unwrap());
        file.extend(0u64.to_le_bytes());
        file.extend(1u32.to_le_bytes());
        file
    }

    #[test]
    fn a_triangle_reads_back() {
        let mesh = parse(&triangle_file(3, 2), 0, false).unwrap();
        assert_eq!(mesh.positions[1], DVec3::X);
        assert_eq!(mesh.indices, vec![[0, 1, 2]]);
        assert_eq!(mesh.uvs.unwrap()[2], Vec2::Y);
        assert!(mesh.normals.is_none());
    }

    #[test]
    fn bad_counts_indices_and_truncation_are_refused_without_allocating() {
        assert!(parse(&triangle_file(3, 3), 0, false).unwrap_err().contains("uses vertex 3"));
        let huge = parse(&triangle_file(u64::MAX / 2, 2), 0, false).unwrap_err();
        assert!(huge.contains("more than the 2 GiB of data a mesh may hold"), "{huge}");
        // Counts that ask for just more than the cap, in a stream of a few bytes.
        let many = parse(&triangle_file(178_956_970, 1), 0, false).unwrap_err();
        assert!(many.contains("more than the 2 GiB"), "{many}");
        let mut file = triangle_file(3, 2);
        file.truncate(file.len() - 6);
        assert!(parse(&file, 0, false).is_err());
        assert!(parse(b"PK\x03\x04", 0, false).unwrap_err().contains("0x041C"));
        let wide = parse(&triangle_file(1 << 20, 2), 0, false).unwrap_err();
        assert!(wide.contains("ends inside"), "{wide}");
        assert!(parse(&triangle_file(3, 2), 1, false).is_err());
    }

    /// What Mitsuba would read past unseen is refused, as the PLY reader refuses data after
    /// its elements: data after the triangles in the stream, flags of no meaning, a table of
    /// meshes that does not match the file (for mesh 0 too).
    #[test]
    fn data_no_mesh_declares_is_refused() {
        let trailing = parse(&triangle_file_with(3, 2, HAS_TEXCOORDS, b"junk"), 0, false);
        assert!(trailing.unwrap_err().contains("data follows the last triangle"));
        let unknown = parse(&triangle_file_with(3, 2, HAS_TEXCOORDS | 0x0100, &[]), 0, false);
        assert!(unknown.unwrap_err().contains("(0x0100) that no serialized mesh defines"));
        let both = HAS_TEXCOORDS | SINGLE_PRECISION | DOUBLE_PRECISION;
        let both = parse(&triangle_file_with(3, 2, both, &[]), 0, false).unwrap_err();
        assert!(both.contains("both single and double"), "{both}");
        let hinted = HAS_TEXCOORDS | SINGLE_PRECISION | FACE_NORMALS;
        assert!(parse(&triangle_file_with(3, 2, hinted, &[]), 0, false).is_ok());

        let good = triangle_file(3, 2);
        let with_count = |count: u32| {
            let mut file = good.clone();
            let at = file.len() - 4;
            file[at..].copy_from_slice(&count.to_le_bytes());
            file
        };
        assert!(parse(&with_count(0), 0, false).unwrap_err().contains("counts 0 meshes"));
        let two = parse(&with_count(2), 0, false).unwrap_err();
        assert!(two.contains("where no mesh starts"), "{two}");
        let mut gap = good[..good.len() - 12].to_vec();
        gap.extend([0u8; 3].iter().chain(&good[good.len() - 12..]));
        let gap = parse(&gap, 0, false).unwrap_err();
        assert!(gap.contains("but the table starts at byte"), "{gap}");
        let mut shifted = good.clone();
        let at = shifted.len() - 12;
        shifted[at] = 4;
        assert!(parse(&shifted, 0, false).unwrap_err().contains("puts mesh 0 at byte 4"));
    }
}
