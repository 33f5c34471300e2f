//! `embray slurm`: a split render as one Slurm array job plus a dependent merge; `status`
//! and `resume` pick up a job folder later (a lost node costs one part, not the render).

use super::console::{note, out};
use anyhow::{Context, Result, bail};
use clap::{Args, Parser, Subcommand};
use embray::distributed::slurm::{
    self, JOB_FILE, JobFile, PartStatus, SbatchOptions, Submission, TaskState, part_path, status,
};
use embray::distributed::{MAX_PARTS, Part, PartIdentity, Split};
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
    let job = submit_round(&dir, job, &all, &[])?;
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

/// What the job's parts must record, from its scene and options as they are now (a part
/// rendered now records that); asked at most once per command, as following a job asks
/// for its status every few seconds.
fn identity_source() -> impl FnMut(&JobFile) -> Result<PartIdentity, String> {
    let mut known: Option<Result<PartIdentity, String>> = None;
    move |job| {
        let identity = || check_render_args(&job.scene, job.parts, job.split, &job.render_args);
        known.get_or_insert_with(|| identity().map_err(|e| format!("{e:#}"))).clone()
    }
}

/// Parses the render options as `embray render` would and checks that the split works for
/// the scene, so that nothing is submitted that every task would refuse. Returns what each
/// part will record of the scene and the options.
fn check_render_args(
    scene: &Path,
    parts: u32,
    split: Split,
    render_args: &[String],
) -> Result<PartIdentity> {
    let read_before_scene = embray::scene::files_read().len();
    let mut argv = vec!["embray".to_owned(), "render".to_owned()];
    argv.push(scene.to_string_lossy().into_owned());
    argv.extend(render_args.iter().cloned());
    let cli = super::Cli::try_parse_from(&argv).context("the render options (after --)")?;
    let super::Command::Render(render) = cli.command else {
        bail!("the render options (after --) are not `embray render` options");
    };
    let mut desc = if embray::scene::ceng795::is_ceng795_path(scene) {
        let cameras = embray::scene::xml::load(scene, &render.defines)?;
        let mut cameras = super::preview::select_cameras(cameras, render.camera.as_deref(), scene)?;
        if cameras.len() != 1 {
            bail!(
                "'{}' has {} cameras; a split render is one image: choose one with --camera \
                 (after --)",
                scene.display(),
                cameras.len()
            );
        }
        cameras.swap_remove(0).scene
    } else {
        super::load_scene(Some(scene), &render.defines)?
    };
    render.apply_preview(&mut desc)?;
    if let Some(problem) = render.part_flag_problem() {
        bail!("{problem} (after --: a split render's parts are `embray render --part`)");
    }
    if let Some(problem) = super::render_args::RenderArgs::part_scene_problem(&desc) {
        bail!(problem);
    }
    let options = render.to_options(&desc)?;
    let camera = render.camera.as_ref().map(|c| format!("camera '{c}'"));
    render.check_samples(&desc, options.spp, camera.as_deref())?;
    let part = Part { index: 0, count: parts, split };
    let size = (desc.camera.width, desc.camera.height);
    part.check(size, embray::render::TILE_SIZE, options.spp.max(1))?;
    // As `render --part` hashes them: the scene and every file it read, in order.
    let scene_files = embray::scene::files_read().split_off(read_before_scene);
    let scene_hash = embray::distributed::hash_files(&scene_files)?;
    Ok(PartIdentity { scene_hash, options: embray::distributed::options_fingerprint(&options) })
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
        let id = slurm::submit(&dir.join("parts.sbatch"), &[format!("--array={list}{throttle}")])?;
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
