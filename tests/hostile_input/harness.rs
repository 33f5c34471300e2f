//! Running the binary in a scratch folder and checking what a hostile case must never do:
//! panic, exit 0 on bad input, change a file that existed before, or leave a temporary file.

use crate::common::command::{TempDir, temp_dir};
use std::collections::BTreeMap;
use std::hash::{DefaultHasher, Hash, Hasher};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

/// A fresh folder removed when the case ends (kept if it failed).
pub struct Scratch {
    dir: TempDir,
}

static NEXT: AtomicUsize = AtomicUsize::new(0);

impl Scratch {
    pub fn new() -> Self {
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        Scratch { dir: temp_dir(&format!("hostile-{n}")) }
    }

    pub fn path(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }

    /// Writes `bytes` to `name` (creating folders) and returns its path.
    pub fn write(&self, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
        let path = self.path(name);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).unwrap();
        }
        std::fs::write(&path, bytes).unwrap();
        path
    }

    /// A command for the binary, run in this folder.
    pub fn command(&self, args: &[&str]) -> Command {
        let mut command = Command::new(env!("CARGO_BIN_EXE_embray"));
        command.args(args).current_dir(&self.dir);
        command
    }

    /// Every file below the folder: its kind and a hash of its bytes (or link target).
    pub fn snapshot(&self) -> BTreeMap<PathBuf, u64> {
        let mut files = BTreeMap::new();
        walk(&self.dir, &self.dir, &mut files);
        files
    }
}

fn walk(root: &Path, dir: &Path, files: &mut BTreeMap<PathBuf, u64>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let meta = std::fs::symlink_metadata(&path).unwrap();
        let mut hasher = DefaultHasher::new();
        if meta.file_type().is_symlink() {
            ("link", std::fs::read_link(&path).unwrap()).hash(&mut hasher);
        } else if meta.is_dir() {
            "dir".hash(&mut hasher);
            walk(root, &path, files);
        } else if meta.is_file() {
            ("file", std::fs::read(&path).unwrap()).hash(&mut hasher);
        } else {
            "special".hash(&mut hasher);
        }
        files.insert(path.strip_prefix(root).unwrap().to_path_buf(), hasher.finish());
    }
}

/// What a run printed and how it ended.
pub struct Run {
    pub code: Option<i32>,
    pub stdout: String,
    pub stderr: String,
}

impl From<Output> for Run {
    fn from(output: Output) -> Self {
        Run {
            code: output.status.code(),
            stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
            stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
        }
    }
}

impl Run {
    #[track_caller]
    pub fn assert_no_panic(&self) {
        assert_ne!(self.code, Some(101), "exit 101 (a panic):\n{}", self.stderr);
        assert!(!self.stderr.contains("panicked"), "a panic:\n{}", self.stderr);
        assert!(self.code.is_some(), "killed by a signal:\n{}", self.stderr);
    }

    #[track_caller]
    pub fn assert_says(&self, parts: &[&str]) {
        for part in parts {
            assert!(self.stderr.contains(part), "expected {part:?} in:\n{}", self.stderr);
        }
    }
}

/// Runs `args` in `scratch`; the run must fail with exit 1, say every one of `expected`,
/// not panic, and change no file (nor leave one behind).
#[track_caller]
pub fn refused_in(scratch: &Scratch, args: &[&str], expected: &[&str]) -> Run {
    let before = scratch.snapshot();
    let run = Run::from(scratch.command(args).output().unwrap());
    run.assert_no_panic();
    assert_eq!(run.code, Some(1), "should fail:\n{}", run.stderr);
    run.assert_says(expected);
    assert!(run.stderr.len() < 4000, "an overlong message ({} bytes)", run.stderr.len());
    assert_eq!(scratch.snapshot(), before, "files changed:\n{}", run.stderr);
    run
}

/// Runs `args` in `scratch` under a memory budget of `budget_bytes` (`EMBRAY_MAX_MEMORY`); as
/// `refused_in`, the run must fail with exit 1, say every one of `expected`, not panic, and
/// change no file.
#[track_caller]
pub fn refused_under_memory(
    scratch: &Scratch,
    args: &[&str],
    budget_bytes: u64,
    expected: &[&str],
) -> Run {
    let before = scratch.snapshot();
    let mut command = scratch.command(args);
    let run =
        Run::from(command.env("EMBRAY_MAX_MEMORY", budget_bytes.to_string()).output().unwrap());
    run.assert_no_panic();
    assert_eq!(run.code, Some(1), "should fail:\n{}", run.stderr);
    run.assert_says(expected);
    assert_eq!(scratch.snapshot(), before, "files changed:\n{}", run.stderr);
    run
}

/// As `refused_in`, in a fresh folder holding `files`.
#[track_caller]
pub fn refused(files: &[(&str, &str)], args: &[&str], expected: &[&str]) -> Run {
    let scratch = Scratch::new();
    for (name, text) in files {
        scratch.write(name, text);
    }
    refused_in(&scratch, args, expected)
}

