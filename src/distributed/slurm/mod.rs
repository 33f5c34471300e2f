//! Running a split render on Slurm: the job folder's record (`job_file`), the batch scripts
//! (`scripts`), the scheduler's commands (`scheduler`) and where a job stands (`status`). The command line
//! (`embray slurm`) drives them.

mod job_file;
mod scheduler;
mod scripts;
mod status;

pub use job_file::{JOB_FILE, JobFile, SbatchOptions, Submission, part_path};
pub use scheduler::{SchedulerError, TaskState, cancel, job_state, submit, task_states, version};
pub use scripts::{array_ranges, merge_script, parts_script, shell_quote};
pub use status::{PartStatus, Report, StatusError, status};
