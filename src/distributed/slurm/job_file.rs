//! `DIR/job.json`: what `embray slurm` submitted, so that `status` and `resume` can pick it
//! up from any login node later.

use crate::distributed::Split;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

pub const JOB_FILE: &str = "job.json";

/// The `sbatch` settings every job of the render gets.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SbatchOptions {
    pub partition: Option<String>,
    pub time: Option<String>,
    pub cpus_per_task: u32,
    /// At most this many array tasks at once (`--array=…%K`).
    pub max_running: Option<u32>,
    /// Passed to `sbatch` as they are.
    pub extra: Vec<String>,
}

/// One `sbatch` of parts and the merge that waits for them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Submission {
    /// The array job, if any part was submitted.
    pub array_job: Option<String>,
    pub parts: Vec<u32>,
    pub merge_job: String,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct JobFile {
    /// The `embray` binary every task runs (absolute).
    pub embray: PathBuf,
    /// The scene (absolute).
    pub scene: PathBuf,
    pub parts: u32,
    pub split: Split,
    /// `embray render` options given after `--`, passed to every part.
    pub render_args: Vec<String>,
    pub sbatch: SbatchOptions,
    /// Oldest first.
    pub submissions: Vec<Submission>,
}

impl JobFile {
    pub fn read(dir: &Path) -> Result<JobFile, String> {
        let path = dir.join(JOB_FILE);
        let text = crate::scene::read_input_bytes(&path).map_err(|e| {
            format!("cannot read '{}': {e} (is it a folder `embray slurm` made?)", path.display())
        })?;
        let job: JobFile = serde_json::from_slice(&text)
            .map_err(|e| format!("'{}' does not parse: {e}", path.display()))?;
        // `status` and `resume` keep a slot per part: the count is checked before it is used.
        if !(1..=crate::distributed::MAX_PARTS).contains(&job.parts) {
            return Err(format!(
                "'{}': parts is {}, but a render has 1 to {} parts",
                path.display(),
                job.parts,
                crate::distributed::MAX_PARTS
            ));
        }
        if let Some(part) = job.submissions.iter().flat_map(|s| &s.parts).find(|&&p| p >= job.parts)
        {
            return Err(format!(
                "'{}': a submission names part {part}, but the render has {} parts",
                path.display(),
                job.parts
            ));
        }
        for (i, round) in job.submissions.iter().enumerate() {
            let ids =
                [("array_job", round.array_job.as_deref()), ("merge_job", Some(&*round.merge_job))];
            for (field, id) in ids {
                if let Some(id) = id.filter(|id| !is_job_id(id)) {
                    return Err(format!(
                        "'{}': submissions[{i}].{field} is '{}', but a Slurm job id is digits, as \
                         `sbatch --parsable` printed it",
                        path.display(),
                        crate::excerpt::excerpt(id)
                    ));
                }
            }
        }
        Ok(job)
    }

    pub fn encode(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default() + "\n"
    }
}

/// Whether `id` is a job id as `submit` records it: these are handed to `squeue` and
/// `scancel` as arguments of their own, where a hand-edited `--user=root` would be an option.
pub(super) fn is_job_id(id: &str) -> bool {
    !id.is_empty() && id.len() <= 20 && id.bytes().all(|b| b.is_ascii_digit())
}

/// Where part `index` of `count` is written in the job folder `dir`.
pub fn part_path(dir: &Path, index: u32, count: u32) -> PathBuf {
    dir.join("parts").join(format!("part-{index}-of-{count}.exr"))
}
