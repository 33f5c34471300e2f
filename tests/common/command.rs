//! Running the `embray` binary in a scratch folder, and a small scene that renders.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub fn embray(args: &[&str], dir: &Path) -> Output {
    embray_with_env(args, dir, &[])
}

/// `embray`, with the environment variables `env` set.
pub fn embray_with_env(args: &[&str], dir: &Path, env: &[(&str, &str)]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_embray"))
        .args(args)
        .current_dir(dir)
        .envs(env.iter().copied())
        .output()
        .expect("embray runs")
}

/// Each `render s.toml EXTRA…` in `dir` must fail with exit 1 and say its expected words.
pub fn assert_render_refusals(dir: &Path, cases: &[(&[&str], &str)]) {
    for (extra, expected) in cases {
        let mut args = vec!["render", "s.toml"];
        args.extend(*extra);
        let out = embray(&args, dir);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
    }
}

/// A scratch folder of its own for a test, emptied first, and removed with all it holds when
/// the test is done with it (dropped), unless the test failed.
pub struct TempDir(PathBuf);

impl std::ops::Deref for TempDir {
    type Target = Path;

    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for TempDir {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    /// Kept where the test failed, to be looked at.
    fn drop(&mut self) {
        if !std::thread::panicking() {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

impl TempDir {
    /// The path of `name` in it, which keeps the folder until it is dropped.
    pub fn file(self, name: &str) -> TempPath {
        TempPath { path: self.0.join(name), _dir: self }
    }
}

/// A path in a `TempDir`, the folder's owner.
pub struct TempPath {
    path: PathBuf,
    _dir: TempDir,
}

impl std::ops::Deref for TempPath {
    type Target = Path;

    fn deref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<Path> for TempPath {
    fn as_ref(&self) -> &Path {
        &self.path
    }
}

pub fn temp_dir(name: &str) -> TempDir {
    let dir = std::env::temp_dir().join(format!("embray-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    TempDir(dir)
}

pub const GOOD_SCENE: &str = r#"
[camera]
lookfrom = [0.0, 1.0, 4.0]
lookat = [0.0, 0.0, 0.0]
vfov = 40.0
resolution = [16, 12]

[materials.white]
albedo = [0.8, 0.8, 0.8]

[[objects]]
type = "sphere"
material = "white"
center = [0.0, 0.0, 0.0]
radius = 1.0

[[lights]]
type = "point"
position = [2.0, 3.0, 2.0]
intensity = [10.0, 10.0, 10.0]
"#;
