//! `embray slurm`: a split render as one Slurm array job plus a dependent merge; `status`
//! and `resume` pick up a job folder later (a lost node costs one part, not the render).

use super::console::{note, out};
use super::slurm_render_args::{check_render_args, identity_source};
use anyhow::{Context, Result, bail};
use clap::{Args, Subcommand};
use embray::distributed::slurm::{
    self, JOB_FILE, JobFile, PartStatus, SbatchOptions, Submission, TaskState, part_path, status,
};
use embray::distributed::{MAX_PARTS, Split};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::path::{Path, PathBuf};
use std::time::Duration;

#[derive(Args, Debug)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct SlurmArgs {
    #[command(subcommand)]
    pub action: Option<SlurmAction>,
    #[command(flatten)]
    pub submit: SubmitArgs,
}

#[derive(Subcommand, Debug)]
pub enum SlurmAction {
    /// What each part and the merge of a job folder are doing; names the missing parts.
    Status {
        /// The job folder (`--out` of the submission).
        dir: PathBuf,
    },
    /// Resubmit only the parts that are missing or failed, then the merge.
    Resume {
        dir: PathBuf,
        /// Return after submitting instead of following the jobs.
        #[arg(long)]
        no_wait: bool,
    },
}

#[derive(Args, Debug)]
pub struct SubmitArgs {
    /// Scene file (.toml, or a one-camera CENG795 .xml). It, its meshes, the job folder and
    /// the embray binary must be on storage every node mounts.
    #[arg(required = true)]
    pub scene: Option<PathBuf>,
    /// Number of parts: array tasks 0..N-1.
    #[arg(long, required = true)]
    pub parts: Option<u32>,
    /// Job folder: scripts, part files, logs, and the merged render.exr/render.png.
    #[arg(long, required = true)]
    pub out: Option<PathBuf>,
    /// How the render is divided among the parts.
    #[arg(long, value_parser = super::choices::choice::<Split>(), default_value_t = Split::Tiles)]
    pub split: Split,
    /// Slurm partition of every job (sbatch --partition) [default: the cluster's].
    #[arg(long)]
    pub partition: Option<String>,
    /// Time limit of each task (sbatch --time, e.g. 01:00:00).
    #[arg(long)]
    pub time: Option<String>,
    /// CPUs of each task; the part renders with that many threads.
    #[arg(long, default_value_t = 1)]
    pub cpus_per_task: u32,
    /// At most K tasks of the array at once (--array=0-N%K).
    #[arg(long, value_name = "K")]
    pub max_running: Option<u32>,
    /// Any other sbatch option, given to every job (repeat for several).
    #[arg(long, allow_hyphen_values = true)]
    pub sbatch_arg: Vec<String>,
    /// Return after submitting instead of following the jobs.
    #[arg(long)]
    pub no_wait: bool,
    /// `embray render` options for every part (after `--`: e.g. `-- --spp 64 --seed 3`).
    #[arg(last = true)]
    pub render_args: Vec<String>,
}

pub fn run(args: &SlurmArgs) -> Result<()> {
    match &args.action {
        Some(SlurmAction::Status { dir }) => {
            let report = status(dir, &mut identity_source())?;
            out(report.text(dir))
        }
        Some(SlurmAction::Resume { dir, no_wait }) => resume(dir, *no_wait),
        None => submit(&args.submit),
    }
}

/// Options `embray slurm` sets itself on every part.
const OWN_OPTIONS: [&str; 8] =
    ["-o", "--output", "--png", "--part", "--split", "--stats-json", "--threads", "--out-dir"];

