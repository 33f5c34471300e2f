//! Where a split render on Slurm stands: every part (done, running, missing, damaged) and
//! the merge, from the job folder's record, the part files and the scheduler's states.

use super::job_file::{JobFile, part_path};
use super::scheduler::{SchedulerError, TaskState, job_state, task_states};
use crate::distributed::{PartIdentity, PartTiming, identity_difference, read_part_meta};
use std::path::Path;

#[derive(Debug, thiserror::Error)]
pub enum StatusError {
    #[error("{0}")]
    JobFile(String),
    #[error(transparent)]
    Scheduler(#[from] SchedulerError),
}

/// Where one part stands.
#[derive(Debug)]
pub enum PartStatus {
    Done(PartTiming),
    /// Its task is pending or running.
    Active(TaskState),
    /// No file, no live task: `resume` resubmits it (the last state Slurm knew, if any).
    Missing(Option<TaskState>),
    /// A file that is not this part of this job.
    Damaged(String),
    /// This part of another render: the scene or the options changed since it was rendered
    /// (how it differs). The merge would refuse it, so `resume` renders it again.
    Stale(String),
}

pub struct Report {
    pub job: JobFile,
    pub parts: Vec<PartStatus>,
    /// The merge job of the last submission round, as Slurm knows it.
    pub merge: Option<TaskState>,
    /// Whether the merged image exists.
    pub merged: bool,
    /// Why the part files could not be checked against the scene and options, if they
    /// could not (the scene no longer loads).
    pub unchecked: Option<String>,
}

/// Where the split render in job folder `dir` stands: each part, and the merge. A part
/// file counts as done only if it records what `identity` gives for the job (the scene's
/// contents and the options, as a part rendered now would); `identity` is asked once, and
/// only if there is a part file to check.
pub fn status(
    dir: &Path,
    identity: &mut dyn FnMut(&JobFile) -> Result<PartIdentity, String>,
) -> Result<Report, StatusError> {
    let job = JobFile::read(dir).map_err(StatusError::JobFile)?;
    let mut states: Vec<Option<TaskState>> = vec![None; job.parts as usize];
    for round in &job.submissions {
        if let Some(array) = &round.array_job {
            for (task, state) in task_states(array)? {
                if let Some(slot) = states.get_mut(task as usize) {
                    *slot = Some(state);
                }
            }
        }
    }
    let mut expected: Option<Result<PartIdentity, String>> = None;
    let mut parts = Vec::with_capacity(states.len());
    for (i, state) in states.into_iter().enumerate() {
        let path = part_path(dir, i as u32, job.parts);
        if !path.exists() {
            parts.push(match state {
                Some(s) if s.is_active() => PartStatus::Active(s),
                other => PartStatus::Missing(other),
            });
            continue;
        }
        parts.push(match read_part_meta(&path) {
            Ok(meta) if meta.part.index == i as u32 && meta.part.count == job.parts => {
                match expected.get_or_insert_with(|| identity(&job)) {
                    Ok(identity) => match identity_difference(&meta, identity) {
                        Some(why) => PartStatus::Stale(why),
                        None => PartStatus::Done(meta.timing),
                    },
                    Err(_) => PartStatus::Done(meta.timing),
                }
            }
            Ok(meta) => PartStatus::Damaged(format!("holds part {}", meta.part)),
            Err(e) => PartStatus::Damaged(e.to_string()),
        });
    }
    let unchecked = expected.and_then(Result::err);
    let merge = match job.submissions.last() {
        Some(round) => job_state(&round.merge_job)?,
        None => None,
    };
    let merged = dir.join("render.exr").exists();
    Ok(Report { job, parts, merge, merged, unchecked })
}

impl Report {
    /// Parts whose file is there.
    pub fn done(&self) -> usize {
        self.parts.iter().filter(|p| matches!(p, PartStatus::Done(_))).count()
    }

    /// Parts that `resume` renders again: no file and no live task, or an unusable file.
    pub fn missing(&self) -> Vec<u32> {
        let lost = |p: &PartStatus| {
            matches!(p, PartStatus::Missing(_) | PartStatus::Damaged(_) | PartStatus::Stale(_))
        };
        (0..self.job.parts).filter(|&i| lost(&self.parts[i as usize])).collect()
    }

    /// The report as `embray slurm status` prints it.
    pub fn text(&self, dir: &Path) -> String {
        let describe = |s: &TaskState| {
            let reason = if s.reason.is_empty() || s.reason == "None" {
                String::new()
            } else {
                format!(" ({})", s.reason)
            };
            format!("{}{reason}, job {}", s.state, s.job_id)
        };
        let mut text = format!(
            "{}: {} parts ({} split) of {}\n",
            dir.display(),
            self.job.parts,
            self.job.split,
            self.job.scene.display()
        );
        for (i, part) in self.parts.iter().enumerate() {
            let line = match part {
                PartStatus::Done(t) => format!(
                    "done: render {:.2} s, {:.2} s of CPU on {} ({} thread{})",
                    t.render_seconds,
                    t.cpu_seconds,
                    t.host,
                    t.threads,
                    if t.threads == 1 { "" } else { "s" }
                ),
                PartStatus::Active(s) => describe(s),
                PartStatus::Missing(Some(s)) => format!("missing: its task ended {}", describe(s)),
                PartStatus::Missing(None) => "missing (Slurm no longer knows its task)".to_owned(),
                PartStatus::Damaged(why) => format!("missing: its file is unusable ({why})"),
                PartStatus::Stale(why) => {
                    format!("missing: its file is of another render: {why}")
                }
            };
            text += &format!("part {i}/{}  {line}\n", self.job.parts);
        }
        let merge = match (&self.merge, self.merged) {
            (_, true) => format!("done: {}", dir.join("render.exr").display()),
            (Some(s), false) => describe(s),
            (None, false) => "not run (Slurm no longer knows the job)".to_owned(),
        };
        text += &format!("merge  {merge}\n");
        if let Some(why) = &self.unchecked {
            text += &format!(
                "the part files were not checked against the scene and the options: {why}\n"
            );
        }
        let missing = self.missing();
        if !missing.is_empty() {
            let list = missing
                .iter()
                .map(|i| format!("{i}/{}", self.job.parts))
                .collect::<Vec<_>>()
                .join(", ");
            text += &format!(
                "{} of {} parts done; missing: {list}. `embray slurm resume {}` renders them and merges.\n",
                self.done(),
                self.job.parts,
                dir.display()
            );
        }
        text
    }
}
