//! Values a mesh carries per vertex or per triangle beyond its geometry (Mitsuba's mesh
//! attributes: a PLY file's extra vertex and face properties), looked up by the
//! `mesh_attribute` texture.

/// One named attribute: `channels` values per vertex or per triangle.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshAttribute {
    /// Mitsuba's name: `vertex_` or `face_` and the property's prefix (`face_weight`,
    /// `vertex_color`).
    pub name: String,
    /// 1 or 3.
    pub channels: usize,
    /// `channels` values per vertex, or per triangle for a `face_` attribute (a polygon's
    /// values repeated for each triangle of its fan).
    pub values: Vec<f32>,
}

impl MeshAttribute {
    pub fn per_face(&self) -> bool {
        self.name.starts_with("face_")
    }

    /// The value of element `index` (a vertex or a triangle) as a colour (a single channel
    /// in all three).
    pub fn value(&self, index: usize) -> glam::Vec3 {
        match self.channels {
            1 => glam::Vec3::splat(self.values[index]),
            _ => glam::Vec3::from_slice(&self.values[3 * index..3 * index + 3]),
        }
    }
}
