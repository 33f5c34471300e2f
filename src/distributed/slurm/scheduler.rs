//! Slurm's own commands (`sbatch`, `squeue`, `scontrol`, `scancel`), each run with a time
//! limit and its answer parsed. No accounting database is assumed (`sacct` is often off on
//! small clusters): job states come from `squeue -t all`, which keeps finished jobs for
//! `MinJobAge`, and a job it no longer knows is judged by the files it was to write.

use std::io::Read;
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// How long one scheduler command may take before it is given up.
const COMMAND_TIMEOUT: Duration = Duration::from_secs(60);

#[derive(Debug, thiserror::Error)]
pub enum SchedulerError {
    #[error(
        "cannot run `{command}`: {message} (is Slurm installed here, and is this a login node?)"
    )]
    Spawn { command: String, message: String },
    #[error("`{command}` failed: {message}")]
    Failed { command: String, message: String },
    #[error("`{command}` did not answer within {} s", COMMAND_TIMEOUT.as_secs())]
    Timeout { command: String },
    #[error("`{command}` answered '{answer}', not a job id")]
    NoJobId { command: String, answer: String },
}

/// The most bytes kept of one command's output: `squeue`'s answer for the largest job
/// (100,000 tasks of about 40 bytes each) with room to spare.
const MAX_ANSWER: u64 = 64 << 20;

/// What a reader thread got from one of a command's pipes: the bytes kept, and whether
/// there were more.
type Drained = std::io::Result<(Vec<u8>, bool)>;

/// Reads `stream` to its end on a thread of its own. The command's pipes are drained while
/// it runs: a pipe holds 64 KiB, and a command whose output is larger (`squeue` on a few
/// thousand tasks) blocks writing until it is read, so it would never exit.
fn drain(stream: Option<impl Read + Send + 'static>) -> mpsc::Receiver<Drained> {
    let (sender, receiver) = mpsc::channel();
    std::thread::spawn(move || {
        let Some(mut stream) = stream else {
            let _ = sender.send(Ok((Vec::new(), false)));
            return;
        };
        let mut bytes = Vec::new();
        let result = (&mut stream).take(MAX_ANSWER).read_to_end(&mut bytes).and_then(|_| {
            // Past the cap the rest is still read, so the command can finish.
            let more = std::io::copy(&mut stream, &mut std::io::sink())?;
            Ok((bytes, more > 0))
        });
        let _ = sender.send(result);
    });
    receiver
}

