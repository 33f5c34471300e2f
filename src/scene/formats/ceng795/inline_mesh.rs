//! A mesh of the scene's own vertices (`<Faces>` without a plyFile, a triangle's
//! `<Indices>`): 1-based indices plus `vertexOffset` into `<VertexData>`, and per vertex the
//! `<TexCoordData>` entry `i + textureOffset` for vertex index `i`.

use super::xml::{Xml, tokens};
use crate::scene::desc::MeshData;
use crate::scene::error::SceneError;
use crate::scene::vertex_normals::VertexNormals;
use glam::{DVec3, Vec2};
use roxmltree::Node;
use std::collections::HashMap;

/// A mesh and, where it has no texture coordinates, why (for a texture that needs them).
pub(super) struct InlineMesh {
    pub mesh: MeshData,
    pub no_uvs: Option<String>,
}

/// The 0-based scene vertex of the 1-based `token` (plus `offset`) at `pos` in `node`.
pub(super) fn vertex_index(
    x: &Xml,
    vertices: &[DVec3],
    node: Node,
    token: &str,
    pos: usize,
    offset: i64,
) -> Result<usize, SceneError> {
    let count = vertices.len();
    let bad = |problem: String| x.token_error(node, pos, problem);
    let id: i64 =
        token.parse().map_err(|_| bad(format!("vertex index '{token}' is not a whole number")))?;
    let index = id.saturating_add(offset);
    if index < 1 || index as u64 > count as u64 {
        let shown = if offset == 0 {
            format!("vertex index {id}")
        } else {
            format!("vertex index {id} + vertexOffset {offset} = {index}")
        };
        return Err(bad(format!(
            "{shown} is out of range: the scene has {count} vertices (indices 1 to {count})"
        )));
    }
    Ok(index as usize - 1)
}

/// A mesh of the listed scene vertices (triples of indices in `node`'s text), keeping only
/// the vertices it uses.
pub(super) fn inline_mesh(
    x: &Xml,
    (vertices, texcoords): (&[DVec3], &[Vec2]),
    node: Node,
    (offset, texture_offset): (i64, i64),
    smooth: bool,
) -> Result<InlineMesh, SceneError> {
    let mut local: HashMap<usize, u32> = HashMap::new();
    let mut positions = Vec::new();
    let mut used = Vec::new();
    let mut corners = Vec::new();
    for (token, pos) in tokens(node) {
        let global = vertex_index(x, vertices, node, token, pos, offset)?;
        let index = *local.entry(global).or_insert_with(|| {
            positions.push(vertices[global]);
            used.push(global);
            (positions.len() - 1) as u32
        });
        corners.push(index);
    }
    if corners.is_empty() {
        return Err(x.error(node, "the mesh has no faces"));
    }
    if !corners.len().is_multiple_of(3) {
        return Err(x.error(
            node,
            format!("{} vertex indices is not a whole number of triangles", corners.len()),
        ));
    }
    let indices: Vec<[u32; 3]> = corners.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    // Vertex `g` (0-based, vertexOffset included) has the coordinates of entry
    // `g - vertexOffset + textureOffset`; a mesh any of whose vertices has none gets none.
    let entry = |g: usize| (g as i64).checked_sub(offset)?.checked_add(texture_offset);
    let uv = |g: usize| usize::try_from(entry(g)?).ok().and_then(|i| texcoords.get(i).copied());
    let uvs = used.iter().map(|&g| uv(g)).collect::<Option<Vec<Vec2>>>();
    let no_uvs = match used.iter().find(|&&g| uv(g).is_none()) {
        None => None,
        Some(_) if texcoords.is_empty() => Some("the scene has no <TexCoordData>".to_owned()),
        Some(&g) => Some(format!(
            "<TexCoordData> holds {} u v pairs, and scene vertex {} would take pair {} \
             (textureOffset {texture_offset})",
            texcoords.len(),
            g + 1,
            entry(g).map_or_else(|| "out of range".to_owned(), |e| (e + 1).to_string()),
        )),
    };
    let normals = smooth.then(|| VertexNormals::AreaWeighted.of(&positions, &indices));
    let mesh = MeshData { positions, indices, normals, uvs, attributes: Vec::new() };
    Ok(InlineMesh { mesh, no_uvs })
}
