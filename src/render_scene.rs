//! The scene as the backends and the integrator see it: f32 geometry in render space.
//! Built once from a `SceneDesc` by `render_space::to_render_scene`.

use crate::camera::Camera;
use crate::light::LightSet;
use crate::material::Material;
use glam::{Vec2, Vec3};

/// A triangle mesh in render space.
#[derive(Clone, Debug, Default)]
pub struct TriangleMesh {
    pub positions: Vec<Vec3>,
    pub indices: Vec<[u32; 3]>,
    /// Per-vertex shading normals (unit length), if the mesh has them.
    pub normals: Option<Vec<Vec3>>,
    /// Per-vertex texture coordinates, if the mesh has them.
    pub uvs: Option<Vec<Vec2>>,
}

impl TriangleMesh {
    pub fn triangle(&self, prim: u32) -> [Vec3; 3] {
        let [a, b, c] = self.indices[prim as usize];
        [self.positions[a as usize], self.positions[b as usize], self.positions[c as usize]]
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    pub center: Vec3,
    pub radius: f32,
}

#[derive(Clone, Debug)]
pub enum Geometry {
    Triangles(TriangleMesh),
    Sphere(Sphere),
}

/// One geometry of the scene; its index in `RenderScene::shapes` is the backends' geometry id.
#[derive(Clone, Debug)]
pub struct Shape {
    pub geometry: Geometry,
    pub material: u32,
    /// The scene object this shape came from (for messages).
    pub name: String,
}

#[derive(Clone, Debug)]
pub struct RenderScene {
    pub camera: Camera,
    pub shapes: Vec<Shape>,
    pub materials: Vec<Material>,
    pub lights: LightSet,
    /// Radiance of rays that leave the scene.
    pub background: Vec3,
}
