//! `SceneDesc`: a validated scene in world space with f64 transforms, independent of the file
//! format it came from.

use glam::{DAffine3, DVec3, Vec2, Vec3};
use std::path::PathBuf;

#[derive(Clone, Debug, PartialEq)]
pub struct CameraDesc {
    pub lookfrom: DVec3,
    pub lookat: DVec3,
    pub up: DVec3,
    /// Vertical field of view in degrees.
    pub vfov_deg: f64,
    pub width: u32,
    pub height: u32,
    /// Lens diameter; 0 is a pinhole.
    pub aperture: f64,
    /// Distance to the plane in focus; `None` means the lookat distance.
    pub focus_distance: Option<f64>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct MaterialDesc {
    pub name: String,
    /// Diffuse reflectance in [0, 1].
    pub albedo: Vec3,
    /// Emitted radiance.
    pub emission: Vec3,
}

/// Mesh data in object space. Positions are f64 so that no precision is lost before the
/// object is placed in render space.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    pub positions: Vec<DVec3>,
    pub indices: Vec<[u32; 3]>,
    pub normals: Option<Vec<DVec3>>,
    pub uvs: Option<Vec<Vec2>>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ShapeDesc {
    Mesh(MeshData),
    Sphere { center: DVec3, radius: f64 },
}

#[derive(Clone, Debug, PartialEq)]
pub struct ObjectDesc {
    /// Human-readable name for messages ("objects[3] (bunny.obj: Bunny)").
    pub name: String,
    pub shape: ShapeDesc,
    /// Index into `SceneDesc::materials`.
    pub material: u32,
    pub world_from_object: DAffine3,
}

#[derive(Clone, Debug, PartialEq)]
pub enum LightDesc {
    /// Isotropic point light; `intensity` is radiant intensity (W/sr per channel).
    Point { position: DVec3, intensity: Vec3 },
}

/// Defaults for the renderer that a scene may carry; command-line options override them.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    pub spp: u32,
    pub max_depth: u32,
    pub background: Vec3,
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings { spp: 16, max_depth: 5, background: Vec3::ZERO }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct SceneDesc {
    /// The file it was loaded from, for messages.
    pub source: PathBuf,
    pub camera: CameraDesc,
    pub settings: RenderSettings,
    pub materials: Vec<MaterialDesc>,
    pub objects: Vec<ObjectDesc>,
    pub lights: Vec<LightDesc>,
}

impl SceneDesc {
    /// Moves the whole scene, camera included, by `offset` (exactly, in f64). Used to
    /// reproduce the far-from-origin precision problem with any scene.
    pub fn translate(&mut self, offset: DVec3) {
        let shift = DAffine3::from_translation(offset);
        self.camera.lookfrom += offset;
        self.camera.lookat += offset;
        for object in &mut self.objects {
            object.world_from_object = shift * object.world_from_object;
        }
        for light in &mut self.lights {
            match light {
                LightDesc::Point { position, .. } => *position += offset,
            }
        }
    }
}