/// Runs `program args…`, returning its standard output.
fn run(program: &str, args: &[String]) -> Result<String, SchedulerError> {
    let command = std::iter::once(program.to_owned())
        .chain(args.iter().cloned())
        .collect::<Vec<_>>()
        .join(" ");
    let mut child = Command::new(program)
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| SchedulerError::Spawn { command: command.clone(), message: e.to_string() })?;
    let (stdout, stderr) = (drain(child.stdout.take()), drain(child.stderr.take()));
    let deadline = Instant::now() + COMMAND_TIMEOUT;
    let failed = |message: String| SchedulerError::Failed { command: command.clone(), message };
    let status = loop {
        if let Some(status) = child.try_wait().map_err(|e| failed(e.to_string()))? {
            break status;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            return Err(SchedulerError::Timeout { command });
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    // A process the command left behind may hold its pipes open: the wait stays bounded.
    let collect = |receiver: mpsc::Receiver<Drained>, name: &str| {
        let left = deadline.saturating_duration_since(Instant::now());
        match receiver.recv_timeout(left) {
            Ok(Ok((bytes, more))) => Ok((String::from_utf8_lossy(&bytes).into_owned(), more)),
            Ok(Err(e)) => Err(failed(format!("cannot read its {name}: {e}"))),
            Err(_) => Err(SchedulerError::Timeout { command: command.clone() }),
        }
    };
    let (err, _) = collect(stderr, "standard error")?;
    if !status.success() {
        let message = crate::excerpt::excerpt(err.trim());
        return Err(SchedulerError::Failed { command, message });
    }
    match collect(stdout, "standard output")? {
        (out, false) => Ok(out),
        (_, true) => {
            Err(failed(format!("its standard output is longer than {} MiB", MAX_ANSWER >> 20)))
        }
    }
}

/// Submits `script` with `args` (`--array`, `--dependency`) and returns the job id.
pub fn submit(script: &Path, args: &[String]) -> Result<String, SchedulerError> {
    let mut all = vec!["--parsable".to_owned()];
    all.extend(args.iter().cloned());
    all.push(script.to_string_lossy().into_owned());
    let answer = run("sbatch", &all)?;
    // `--parsable` prints `id` or `id;cluster`.
    let id = answer.trim().split(';').next().unwrap_or("").to_owned();
    if !super::job_file::is_job_id(&id) {
        return Err(SchedulerError::NoJobId {
            command: format!("sbatch {}", all.join(" ")),
            answer: crate::excerpt::excerpt(answer.trim()),
        });
    }
    Ok(id)
}

/// A job's (or an array task's) state as Slurm reports it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TaskState {
    /// `PENDING`, `RUNNING`, `COMPLETED`, `FAILED`, `CANCELLED`, `TIMEOUT`, …
    pub state: String,
    /// Why it is pending (`Dependency`, `DependencyNeverSatisfied`, …).
    pub reason: String,
    /// The task's own job id (an array task has one besides `array_task`).
    pub job_id: String,
}

impl TaskState {
    /// Pending or running: it may still write its file.
    pub fn is_active(&self) -> bool {
        let live = [
            "PENDING",
            "RUNNING",
            "CONFIGURING",
            "COMPLETING",
            "REQUEUED",
            "RESIZING",
            "SUSPENDED",
        ];
        live.contains(&self.state.as_str()) && self.reason != "DependencyNeverSatisfied"
    }
}

fn squeue(jobs: &str) -> Result<Vec<(String, TaskState)>, SchedulerError> {
    let args = ["-t", "all", "-r", "-h", "-j", jobs, "-o", "%K|%T|%r|%A"].map(String::from);
    let out = match run("squeue", &args) {
        Ok(out) => out,
        // A job Slurm has forgotten (older than MinJobAge) is an error to squeue.
        Err(SchedulerError::Failed { message, .. }) if message.contains("Invalid job id") => {
            String::new()
        }
        Err(e) => return Err(e),
    };
    Ok(out
        .lines()
        .filter_map(|line| {
            let f: Vec<&str> = line.trim().split('|').collect();
            (f.len() == 4).then(|| {
                let state =
                    TaskState { state: f[1].into(), reason: f[2].into(), job_id: f[3].into() };
                (f[0].to_owned(), state)
            })
        })
        .collect())
}

/// The state of each task of the array job `array` that Slurm still knows: (task index,
/// state).
pub fn task_states(array: &str) -> Result<Vec<(u32, TaskState)>, SchedulerError> {
    Ok(squeue(array)?
        .into_iter()
        .filter_map(|(task, state)| Some((task.parse().ok()?, state)))
        .collect())
}

/// The state of the job `id`, if Slurm still knows it.
pub fn job_state(id: &str) -> Result<Option<TaskState>, SchedulerError> {
    Ok(squeue(id)?.into_iter().next().map(|(_, state)| state))
}

/// Cancels the job `id` (an array, one task `id_i`, or a plain job).
pub fn cancel(id: &str) -> Result<(), SchedulerError> {
    run("scancel", &[id.to_owned()]).map(|_| ())
}

/// Slurm's version as `sbatch` reports it ("slurm 22.05.8"): fails where there is no Slurm
/// client, before anything is written.
pub fn version() -> Result<String, SchedulerError> {
    Ok(run("sbatch", &["--version".to_owned()])?.trim().to_owned())
}
