//! What a PLY's mesh will hold, held against the memory the process may use before it is
//! spent: its vertices from the header (a `uchar` coordinate becomes 24 bytes, an
//! attribute's `uchar` 4), and its triangles as the faces are read, since a face's list
//! length is in the body (a face of 255 vertices and 900 attribute values becomes 253
//! triangles, each with its own copy of the values: 910 KB from 1.2 KB).

use super::{PlyProblem, problem};
use crate::scene::budget::size;
use std::mem::size_of;

pub(super) struct MeshMemory {
    /// What the mesh may take (`None`: no limit is known).
    available: Option<u64>,
    vertices: u64,
    per_vertex: u64,
    per_triangle: u64,
}

impl MeshMemory {
    /// The memory of `vertices` vertices of `per_vertex` bytes and at least one triangle of
    /// `per_triangle` bytes a face, refused when it passes `available`.
    pub(super) fn new(
        available: Option<u64>,
        (vertices, per_vertex): (u64, u64),
        (faces, per_triangle): (u64, u64),
    ) -> Result<Self, PlyProblem> {
        let memory = MeshMemory { available, vertices, per_vertex, per_triangle };
        memory.check(faces, None)?;
        Ok(memory)
    }

    /// Bytes a vertex takes: its position, its normal and texture coordinates if it has
    /// them, and `channels` attribute values (held as f32).
    pub(super) fn vertex_bytes(normals: bool, uvs: bool, channels: usize) -> u64 {
        let vector = size_of::<glam::DVec3>() as u64;
        vector
            + if normals { vector } else { 0 }
            + if uvs { size_of::<glam::Vec2>() as u64 } else { 0 }
            + channels as u64 * 4
    }

    /// Bytes a triangle takes: its indices and a copy of its face's `channels` values.
    pub(super) fn triangle_bytes(channels: usize) -> u64 {
        size_of::<[u32; 3]>() as u64 + channels as u64 * 4
    }

    /// Refuses `triangles` triangles, with the arrays that hold them about to double (as a
    /// `Vec` grows), when the mesh would pass what it may take. `line` is the body's.
    pub(super) fn check_growth(
        &self,
        triangles: usize,
        line: Option<usize>,
    ) -> Result<(), PlyProblem> {
        self.check((triangles as u64).saturating_mul(2), line)
    }

    fn check(&self, triangles: u64, line: Option<usize>) -> Result<(), PlyProblem> {
        let Some(available) = self.available else { return Ok(()) };
        let vertices = self.vertices.saturating_mul(self.per_vertex);
        let needed = vertices.saturating_add(triangles.saturating_mul(self.per_triangle));
        if needed <= available {
            return Ok(());
        }
        Err(problem(
            line,
            format!(
                "its mesh needs about {} of memory ({} vertices of {} bytes, {triangles} \
                 triangles of {} bytes), but only {} are available",
                size(needed),
                self.vertices,
                self.per_vertex,
                self.per_triangle,
                size(available)
            ),
        ))
    }
}
