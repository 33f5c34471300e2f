//! Counts, memory and inputs with documented limits: refused with the limit and the option
//! or field, before anything large is allocated or anything blocks.

use crate::harness::{
    Run, Scratch, refused_cases, refused_in, refused_under_memory, scene, with_mesh,
};

refused_cases! {
    spp_zero: ["s.toml" => scene("")], ["render", "s.toml", "--spp", "0"] => ["--spp is 0", "between 1 and"];
    spp_absurd: ["s.toml" => scene("")], ["render", "s.toml", "--spp", "2000000"] => ["--spp is 2000000", "1048576"];
    light_samples_absurd: ["s.toml" => scene("")], ["render", "s.toml", "--light-samples", "100000"] => ["--light-samples is 100000", "65536"];
    threads_a_hundred_thousand: ["s.toml" => scene("")], ["render", "s.toml", "--threads", "100000"] => ["--threads is 100000", "1024"];
    threads_zero: ["s.toml" => scene("")], ["render", "s.toml", "--threads", "0"] => ["--threads is 0"];
    max_depth_absurd: ["s.toml" => scene("")], ["render", "s.toml", "--max-depth", "1000000"] => ["--max-depth is 1000000", "100000"];
    pixels_times_spp_too_many: ["s.toml" => scene("").replace("[8, 8]", "[4096, 4096]")], ["render", "s.toml", "--spp", "8192"]
        => ["pixels × spp", "68719476736"];
    bench_runs_zero: [], ["bench", "speed", "--runs", "0"] => ["--runs is 0", "between 1 and 1000"];
    bench_spaces_threads_zero: [], ["bench", "spaces", "--threads", "0"] => ["--threads is 0"];
    bench_speed_large_zero: [], ["bench", "speed", "--large", "0"] => ["--large must be at least 1"];
    bench_speed_spp_zero: [], ["bench", "speed", "--spp", "0"] => ["--spp must be at least 1"];
    bench_effects_runs_zero: [], ["bench", "effects", "--runs", "0"] => ["--runs is 0"];
    scene_on_dev_zero: [], ["render", "/dev/zero"] => ["/dev/zero", "a device, not a regular file"];
}

/// The estimate is checked against the machine's memory; a budget makes the case the same
/// on any machine (16384² needs about 75 GiB, more than the 2-core reference machine has).
#[test]
fn a_render_needing_more_memory_than_there_is_is_refused() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene("").replace("[8, 8]", "[8192, 8192]"));
    let args = ["render", "s.toml", "--threads", "1"];
    refused_under_memory(
        &scratch,
        &args,
        1 << 30,
        &["s.toml", "18.8 GiB of memory", "8192x8192", "only 1.0 GiB", "lower camera.resolution"],
    );
}

/// A symbolic link in the scratch folder to a special file.
fn link(scratch: &Scratch, name: &str, to: &str) {
    std::os::unix::fs::symlink(to, scratch.path(name)).unwrap();
}

#[test]
fn a_scene_that_is_a_fifo_is_refused_without_blocking() {
    let scratch = Scratch::new();
    let status = std::process::Command::new("mkfifo").arg(scratch.path("s.toml")).status().unwrap();
    assert!(status.success());
    refused_in(&scratch, &["render", "s.toml"], &["s.toml", "a FIFO, not a regular file"]);
}

#[test]
fn an_obj_on_dev_zero_is_refused() {
    let scratch = Scratch::new();
    scratch.write("s.toml", with_mesh("m.obj"));
    link(&scratch, "m.obj", "/dev/zero");
    refused_in(&scratch, &["render", "s.toml"], &["m.obj", "a device", "objects[1].file"]);
}

#[test]
fn a_ply_on_dev_zero_is_refused() {
    let scratch = Scratch::new();
    scratch.write("s.toml", with_mesh("m.ply"));
    link(&scratch, "m.ply", "/dev/zero");
    refused_in(&scratch, &["render", "s.toml"], &["m.ply", "a device"]);
}

#[test]
fn an_mtl_on_dev_zero_is_refused() {
    let scratch = Scratch::new();
    scratch.write("s.toml", with_mesh("m.obj"));
    scratch.write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    link(&scratch, "m.mtl", "/dev/zero");
    refused_in(&scratch, &["render", "s.toml"], &["m.obj", "m.mtl", "a device"]);
}