fn submit(args: &SubmitArgs) -> Result<()> {
    let (Some(scene), Some(parts), Some(dir)) = (&args.scene, args.parts, &args.out) else {
        bail!("embray slurm needs SCENE, --parts and --out");
    };
    if !(1..=MAX_PARTS).contains(&parts) {
        bail!("--parts is {parts}, but must be between 1 and {MAX_PARTS}");
    }
    if args.cpus_per_task == 0 {
        bail!("--cpus-per-task must be at least 1");
    }
    if args.max_running == Some(0) {
        bail!("--max-running must be at least 1");
    }
    if let Some(own) = args
        .render_args
        .iter()
        .find(|a| OWN_OPTIONS.iter().any(|o| a.as_str() == *o || a.starts_with(&format!("{o}="))))
    {
        bail!("'{own}' is set by embray slurm for every part; leave it out of the render options");
    }
    let scene = scene
        .canonicalize()
        .with_context(|| format!("cannot find the scene '{}'", scene.display()))?;
    check_render_args(&scene, parts, args.split, &args.render_args)?;
    let slurm_version = slurm::version()?;
    if dir.join(JOB_FILE).exists() {
        bail!(
            "'{}' already holds a job ({JOB_FILE}): `embray slurm status {0}` or `embray slurm \
             resume {0}`, or choose another --out",
            dir.display()
        );
    }
    // Job-only fields are checked before any folder is made (the real paths come after).
    let draft = job_file(args, &scene, parts)?;
    slurm::parts_script(&draft, &std::path::absolute(dir)?).map_err(anyhow::Error::msg)?;
    let existed = dir.exists();
    for sub in ["parts", "logs"] {
        std::fs::create_dir_all(dir.join(sub))
            .with_context(|| format!("cannot create '{}'", dir.join(sub).display()))?;
    }
    let dir = dir.canonicalize()?;
    let job = draft;
    let parts_script = slurm::parts_script(&job, &dir).map_err(anyhow::Error::msg)?;
    let merge_script = slurm::merge_script(&job, &dir).map_err(anyhow::Error::msg)?;
    write_text(&dir.join("parts.sbatch"), &parts_script)?;
    write_text(&dir.join("merge.sbatch"), &merge_script)?;
    write_text(&dir.join(JOB_FILE), &job.encode())?;
    note(format!(
        "{}: {parts} parts of {} into {}",
        slurm_version,
        job.scene.display(),
        dir.display()
    ));
    let all: Vec<u32> = (0..parts).collect();
    let job = submit_round(&dir, job, &all, &[]).inspect_err(|error| {
        // Nothing queued (Slurm down, say): the folder as it was, so that a retry starts anew
        // rather than finding a job that never ran.
        if error.downcast_ref::<NothingSubmitted>().is_some() {
            remove_unsubmitted(&dir, existed);
        }
    })?;
    if args.no_wait {
        return Ok(());
    }
    follow(&dir, &job)
}

/// The job file of a new submission of `parts` parts of `scene`.
fn job_file(args: &SubmitArgs, scene: &Path, parts: u32) -> Result<JobFile> {
    Ok(JobFile {
        embray: std::env::current_exe().context("cannot find the embray binary")?,
        scene: scene.to_path_buf(),
        parts,
        split: args.split,
        render_args: args.render_args.clone(),
        sbatch: SbatchOptions {
            partition: args.partition.clone(),
            time: args.time.clone(),
            cpus_per_task: args.cpus_per_task,
            max_running: args.max_running,
            extra: args.sbatch_arg.clone(),
        },
        submissions: Vec::new(),
    })
}

fn write_text(path: &Path, text: &str) -> Result<()> {
    embray::output::write_one(path, |w| w.write_all(text.as_bytes()))?;
    Ok(())
}

/// Submits `parts` as one array job and a merge that waits for it and for `also_wait_for`
/// (jobs still running from earlier rounds); records the round in the job file.
fn submit_round(
    dir: &Path,
    mut job: JobFile,
    parts: &[u32],
    also_wait_for: &[String],
) -> Result<JobFile> {
    let mut dependencies = also_wait_for.to_vec();
    let array_job = if parts.is_empty() {
        None
    } else {
        let list = slurm::array_ranges(parts);
        let throttle = job.sbatch.max_running.map(|k| format!("%{k}")).unwrap_or_default();
        let script = dir.join("parts.sbatch");
        let id = slurm::submit(&script, &[format!("--array={list}{throttle}")])
            .map_err(NothingSubmitted)?;
        note(format!("submitted parts {list} of {} as array job {id}", job.parts));
        dependencies.push(id.clone());
        Some(id)
    };
    let merge_args = if dependencies.is_empty() {
        Vec::new()
    } else {
        vec![format!("--dependency=afterok:{}", dependencies.join(":"))]
    };
    let merge_job = slurm::submit(&dir.join("merge.sbatch"), &merge_args)?;
    note(format!(
        "submitted the merge as job {merge_job} (after {})",
        if dependencies.is_empty() { "nothing".to_owned() } else { dependencies.join(", ") }
    ));
    job.submissions.push(Submission { array_job, parts: parts.to_vec(), merge_job });
    write_text(&dir.join(JOB_FILE), &job.encode())?;
    Ok(job)
}

/// A round Slurm refused before queuing any job of it.
#[derive(Debug, thiserror::Error)]
#[error(transparent)]
struct NothingSubmitted(slurm::SchedulerError);

