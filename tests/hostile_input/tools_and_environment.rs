//! The tools around a render under hostile input: environment variables, Slurm's commands
//! and a hand-edited job file, part files whose metadata lies, output names whose
//! extension is not what would be written, and ambiguous or degenerate arguments.

use crate::harness::{Run, Scratch, accepted_in, refused_in, scene, xml_scene};
use embray::film::Film;
use glam::Vec3;
use std::time::{Duration, Instant};

/// Runs `args` with the environment variables `env`; as `refused_in`, the run must fail
/// with exit 1, say every one of `expected` and change no file.
#[track_caller]
fn refused_with_env(scratch: &Scratch, env: &[(&str, &str)], args: &[&str], expected: &[&str]) {
    let before = scratch.snapshot();
    let run = Run::from(scratch.command(args).envs(env.iter().copied()).output().unwrap());
    run.assert_no_panic();
    assert_eq!(run.code, Some(1), "{env:?} should fail:\n{}", run.stderr);
    run.assert_says(expected);
    assert_eq!(scratch.snapshot(), before, "files changed:\n{}", run.stderr);
}

#[test]
fn a_progress_interval_that_is_no_number_of_seconds_is_refused_naming_it() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    // 1e20 s panicked converting to a Duration; the others silently became 5 s.
    for value in ["1e20", "abc", "-1", "nan", "inf"] {
        let env = [("EMBRAY_PROGRESS_SECONDS", value)];
        let expected = ["EMBRAY_PROGRESS_SECONDS", &format!("'{value}'"), "0 to 1000000"];
        refused_with_env(&scratch, &env, &["render", "s.toml", "-o", "o.exr"], &expected);
    }
    let mut command = scratch.command(&["render", "s.toml", "-o", "o.exr", "-q"]);
    let run = Run::from(command.env("EMBRAY_PROGRESS_SECONDS", "0.5").output().unwrap());
    assert_eq!(run.code, Some(0), "{}", run.stderr);
}

#[test]
fn a_memory_budget_that_is_no_whole_number_of_bytes_is_refused_not_ignored() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    for value in ["1e3", "1KiB", "-1", "8 GB"] {
        let env = [("EMBRAY_MAX_MEMORY", value)];
        let expected = ["EMBRAY_MAX_MEMORY", &format!("'{value}'"), "whole number of bytes"];
        refused_with_env(&scratch, &env, &["render", "s.toml", "-o", "o.exr"], &expected);
    }
    // A plain number is a budget: 1000 bytes fit no render.
    let env = [("EMBRAY_MAX_MEMORY", "1000")];
    refused_with_env(&scratch, &env, &["render", "s.toml", "-o", "o.exr"], &["memory"]);
}

/// A job folder of `parts` parts in one array job `array` and a merge job `merge`.
fn job_folder(scratch: &Scratch, parts: u32, array: &str, merge: &str) {
    let job = format!(
        r#"{{"embray": "/bin/embray", "scene": "/s.toml", "parts": {parts}, "split": "samples",
        "render_args": [], "sbatch": {{"partition": null, "time": null, "cpus_per_task": 1,
        "max_running": null, "extra": []}}, "submissions": [{{"array_job": "{array}",
        "parts": [0], "merge_job": "{merge}"}}]}}"#
    );
    scratch.write("job/job.json", job);
}

