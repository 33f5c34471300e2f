//! The two batch scripts of a Slurm render: the array job whose task I renders part I, and
//! the merge. Every path in them is absolute and must be visible on every node; each script
//! checks that before it starts, so a node without the shared folder fails with a message
//! rather than a missing part.

use super::job_file::{JOB_FILE, JobFile, part_path};
use std::fmt::Write;
use std::path::Path;

/// Sorted task indices as sbatch's `--array` list: runs become ranges (`0-3,7,9-10`).
pub fn array_ranges(tasks: &[u32]) -> String {
    let mut sorted = tasks.to_vec();
    sorted.sort_unstable();
    sorted.dedup();
    let mut out: Vec<String> = Vec::new();
    let mut i = 0;
    while i < sorted.len() {
        let start = sorted[i];
        while i + 1 < sorted.len() && sorted[i + 1] == sorted[i] + 1 {
            i += 1;
        }
        let end = sorted[i];
        out.push(if start == end { start.to_string() } else { format!("{start}-{end}") });
        i += 1;
    }
    out.join(",")
}

/// `text` quoted for a POSIX shell.
pub fn shell_quote(text: &str) -> String {
    if !text.is_empty()
        && text.bytes().all(|b| b.is_ascii_alphanumeric() || b"/._-=,:+%@".contains(&b))
    {
        return text.to_owned();
    }
    format!("'{}'", text.replace('\'', r"'\''"))
}

fn quote_path(path: &Path) -> String {
    shell_quote(&path.to_string_lossy())
}

/// `text` quoted for an `#SBATCH` line, which `sbatch` reads with its own rule, not the
/// shell's: a backslash escapes the next character even inside quotes, and an unquoted
/// `#` ends the line.
fn sbatch_quote(text: &str) -> String {
    if !text.is_empty()
        && text.bytes().all(|b| b.is_ascii_alphanumeric() || b"/._-=,:+%@".contains(&b))
    {
        return text.to_owned();
    }
    format!("\"{}\"", text.replace('\\', "\\\\").replace('"', "\\\""))
}

/// Refuses what an `#SBATCH` line cannot carry: a line break would end the line, and the
/// rest would run as a command of the script.
fn check_line(what: &str, text: &str) -> Result<(), String> {
    if text.chars().any(char::is_control) {
        return Err(format!(
            "{what} \"{}\" holds a line break or another control character, which a batch \
             script's #SBATCH line cannot carry",
            text.escape_debug()
        ));
    }
    Ok(())
}

fn header(
    out: &mut String,
    job: &JobFile,
    dir: &Path,
    name: &str,
    log: &str,
    cpus: u32,
) -> Result<(), String> {
    let dir_text = dir.to_string_lossy();
    check_line("the job folder", &dir_text)?;
    let sbatch = &job.sbatch;
    for (what, value) in [("--partition", &sbatch.partition), ("--time", &sbatch.time)] {
        value.as_deref().map_or(Ok(()), |v| check_line(what, v))?;
    }
    for arg in &sbatch.extra {
        check_line("--sbatch-arg", arg)?;
    }
    let _ = writeln!(out, "#!/bin/bash");
    let _ = writeln!(out, "#SBATCH --job-name={name}");
    // `%` starts one of Slurm's file name patterns: a folder's own `%` is doubled.
    let log_path = format!("{}/logs/{log}", dir_text.replace('%', "%%"));
    let _ = writeln!(out, "#SBATCH --output={}", sbatch_quote(&log_path));
    let _ = writeln!(out, "#SBATCH --cpus-per-task={cpus}");
    if let Some(p) = &sbatch.partition {
        let _ = writeln!(out, "#SBATCH --partition={}", sbatch_quote(p));
    }
    if let Some(t) = &sbatch.time {
        let _ = writeln!(out, "#SBATCH --time={}", sbatch_quote(t));
    }
    for arg in &sbatch.extra {
        let _ = writeln!(out, "#SBATCH {}", sbatch_quote(arg));
    }
    let _ = writeln!(out, "set -euo pipefail");
    // Written by the submitting node: a node that cannot read it does not share the folder.
    // The paths are printf's arguments, each quoted as the exec line quotes it: inside the
    // message's own quotes a folder named `$(…)` would run.
    let job_file = quote_path(&dir.join(JOB_FILE));
    let embray = quote_path(&job.embray);
    let message = shell_quote(
        "embray: node %s cannot see '%s' or '%s': the job folder and embray must be on \
         storage every node mounts\\n",
    );
    let _ = writeln!(
        out,
        "if [ ! -r {job_file} ] || [ ! -x {embray} ]; then\n  printf {message} \"$(hostname)\" \
         {job_file} {embray} >&2\n  exit 2\nfi"
    );
    Ok(())
}

