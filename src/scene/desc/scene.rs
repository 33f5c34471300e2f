//! The whole scene.

use super::camera::CameraDesc;
use super::light::LightDesc;
use super::material::MaterialDesc;
use super::settings::RenderSettings;
use super::shape::ObjectDesc;
use glam::{DAffine3, DVec3};
use std::path::PathBuf;

#[derive(Clone, Debug, PartialEq)]
pub struct SceneDesc {
    /// The file it was loaded from, for messages.
    pub source: PathBuf,
    pub camera: CameraDesc,
    pub settings: RenderSettings,
    pub materials: Vec<MaterialDesc>,
    pub objects: Vec<ObjectDesc>,
    pub lights: Vec<LightDesc>,
    /// The memory that reading the scene's files leaves held (by the allocator, as its
    /// reader estimates it from their size): a render's memory counts it.
    pub reading_bytes: u64,
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
            if let Some(end) = &mut object.world_from_object_end {
                *end = shift * *end;
            }
        }
        for light in &mut self.lights {
            light.translate(offset);
        }
    }
}
