//! Shapes and their placements: meshes, spheres, objects.

use glam::{DAffine3, DVec3, Vec2};

pub use crate::texels::TextureImage;

/// Mesh data in object space. Positions are f64 so that no precision is lost before the
/// object is placed in render space.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    pub positions: Vec<DVec3>,
    pub indices: Vec<[u32; 3]>,
    pub normals: Option<Vec<DVec3>>,
    pub uvs: Option<Vec<Vec2>>,
    /// Named per-vertex or per-triangle values (a PLY file's extra properties).
    pub attributes: Vec<super::MeshAttribute>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ShapeDesc {
    /// Shared (`Arc`) so that every placement of one mesh uses the same data: objects whose
    /// meshes are the same `Arc` become instances of one prototype, O(1) memory each.
    Mesh(std::sync::Arc<MeshData>),
    Sphere {
        center: DVec3,
        radius: f64,
    },
    /// A signed distance grid over [0, 1]³ (shared, as meshes are, by its placements).
    SdfGrid(std::sync::Arc<super::SdfGridData>),
}

#[derive(Clone, Debug, PartialEq)]
pub struct ObjectDesc {
    /// Human-readable name for messages ("objects[3] (bunny.obj: Bunny)").
    pub name: String,
    pub shape: ShapeDesc,
    /// Index into `SceneDesc::materials`.
    pub material: u32,
    /// Placement at shutter open (t = 0).
    pub world_from_object: DAffine3,
    /// Placement at shutter close (t = 1) for a moving object; interpolated as translation,
    /// rotation (slerp) and scale in between. `None` for a static object.
    pub world_from_object_end: Option<DAffine3>,
}

impl ObjectDesc {
    pub fn is_moving(&self) -> bool {
        self.world_from_object_end.is_some_and(|end| end != self.world_from_object)
    }
}