/// Removes what a first submission made in `dir` (and `dir`, unless it `existed`).
fn remove_unsubmitted(dir: &Path, existed: bool) {
    for file in [JOB_FILE, "parts.sbatch", "merge.sbatch"] {
        let _ = std::fs::remove_file(dir.join(file));
    }
    // Only if empty: anything else in them is not this command's.
    for sub in ["parts", "logs"] {
        let _ = std::fs::remove_dir(dir.join(sub));
    }
    if !existed {
        let _ = std::fs::remove_dir(dir);
    }
}

fn resume(dir: &Path, no_wait: bool) -> Result<()> {
    let dir = dir.canonicalize().with_context(|| format!("cannot find '{}'", dir.display()))?;
    let report = status(&dir, &mut identity_source())?;
    if let Some(why) = &report.unchecked {
        bail!(
            "cannot check the part files against the scene and the options, so neither can \
             new parts be rendered: {why}"
        );
    }
    if report.merged {
        note(format!(
            "nothing to resume: the render is merged ({})",
            dir.join("render.exr").display()
        ));
        return Ok(());
    }
    let missing = report.missing();
    let merge_live = report.merge.as_ref().is_some_and(TaskState::is_active);
    if missing.is_empty() && merge_live {
        note("nothing to resume: every part is done or queued, and so is the merge");
    } else {
        if let (true, Some(round)) = (report.merge.is_some(), report.job.submissions.last()) {
            // A merge waiting on a failed task would wait for ever (or run on old parts).
            if report.merge.as_ref().is_some_and(|s| s.state == "PENDING") {
                slurm::cancel(&round.merge_job)?;
                note(format!(
                    "cancelled the merge job {} that waited for the lost parts",
                    round.merge_job
                ));
            }
        }
        let running: Vec<String> = report
            .parts
            .iter()
            .filter_map(|p| match p {
                PartStatus::Active(s) => Some(s.job_id.clone()),
                _ => None,
            })
            .collect();
        for &i in &missing {
            // A damaged file, or one of another render, is replaced when the part is
            // rendered again; the merge must not see it before.
            if matches!(report.parts[i as usize], PartStatus::Damaged(_) | PartStatus::Stale(_)) {
                let path = part_path(&dir, i, report.job.parts);
                std::fs::remove_file(&path)
                    .with_context(|| format!("cannot remove '{}'", path.display()))?;
            }
        }
        submit_round(&dir, report.job, &missing, &running)?;
    }
    if no_wait {
        return Ok(());
    }
    follow(&dir, &JobFile::read(&dir).map_err(anyhow::Error::msg)?)
}

/// Follows the last round of `job` until the merge has written its image.
fn follow(dir: &Path, job: &JobFile) -> Result<()> {
    let bar =
        ProgressBar::with_draw_target(Some(u64::from(job.parts) + 1), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template("{bar:40} {pos}/{len} {elapsed} {msg}") {
        bar.set_style(style);
    }
    let mut identity = identity_source();
    loop {
        let report = status(dir, &mut identity)?;
        let done = report.done() as u64;
        bar.set_position(done + u64::from(report.merged));
        let merge = report.merge.clone();
        bar.set_message(match &merge {
            Some(s) => format!("merge {}", s.state.to_lowercase()),
            None => String::new(),
        });
        let finished = merge.as_ref().is_none_or(|s| !s.is_active());
        if finished {
            bar.finish_and_clear();
            if report.merged && merge.as_ref().is_none_or(|s| s.state == "COMPLETED") {
                note(format!(
                    "merged: {} and {}",
                    dir.join("render.exr").display(),
                    dir.join("render.png").display()
                ));
                return Ok(());
            }
            out(report.text(dir))?;
            let log =
                merge.as_ref().map(|s| dir.join("logs").join(format!("merge.{}.out", s.job_id)));
            match merge {
                Some(s) if s.reason == "DependencyNeverSatisfied" => bail!(
                    "a part failed or was cancelled, so the merge cannot run: `embray slurm resume {}`",
                    dir.display()
                ),
                Some(s) => bail!(
                    "the merge job {} ended {}: see {}",
                    s.job_id,
                    s.state,
                    log.map(|l| l.display().to_string()).unwrap_or_default()
                ),
                None => bail!("Slurm no longer knows the merge job and there is no render.exr"),
            }
        }
        // Polite to the controller on large arrays: every 2 s, plus 1 s per 100 tasks, at most
        // every 30 s (one `squeue` per submission round and one for the merge).
        let seconds = (2 + u64::from(job.parts) / 100).min(30);
        std::thread::sleep(Duration::from_secs(seconds));
    }
}