/// Fake Slurm commands in `bin/` (each logs its arguments to `calls.log`) and a PATH that
/// finds them first.
fn fake_slurm(scratch: &Scratch, squeue_body: &str) -> String {
    use std::os::unix::fs::PermissionsExt;
    let log = scratch.path("calls.log");
    for (name, body) in [("squeue", squeue_body), ("scancel", ""), ("sbatch", "echo 1")] {
        let script = format!("#!/bin/sh\necho \"{name} $*\" >> '{}'\n{body}\n", log.display());
        let path = scratch.write(&format!("bin/{name}"), script);
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    let path = std::env::var("PATH").unwrap_or_default();
    format!("{}:{path}", scratch.path("bin").display())
}

#[test]
fn slurm_status_reads_an_answer_larger_than_a_pipe_holds() {
    // 5000 task lines (~90 KB) and as much on standard error: a reader that waits for
    // squeue to exit first waits for ever on a full pipe (until its 60 s time limit).
    let scratch = Scratch::new();
    job_folder(&scratch, 5000, "1000", "2000");
    let squeue = "awk 'BEGIN { for (i = 0; i < 5000; i++) { print i \"|PENDING|None|\" 1000 + i; \
                  print \"noise on standard error, line \" i > \"/dev/stderr\" } }'";
    let path = fake_slurm(&scratch, squeue);
    let start = Instant::now();
    let output = scratch.command(&["slurm", "status", "job"]).env("PATH", path).output().unwrap();
    let run = Run::from(output);
    run.assert_no_panic();
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(start.elapsed() < Duration::from_secs(30), "took {:?}", start.elapsed());
    let head: String = run.stdout.chars().take(500).collect();
    assert!(run.stdout.contains("part 4999/5000  PENDING, job 5999"), "{head}");
}

#[test]
fn job_ids_that_are_not_slurm_ids_are_refused_before_any_slurm_command_runs() {
    for (array, merge, field, id) in [
        ("1000", "--user=root", "submissions[0].merge_job", "--user=root"),
        ("-h", "1001", "submissions[0].array_job", "-h"),
        ("1000", "", "submissions[0].merge_job", "''"),
    ] {
        let scratch = Scratch::new();
        job_folder(&scratch, 2, array, merge);
        let path = fake_slurm(&scratch, "");
        for command in ["status", "resume"] {
            let env = [("PATH", path.as_str())];
            let args = ["slurm", command, "job"];
            refused_with_env(&scratch, &env, &args, &["job.json", field, id, "digits"]);
        }
        assert!(!scratch.path("calls.log").exists(), "a Slurm command ran");
    }
}

/// A linear EXR of 8×4 pixels of `color`.
fn exr(scratch: &Scratch, name: &str, color: Vec3) {
    let mut film = Film::new(8, 4);
    film.color.fill(color);
    embray::output::write_exr(&film, &scratch.path(name)).unwrap();
}

#[test]
fn tonemap_and_heatmap_outputs_are_what_their_extension_says() {
    let scratch = Scratch::new();
    exr(&scratch, "in.exr", Vec3::splat(0.5));
    // PNG bytes under these names had exit 0.
    for out in ["t.exr", "t.EXR"] {
        refused_in(&scratch, &["tonemap", "in.exr", "-o", out], &[out, "names an EXR"]);
    }
    refused_in(&scratch, &["tonemap", "in.exr", "-o", "t.tif"], &["t.tif", "'.tif'"]);
    accepted_in(&scratch, &["tonemap", "in.exr", "-o", "t.jpg"]);
    assert!(std::fs::read(scratch.path("t.jpg")).unwrap().starts_with(&[0xFF, 0xD8, 0xFF]));
    accepted_in(&scratch, &["tonemap", "in.exr", "-o", "t.png"]);
    let heatmap = |out| ["compare", "t.png", "t.png", "--heatmap", out];
    refused_in(&scratch, &heatmap("h.exr"), &["--heatmap 'h.exr'", "names an EXR"]);
    refused_in(&scratch, &heatmap("h.tiff"), &["--heatmap 'h.tiff'", "'.tiff'"]);
    accepted_in(&scratch, &heatmap("h.jpeg"));
    assert!(std::fs::read(scratch.path("h.jpeg")).unwrap().starts_with(&[0xFF, 0xD8, 0xFF]));
}

/// The image is one tile: its parts are sample ranges.
const SPLIT: [&str; 4] = ["--split", "samples", "--spp", "2"];

/// Renders part `i` of 2 of `s.toml`, `p{i}.exr`, with `extra` options.
fn part(scratch: &Scratch, i: u32, extra: &[&str]) {
    let (part, out) = (format!("{i}/2"), format!("p{i}.exr"));
    let mut args = vec!["render", "s.toml", "--part", &part, "-o", &out, "-q"];
    args.extend(SPLIT);
    args.extend(extra);
    accepted_in(scratch, &args);
}

fn parts(scratch: &Scratch, extra: &[&str]) {
    part(scratch, 0, extra);
    part(scratch, 1, extra);
}

/// Replaces `from` by `to` (as long) in the part file's JSON metadata: no offset moves.
fn edit_part(scratch: &Scratch, name: &str, from: &str, to: &str) {
    assert_eq!(from.len(), to.len());
    let path = scratch.path(name);
    let mut bytes = std::fs::read(&path).unwrap();
    let at = bytes.windows(from.len()).position(|w| w == from.as_bytes()).expect(from);
    bytes[at..at + to.len()].copy_from_slice(to.as_bytes());
    std::fs::write(&path, bytes).unwrap();
}

#[test]
fn a_part_whose_tone_mapping_the_command_line_would_refuse_is_damaged() {
    for (to, problem) in [
        ("[0.00,1.0,1.0,2.2]", "the key must be > 0, not 0"),
        ("[0.18,1.0,1.0,0.0]", "the gamma must be > 0, not 0"),
        ("[0.18,-5 ,1.0,2.2]", "burn-out percentage must be in [0, 100), not -5"),
        ("[0.18,1.0,-7 ,2.2]", "the saturation must be >= 0, not -7"),
    ] {
        let scratch = Scratch::new();
        scratch.write("s.toml", scene(""));
        parts(&scratch, &[]);
        edit_part(&scratch, "p1.exr", "[0.18,1.0,1.0,2.2]", to);
        let args = ["merge", "p0.exr", "p1.exr", "-o", "m.exr", "--png", "m.png"];
        refused_in(&scratch, &args, &["part file 'p1.exr' is damaged", "PNG settings", problem]);
    }
}

#[test]
fn a_part_claiming_albedo_it_did_not_record_is_damaged() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    parts(&scratch, &[]);
    // Its albedo sums are zeros: the merged EXR would have had black albedo channels.
    edit_part(&scratch, "p0.exr", "\"aovs\":\"depth,normal\"", "\"aovs\":\"albedo,alpha\"");
    refused_in(
        &scratch,
        &["merge", "p0.exr", "p1.exr", "-o", "m.exr"],
        &["part file 'p0.exr' is damaged", "albedo", "first_hit_albedo: false", "albedo.R"],
    );
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    parts(&scratch, &["--aovs", "albedo"]);
    accepted_in(&scratch, &["merge", "p0.exr", "p1.exr", "-o", "m.exr"]);
}

