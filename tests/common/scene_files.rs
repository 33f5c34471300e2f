//! Where the loader tests' scene text "comes from", and the camera they start with.

use std::path::{Path, PathBuf};

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