/// The array job's script: task `$SLURM_ARRAY_TASK_ID` renders that part (the array range
/// is given to `sbatch`, so a resume can submit only some parts).
pub fn parts_script(job: &JobFile, dir: &Path) -> Result<String, String> {
    let mut out = String::new();
    header(&mut out, job, dir, "embray-parts", "part-%a.%A.out", job.sbatch.cpus_per_task)?;
    let parts_dir = quote_path(&dir.join("parts"));
    let part_file = format!("{parts_dir}/part-\"$i\"-of-{}.exr", job.parts);
    let _ = writeln!(out, "i=$SLURM_ARRAY_TASK_ID");
    let mut command = vec![
        quote_path(&job.embray),
        "render".to_owned(),
        quote_path(&job.scene),
        "--part".to_owned(),
        format!("\"$i/{}\"", job.parts),
        "--split".to_owned(),
        job.split.to_string(),
        "-o".to_owned(),
        part_file,
        "--threads".to_owned(),
        "\"${SLURM_CPUS_PER_TASK:-1}\"".to_owned(),
        "--quiet".to_owned(),
    ];
    command.extend(job.render_args.iter().map(|a| shell_quote(a)));
    let _ = writeln!(out, "exec {}", command.join(" "));
    Ok(out)
}

/// The merge's script: every part into `DIR/render.exr` and `DIR/render.png`.
pub fn merge_script(job: &JobFile, dir: &Path) -> Result<String, String> {
    let mut out = String::new();
    header(&mut out, job, dir, "embray-merge", "merge.%j.out", 1)?;
    let mut command = vec![quote_path(&job.embray), "merge".to_owned()];
    command.extend((0..job.parts).map(|i| quote_path(&part_path(dir, i, job.parts))));
    command.extend([
        "-o".to_owned(),
        quote_path(&dir.join("render.exr")),
        "--png".to_owned(),
        quote_path(&dir.join("render.png")),
    ]);
    let _ = writeln!(out, "exec {}", command.join(" "));
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distributed::Split;
    use crate::distributed::slurm::SbatchOptions;
    use std::path::PathBuf;

    fn job() -> JobFile {
        JobFile {
            embray: PathBuf::from("/opt/embray/bin/embray"),
            scene: PathBuf::from("/shared/scenes/it's here.toml"),
            parts: 4,
            split: Split::Samples,
            render_args: vec!["--spp".into(), "64".into()],
            sbatch: SbatchOptions {
                partition: Some("render".into()),
                time: Some("01:00:00".into()),
                cpus_per_task: 8,
                max_running: None,
                extra: vec!["--constraint=avx2".into()],
            },
            submissions: vec![],
        }
    }

    #[test]
    fn scripts_quote_paths_and_carry_every_setting() {
        let dir = Path::new("/shared/out dir");
        let parts = parts_script(&job(), dir).unwrap();
        assert!(parts.contains("#SBATCH --partition=render\n"), "{parts}");
        assert!(parts.contains("#SBATCH --time=01:00:00\n"));
        assert!(parts.contains("#SBATCH --cpus-per-task=8\n"));
        assert!(parts.contains("#SBATCH --constraint=avx2\n"));
        assert!(parts.contains("#SBATCH --output=\"/shared/out dir/logs/part-%a.%A.out\"\n"));
        assert!(parts.contains(
            "exec /opt/embray/bin/embray render '/shared/scenes/it'\\''s here.toml' --part \"$i/4\" \
             --split samples -o '/shared/out dir/parts'/part-\"$i\"-of-4.exr"
        ), "{parts}");
        assert!(parts.trim_end().ends_with("--spp 64"));
        let merge = merge_script(&job(), dir).unwrap();
        assert!(
            merge.contains(
                "'/shared/out dir/parts/part-3-of-4.exr' -o '/shared/out dir/render.exr'"
            )
        );
        assert!(!merge.contains("part-4-of-4"));
        // Slurm's own rule: `%` doubled, a backslash and a quote escaped.
        let odd = parts_script(&job(), Path::new("/a%b/c\\d\"e")).unwrap();
        assert!(
            odd.contains("#SBATCH --output=\"/a%%b/c\\\\d\\\"e/logs/part-%a.%A.out\"\n"),
            "{odd}"
        );
        let error = parts_script(&job(), Path::new("/a\ntouch PWNED")).unwrap_err();
        assert!(
            error.contains("the job folder \"/a\\ntouch PWNED\" holds a line break"),
            "{error}"
        );
    }

    #[test]
    fn array_lists_use_ranges() {
        assert_eq!(array_ranges(&[0, 1, 2, 3]), "0-3");
        assert_eq!(array_ranges(&[9, 1, 3, 4, 5, 7, 10]), "1,3-5,7,9-10");
        assert_eq!(array_ranges(&[6]), "6");
    }

    #[test]
    fn shell_quote_survives_the_shell() {
        for text in ["plain", "with space", "it's", "$HOME", "a\"b", "", "*"] {
            let out = std::process::Command::new("sh")
                .arg("-c")
                .arg(format!("printf %s {}", shell_quote(text)))
                .output()
                .unwrap();
            assert_eq!(String::from_utf8_lossy(&out.stdout), text);
        }
    }
}
