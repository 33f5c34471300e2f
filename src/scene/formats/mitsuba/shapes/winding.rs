//! Mitsuba takes a mesh triangle's side from its interpolated vertex normal (the diffuse
//! BSDF's `cos_theta(si.wi)` is measured in the shading frame, and an area emitter's front is
//! the sampled vertex normal's side), not from its winding; embray takes it from the
//! winding. A Mitsuba mesh is therefore wound, triangle by triangle, to face the way its
//! vertex normals point.

use crate::scene::desc::MeshData;
use glam::DVec3;
use std::collections::HashMap;
use std::sync::Arc;

/// A mesh file's models as Mitsuba reads them (wound as their vertex normals, v flipped for
/// an OBJ), each made once: shapes that name one file share one mesh (an instance each),
/// as they share the file's models.
#[derive(Default)]
pub(in super::super) struct Prepared(HashMap<(*const MeshData, bool), [Arc<MeshData>; 2]>);

impl Prepared {
    /// `mesh` wound as its normals, its v flipped if `flip_v` (and it has uvs).
    pub(super) fn mesh(&mut self, mesh: Arc<MeshData>, flip_v: bool) -> Arc<MeshData> {
        // The source is kept beside what is made of it, so its address stays its own.
        let key = (Arc::as_ptr(&mesh), flip_v);
        let [_, made] = self.0.entry(key).or_insert_with(|| {
            let wound = wound_as_normals(Arc::clone(&mesh));
            let made = if !flip_v || wound.uvs.is_none() {
                wound
            } else {
                let mut flipped = MeshData::clone(&wound);
                for uv in flipped.uvs.iter_mut().flatten() {
                    uv.y = 1.0 - uv.y;
                }
                Arc::new(flipped)
            };
            [mesh, made]
        });
        Arc::clone(made)
    }
}

/// `mesh` with every triangle whose vertex normals point against its winding's normal
/// wound the other way round; the same `Arc` (shared with other objects) when none does or
/// the mesh has no vertex normals. A triangle's vertex normals are summed: for one whose
/// normals lie on both sides of its plane, the side most of them point to wins.
pub(super) fn wound_as_normals(mesh: Arc<MeshData>) -> Arc<MeshData> {
    let Some(normals) = mesh.normals.as_ref() else {
        return mesh;
    };
    let against = |&[a, b, c]: &[u32; 3]| {
        let [pa, pb, pc] = [a, b, c].map(|i| mesh.positions[i as usize]);
        let shading: DVec3 = [a, b, c].iter().map(|&i| normals[i as usize]).sum();
        (pb - pa).cross(pc - pa).dot(shading) < 0.0
    };
    if !mesh.indices.iter().any(against) {
        return mesh;
    }
    let indices = mesh
        .indices
        .iter()
        .map(|triangle| {
            let [a, b, c] = *triangle;
            if against(triangle) { [a, c, b] } else { [a, b, c] }
        })
        .collect();
    Arc::new(MeshData { indices, ..MeshData::clone(&mesh) })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit quad in the xz plane wound to face −y, with vertex normals `normal`.
    fn quad(normal: DVec3) -> Arc<MeshData> {
        Arc::new(MeshData {
            positions: vec![DVec3::ZERO, DVec3::Z, DVec3::new(1.0, 0.0, 1.0), DVec3::X],
            indices: vec![[0, 3, 2], [0, 2, 1]],
            normals: Some(vec![normal; 4]),
            ..Default::default()
        })
    }

    #[test]
    fn triangles_are_wound_to_face_their_vertex_normals() {
        let turned = wound_as_normals(quad(DVec3::Y));
        assert_eq!(turned.indices, vec![[0, 2, 3], [0, 1, 2]]);
        let agreeing = quad(DVec3::NEG_Y);
        assert!(Arc::ptr_eq(&wound_as_normals(Arc::clone(&agreeing)), &agreeing));
    }
}