#[test]
fn stats_and_phase_timing_change_neither_the_file_nor_what_merges_on_obvhs() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    let render = |out: &str, extra: &[&str]| {
        let mut args = vec!["render", "s.toml", "--backend", "obvhs", "-o", out, "-q"];
        args.extend(["--spp", "2"]);
        args.extend(extra);
        accepted_in(&scratch, &args);
    };
    render("a.exr", &[]);
    render("b.exr", &["--stats"]);
    render("c.exr", &["--time-phases"]);
    let read = |name: &str| std::fs::read(scratch.path(name)).unwrap();
    assert!(read("a.exr") == read("b.exr"), "--stats changed the EXR");
    assert!(read("a.exr") == read("c.exr"), "--time-phases changed the EXR");
    part(&scratch, 0, &["--backend", "obvhs"]);
    part(&scratch, 1, &["--backend", "obvhs", "--stats"]);
    accepted_in(&scratch, &["merge", "p0.exr", "p1.exr", "-o", "m.exr"]);
    assert!(read("m.exr") == read("a.exr"), "the merge is not the whole render's file");
}

#[test]
fn a_camera_number_that_is_one_cameras_name_and_anothers_position_is_refused() {
    let scratch = Scratch::new();
    scratch.write("s.xml", xml_scene(&["2.png", "1.png"], ""));
    std::fs::create_dir(scratch.path("out")).unwrap();
    for choice in ["1", "2"] {
        refused_in(
            &scratch,
            &["render", "s.xml", "--camera", choice, "--out-dir", "out"],
            &[&format!("--camera '{choice}' is ambiguous"), "'1.png'", "'2.png'", "s.xml"],
        );
    }
    accepted_in(&scratch, &["render", "s.xml", "--camera", "1.png", "--out-dir", "out", "-q"]);
    let written: Vec<_> = std::fs::read_dir(scratch.path("out")).unwrap().collect();
    assert_eq!(written.len(), 2, "one camera's EXR and PNG");
    assert!(scratch.path("out/1.exr").exists());
}