/// Runs `args` with the limit `resource` (`RLIMIT_FSIZE`: a write past it fails with EFBIG,
/// as a full disk fails with ENOSPC, SIGXFSZ being ignored; `RLIMIT_AS`: `ulimit -v`) at
/// `bytes`.
pub fn run_limited(
    scratch: &Scratch,
    args: &[&str],
    resource: libc::__rlimit_resource_t,
    bytes: u64,
) -> Run {
    run_limited_with(scratch.command(args), resource, bytes)
}

/// As `run_limited`, for a command already set up (its environment, say).
pub fn run_limited_with(
    mut command: std::process::Command,
    resource: libc::__rlimit_resource_t,
    bytes: u64,
) -> Run {
    use std::os::unix::process::CommandExt;
    // SAFETY: only async-signal-safe calls (signal, setrlimit) between fork and exec.
    unsafe {
        command.pre_exec(move || {
            libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
            let limit = libc::rlimit { rlim_cur: bytes, rlim_max: bytes };
            if libc::setrlimit(resource, &limit) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    Run::from(command.output().unwrap())
}

/// Runs `args` in `scratch`; the run must succeed without a panic and leave no temporary
/// file behind.
#[track_caller]
pub fn accepted_in(scratch: &Scratch, args: &[&str]) -> Run {
    let run = Run::from(scratch.command(args).output().unwrap());
    run.assert_no_panic();
    assert_eq!(run.code, Some(0), "should succeed:\n{}", run.stderr);
    assert_no_temp_files(scratch);
    run
}

#[track_caller]
pub fn assert_no_temp_files(scratch: &Scratch) {
    let temps: Vec<_> =
        scratch.snapshot().into_keys().filter(|p| p.to_string_lossy().ends_with(".tmp")).collect();
    assert!(temps.is_empty(), "temporary files left: {temps:?}");
}

/// A tiny scene (8×8, 1 spp): a grey quad facing the camera, lit by a point light, plus
/// `extra` TOML.
pub fn scene(extra: &str) -> String {
    format!(
        r#"[camera]
lookfrom = [0.0, 0.0, -3.0]
lookat = [0.0, 0.0, 0.0]
vfov = 60.0
resolution = [8, 8]

[render]
spp = 1

[materials.grey]
albedo = [0.5, 0.5, 0.5]

[[objects]]
type = "quad"
material = "grey"
corner = [-1.0, -1.0, 0.0]
u = [0.0, 2.0, 0.0]
v = [2.0, 0.0, 0.0]

[[lights]]
type = "point"
position = [0.0, 0.0, -2.0]
intensity = [5.0, 5.0, 5.0]
{extra}"#
    )
}

/// A CENG795 scene with one camera per image name (8×8, a sphere, a point light) and
/// `settings` XML after the background.
/// `scene` with a mesh object reading `file` (grey material).
pub fn with_mesh(file: &str) -> String {
    scene(&format!("[[objects]]\ntype = \"mesh\"\nfile = \"{file}\"\nmaterial = \"grey\"\n"))
}

pub fn xml_scene(image_names: &[&str], settings: &str) -> String {
    let cameras: String = image_names
        .iter()
        .enumerate()
        .map(|(i, name)| {
            format!(
                "    <Camera id=\"{}\">\n      <Position>0 0 0</Position>\n      <Gaze>0 0 -1</Gaze>\n      \
                 <Up>0 1 0</Up>\n      <NearPlane>-1 1 -1 1</NearPlane>\n      \
                 <NearDistance>1</NearDistance>\n      <ImageResolution>8 8</ImageResolution>\n      \
                 <ImageName>{name}</ImageName>\n    </Camera>\n",
                i + 1
            )
        })
        .collect();
    format!(
        r#"<Scene>
  <BackgroundColor>0 0 0</BackgroundColor>
{settings}
  <Cameras>
{cameras}  </Cameras>
  <Lights>
    <AmbientLight>25 25 25</AmbientLight>
    <PointLight id="1"><Position>0 2 0</Position><Intensity>1000 1000 1000</Intensity></PointLight>
  </Lights>
  <Materials>
    <Material id="1">
      <AmbientReflectance>1 1 1</AmbientReflectance>
      <DiffuseReflectance>1 1 1</DiffuseReflectance>
      <SpecularReflectance>0 0 0</SpecularReflectance>
    </Material>
  </Materials>
  <VertexData>0 0 -3</VertexData>
  <Objects>
    <Sphere id="1"><Material>1</Material><Center>1</Center><Radius>1</Radius></Sphere>
  </Objects>
</Scene>
"#
    )
}

/// Declares one test per case: `name: files, args => expected message parts`. The run must be
/// refused (exit 1) with every part in its message, without a panic or a changed file.
macro_rules! refused_cases {
    ($($name:ident: [$($file:expr => $text:expr),* $(,)?], [$($arg:expr),* $(,)?] => [$($part:expr),* $(,)?];)*) => {
        $(
            #[test]
            fn $name() {
                let files: Vec<(&str, String)> = vec![$(($file, $text.to_string())),*];
                let files: Vec<(&str, &str)> = files.iter().map(|(n, t)| (*n, t.as_str())).collect();
                $crate::harness::refused(&files, &[$($arg),*], &[$($part),*]);
            }
        )*
    };
}
pub(crate) use refused_cases;
