//! The paths of one run, checked before any work: every output is a usable target
//! (`target.rs`), no two outputs are the same file, and no output is an input of the run
//! (the scene, the images compared). Same file means same device and inode when it exists
//! (hard links, `./x` and `x`, symbolic links), else the same resolved path.

use super::OutputError;
use super::target::{Identity, Target, classify, identity};
use std::path::{Path, PathBuf};

/// A named path of the run: what names it (`-o`, `the scene`) and the path.
#[derive(Clone, Debug)]
struct Named {
    what: String,
    path: PathBuf,
    identity: Identity,
}

/// The inputs and the checked outputs of one run.
#[derive(Default)]
pub struct OutputPlan {
    inputs: Vec<Named>,
    outputs: Vec<(Named, bool)>,
}

impl OutputPlan {
    pub fn new() -> Self {
        Self::default()
    }

    /// Records an input of the run, which no output may overwrite.
    pub fn input(&mut self, what: &str, path: &Path) {
        self.inputs.push(Named {
            what: what.to_owned(),
            path: path.to_path_buf(),
            identity: identity(path),
        });
    }

    /// Records the files a run has read (the scene's meshes and material libraries, as
    /// `input_file::files_read` lists them): none may be overwritten either.
    pub fn inputs_read(&mut self, paths: &[PathBuf]) {
        for path in paths.iter().cloned() {
            if !self.inputs.iter().any(|i| i.path == path) {
                self.input("a file the scene reads,", &path);
            }
        }
    }

    /// Checks the output `path` named by `what`; with `new_folders`, its folder may be
    /// created. Devices may be named more than once (`-o /dev/null --png /dev/null`).
    pub fn output(
        &mut self,
        what: &str,
        path: &Path,
        new_folders: bool,
    ) -> Result<Target, OutputError> {
        let target = classify(what, path, new_folders)?;
        let named = Named {
            what: what.to_owned(),
            path: path.to_path_buf(),
            identity: target.identity.clone(),
        };
        if let Some(input) = self.inputs.iter().find(|i| i.identity == named.identity) {
            return Err(OutputError::IsInput {
                what: named.what,
                path: named.path,
                input_what: input.what.clone(),
                input_path: input.path.clone(),
            });
        }
        let clash = self
            .outputs
            .iter()
            .find(|(o, stream)| o.identity == named.identity && !(*stream && target.is_stream()));
        if let Some((first, _)) = clash {
            return Err(OutputError::Collision {
                first_what: first.what.clone(),
                first_path: first.path.clone(),
                what: named.what,
                path: named.path,
            });
        }
        self.outputs.push((named, target.is_stream()));
        Ok(target)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outputs_may_not_collide_with_each_other_or_an_input() {
        let dir = std::env::temp_dir().join(format!("embray-plan-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let scene = dir.join("scene.toml");
        std::fs::write(&scene, "").unwrap();
        let mut plan = OutputPlan::new();
        plan.input("the scene", &scene);
        let err = plan.output("--png", &dir.join("./scene.toml"), false).unwrap_err().to_string();
        assert!(err.contains("--png") && err.contains("the scene"), "{err}");
        plan.output("-o", &dir.join("x.exr"), false).unwrap();
        let err = plan.output("--stats-json", &dir.join("x.exr"), false).unwrap_err().to_string();
        assert!(err.contains("-o") && err.contains("--stats-json"), "{err}");
        plan.output("--png", Path::new("/dev/null"), false).unwrap();
        plan.output("--stats-json", Path::new("/dev/null"), false).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