/// Built only with both backends: a build of one (`--no-default-features --features
/// obvhs`, as CI also tests) cannot write the other's part.
#[cfg(all(feature = "embree", feature = "obvhs"))]
#[test]
fn parts_of_both_backends_are_refused_in_words_not_debug_text() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    part(&scratch, 0, &["--backend", "obvhs"]);
    part(&scratch, 1, &["--backend", "embree"]);
    let run = refused_in(
        &scratch,
        &["merge", "p0.exr", "p1.exr", "-o", "m.exr"],
        &["does not belong with", "Embree library differs (", "not used"],
    );
    assert!(!run.stderr.contains("Some(") && !run.stderr.contains("None"), "{}", run.stderr);
}

#[test]
fn compare_against_a_black_reference_says_so_instead_of_a_huge_percentage() {
    let scratch = Scratch::new();
    exr(&scratch, "grey.exr", Vec3::splat(0.5));
    exr(&scratch, "black.exr", Vec3::ZERO);
    let run = accepted_in(&scratch, &["compare", "grey.exr", "black.exr"]);
    assert!(run.stdout.contains("no relative difference"), "{}", run.stdout);
    assert!(!run.stdout.contains("0000000000"), "{}", run.stdout);
    let run = accepted_in(&scratch, &["compare", "black.exr", "black.exr"]);
    assert!(run.stdout.contains("(largest difference 0.0000 %)"), "{}", run.stdout);
}

#[test]
fn compare_refuses_a_variance_or_spp_that_would_pass_any_image() {
    let scratch = Scratch::new();
    exr(&scratch, "ten.exr", Vec3::splat(10.0));
    exr(&scratch, "ref.exr", Vec3::splat(0.5));
    exr(&scratch, "var.exr", Vec3::splat(0.01));
    let judge = |variance: &'static str, spp: &'static str| {
        ["compare", "ten.exr", "ref.exr", "--variance", variance, "--spp", spp]
    };
    // Each passed an image 19 times its reference.
    refused_in(&scratch, &judge("var.exr", "0"), &["--spp is 0"]);
    let mut film = Film::new(8, 4);
    film.color.fill(Vec3::splat(0.01));
    for (name, bad, shown) in [
        ("inf.exr", Vec3::new(0.01, f32::INFINITY, 0.01), "G = inf"),
        ("nan.exr", Vec3::new(f32::NAN, 0.01, 0.01), "R = NaN"),
    ] {
        film.color[8 + 3] = bad;
        embray::output::write_exr(&film, &scratch.path(name)).unwrap();
        refused_in(&scratch, &judge(name, "4"), &[name, "pixel (3, 1)", shown, "finite number"]);
    }
    // A negative variance (Mitsuba's own references hold some) is raised to 1e-4, as
    // Mitsuba's test raises it: the image still fails.
    film.color[8 + 3] = Vec3::new(0.01, 0.01, -1.0);
    embray::output::write_exr(&film, &scratch.path("neg.exr")).unwrap();
    for variance in ["var.exr", "neg.exr"] {
        let run = Run::from(scratch.command(&judge(variance, "4")).output().unwrap());
        assert_eq!(run.code, Some(1), "{}", run.stderr);
        assert!(run.stdout.contains("FAIL"), "{}", run.stdout);
    }
}