#[test]
fn an_image_to_compare_on_a_fifo_is_refused() {
    let scratch = Scratch::new();
    let status = std::process::Command::new("mkfifo").arg(scratch.path("a.png")).status().unwrap();
    assert!(status.success());
    image::RgbImage::new(2, 2).save(scratch.path("b.png")).unwrap();
    refused_in(&scratch, &["compare", "a.png", "b.png"], &["a.png", "a FIFO"]);
}

#[test]
fn a_convergence_reference_on_a_fifo_is_refused() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    let status =
        std::process::Command::new("mkfifo").arg(scratch.path("ref.exr")).status().unwrap();
    assert!(status.success());
    let args = ["bench", "convergence", "s.toml", "--reference", "ref.exr", "--spps", "1"];
    refused_in(&scratch, &args, &["ref.exr", "a FIFO"]);
}

/// Texture images count in the estimate (they did not: a scene of many large textures was
/// accepted under any budget and died loading them or rendering).
#[test]
fn texture_texels_count_in_the_memory_estimate() {
    let scratch = Scratch::new();
    image::RgbImage::new(1024, 1024).save(scratch.path("t.png")).unwrap();
    let textured = scene("").replace(
        "albedo = [0.5, 0.5, 0.5]",
        "albedo = [0.5, 0.5, 0.5]\ntexture = { type = \"image\", file = \"t.png\" }",
    );
    scratch.write("s.toml", textured);
    // 24 MiB fixed, 20 MiB of texels: refused under a 40 MiB budget (one thread, which
    // adds nothing, on any machine).
    let expected = [
        "s.toml",
        "needs about 44.0 MiB",
        "1048576 texture texels",
        "only 40.0 MiB",
        "size of the textures",
    ];
    refused_under_memory(&scratch, &["render", "s.toml", "--threads", "1"], 40 << 20, &expected);
}

/// Worker threads count in the estimate (they did not: each holds its stack and its batch of
/// paths, `limits::BYTES_PER_THREAD`, so a thousand threads hold 300 MiB more than one).
#[test]
fn worker_threads_count_in_the_memory_estimate() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    let render = |threads| ["render", "s.toml", "--threads", threads, "-q"];
    // 100 MiB: 24 MiB and 64 pixels fit; 1023 more threads add 320 MiB.
    let budget = 100 << 20;
    let expected =
        ["s.toml", "needs about 343.7 MiB", "1024 threads", "only 100.0 MiB", "--threads"];
    refused_under_memory(&scratch, &render("1024"), budget, &expected);
    let mut command = scratch.command(&render("1"));
    let run = Run::from(command.env("EMBRAY_MAX_MEMORY", budget.to_string()).output().unwrap());
    assert_eq!(run.code, Some(0), "{}", run.stderr);
}

/// Every placement of an emissive mesh samples its own emitters (a sampler's record per
/// triangle, `limits::BYTES_PER_EMITTER`): 400 placements of a 10,000-triangle lamp are four
/// million of them, about a GiB the estimate did not count (it counted the shared mesh once).
#[test]
fn emitters_of_every_placement_count_in_the_memory_estimate() {
    let scratch = Scratch::new();
    let faces = "f 1 2 3\n".repeat(10_000);
    scratch.write("lamp.obj", format!("v 0 0 0\nv 1 0 0\nv 0 1 0\n{faces}"));
    scratch.write(
        "s.toml",
        "[camera]\nlookfrom = [0, 0, 5]\nlookat = [0, 0, 0]\nvfov = 40\nresolution = [8, 8]\n\
         [materials.lamp]\nemission = [1, 1, 1]\n\
         [[objects]]\ntype = \"mesh\"\nfile = \"lamp.obj\"\nmaterial = \"lamp\"\n\
         repeat = { count = [20, 20, 1], spacing = [2, 2, 0] }\n",
    );
    // 24 MiB fixed and a few for the mesh and placements: 200 MiB would pass without them.
    let expected = ["s.toml", "4000000 emitting primitives", "only 200.0 MiB"];
    refused_under_memory(&scratch, &["render", "s.toml", "--threads", "1"], 200 << 20, &expected);
}
