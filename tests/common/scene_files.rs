//! Where the loader tests' scene text "comes from", and the camera they start with.

use embray::scene::{self, MeshData, SceneDesc, ShapeDesc};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The folder of the loader tests' meshes and materials.
pub fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/scene")
}

/// The (virtual) file the test scenes come from; mesh paths resolve against its directory.
pub fn source() -> PathBuf {
    data_dir().join("scene.toml")
}

/// A camera section every test scene can start with.
pub const CAMERA: &str = "\
[camera]
lookfrom = [0.0, 0.0, -5.0]
lookat = [0.0, 0.0, 0.0]
vfov = 40.0
resolution = [32, 24]
";

/// A white material named `white`.
pub const WHITE: &str = "[materials.white]\nalbedo = [0.73, 0.73, 0.73]\n";

/// `CAMERA`, the white material and `rest`.
pub fn scene_with(rest: &str) -> String {
    format!("{CAMERA}{WHITE}{rest}")
}

/// Scene text as if read from `source()`; panics with the error if it does not load.
pub fn load(text: &str) -> SceneDesc {
    load_from(text, &source())
}

/// Scene text as if read from `source`; panics with the error if it does not load.
pub fn load_from(text: &str, source: &Path) -> SceneDesc {
    match scene::load_str(text, source) {
        Ok(scene) => scene,
        Err(e) => panic!("scene should load, got: {e}\n{text}"),
    }
}

/// The mesh of object `object`; panics if it is another shape.
pub fn mesh_of(scene: &SceneDesc, object: usize) -> &Arc<MeshData> {
    match &scene.objects[object].shape {
        ShapeDesc::Mesh(mesh) => mesh,
        other => panic!("object {object} is not a mesh: {other:?}"),
    }
}