/// `embray slurm SCENE` of two sample-range parts into `job/`, with fake Slurm commands
/// (squeue knows no task): returns the PATH that finds them.
fn slurm_job(scratch: &Scratch, out: &str) -> String {
    scratch.write("s.toml", scene(""));
    let path = fake_slurm(scratch, "");
    let args = ["slurm", "s.toml", "--parts", "2", "--split", "samples", "--out", out, "--no-wait"];
    let mut command = scratch.command(&args);
    let run = Run::from(command.args(["--", "--spp", "2"]).env("PATH", &path).output().unwrap());
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    path
}

#[test]
fn a_part_of_an_edited_scene_is_missing_to_slurm_status_and_resume() {
    let scratch = Scratch::new();
    let path = slurm_job(&scratch, "job");
    let task = |i: u32| {
        let (part, out) = (format!("{i}/2"), format!("job/parts/part-{i}-of-2.exr"));
        let args = ["render", "s.toml", "--part", &part, "-o", &out, "-q", "--spp", "2"];
        accepted_in(&scratch, &[&args[..], &["--split", "samples"]].concat());
    };
    task(0);
    // The scene is edited between the tasks: part 0 is of another render, which the merge
    // refuses, so `resume` must render it again (it resubmitted only the merge).
    scratch.write("s.toml", scene("").replace("[0.5, 0.5, 0.5]", "[0.1, 0.1, 0.1]"));
    task(1);
    let status = |command: &str| {
        let args = ["slurm", command, "job", "--no-wait"];
        let args = if command == "status" { &args[..3] } else { &args[..] };
        Run::from(scratch.command(args).env("PATH", &path).output().unwrap())
    };
    let run = status("status");
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(
        run.stdout.contains("part 0/2  missing: its file is of another render: scene contents")
    );
    assert!(run.stdout.contains("part 1/2  done"), "{}", run.stdout);
    assert!(run.stdout.contains("1 of 2 parts done; missing: 0/2."), "{}", run.stdout);
    let run = status("resume");
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let calls = std::fs::read_to_string(scratch.path("calls.log")).unwrap();
    assert!(calls.lines().last().is_some_and(|l| l.contains("--dependency=afterok:1")), "{calls}");
    assert!(calls.contains("--array=0 "), "part 0 is rendered again:\n{calls}");
    assert!(!scratch.path("job/parts/part-0-of-2.exr").exists(), "the stale part is removed");
    assert!(scratch.path("job/parts/part-1-of-2.exr").exists());
}

#[test]
fn a_job_folder_named_like_a_command_is_never_run_by_the_batch_scripts() {
    let scratch = Scratch::new();
    let folder = "job $(touch PWNED) `touch PWNED2` 'q\" %x";
    slurm_job(&scratch, folder);
    // A node that cannot see the job file prints the paths; the folder's name was run there.
    std::fs::remove_file(scratch.path(&format!("{folder}/job.json"))).unwrap();
    for script in ["parts.sbatch", "merge.sbatch"] {
        let text = std::fs::read_to_string(scratch.path(&format!("{folder}/{script}"))).unwrap();
        assert!(text.contains("#SBATCH --output=\""), "{text}");
        let output = std::process::Command::new("bash")
            .arg(scratch.path(&format!("{folder}/{script}")))
            .current_dir(scratch.path(""))
            .env("SLURM_ARRAY_TASK_ID", "0")
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains(&format!("{folder}/job.json' or '")), "{stderr}");
        assert!(!scratch.path("PWNED").exists() && !scratch.path("PWNED2").exists(), "{text}");
    }
    let args = ["slurm", "s.toml", "--parts", "2", "--split", "samples", "--out", "a\ntouch PWNED"];
    let mut command = scratch.command(&args);
    command.args(["--no-wait", "--", "--spp", "2"]).env("PATH", fake_slurm(&scratch, ""));
    let run = Run::from(command.output().unwrap());
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    run.assert_says(&["the job folder", "a\\ntouch PWNED", "line break"]);
    assert!(!scratch.path("a\ntouch PWNED").exists(), "no folder is made");
}
