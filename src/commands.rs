//! What each subcommand does.

use crate::cli::{
    AccuracyArgs, BenchArgs, BenchCommand, Cli, Command, CompareArgs, ConvertArgs, EffectsArgs,
    RenderArgs, SpeedArgs, load_scene,
};
use anyhow::{Context, Result, bail};
use embray::output::{write_exr, write_png};
use embray::render::{RenderOutput, render};
use embray::scene::ceng795;
use embray::scene::{LightDesc, SceneDesc, ShapeDesc};
use embray::stats::RenderStats;
use std::path::{Path, PathBuf};

pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Render(args) => render_command(&args),
        Command::Bench(BenchCommand::Spaces(args)) => bench_spaces(&args),
        Command::Bench(BenchCommand::Accuracy(args)) => bench_accuracy(&args),
        Command::Bench(BenchCommand::Speed(args)) => bench_speed(&args),
        Command::Bench(BenchCommand::Effects(args)) => bench_effects(&args),
        Command::Info { scene: Some(path) } if ceng795::is_ceng795_path(&path) => {
            for camera in ceng795::load(&path)? {
                println!("camera: {}", camera.image_name);
                print!("{}", describe(&camera.scene));
            }
            Ok(())
        }
        Command::Info { scene } => {
            let scene = load_scene(scene.as_deref())?;
            print!("{}", describe(&scene));
            Ok(())
        }
        Command::Convert(args) => convert_command(&args),
        Command::Compare(args) => compare_command(&args),
    }
}

fn render_command(args: &RenderArgs) -> Result<()> {
    if let Some(path) = args.scene.as_deref().filter(|p| ceng795::is_ceng795_path(p)) {
        return render_ceng795(args, path);
    }
    let scene = load_scene(args.scene.as_deref())?;
    render_one(args, &scene, &args.output_path(), &args.png_path())
}

/// Renders every camera of a CENG795 file: each to its ImageName (PNG) in --out-dir and an
/// EXR of the same stem, or, for a one-camera file, to -o/--png when given.
fn render_ceng795(args: &RenderArgs, path: &Path) -> Result<()> {
    let cameras = ceng795::load(path)?;
    if cameras.len() > 1 {
        for (flag, given) in [
            ("-o", args.output.is_some()),
            ("--png", args.png.is_some()),
            ("--stats-json", args.stats_json.is_some()),
        ] {
            if given {
                bail!(
                    "{flag} names one file, but '{}' has {} cameras: their images are written \
                     to --out-dir under their ImageName",
                    path.display(),
                    cameras.len()
                );
            }
        }
    }
    for camera in &cameras {
        args.to_options(&camera.scene)?;
    }
    if args.output.is_none() {
        std::fs::create_dir_all(&args.out_dir)
            .with_context(|| format!("cannot create '{}'", args.out_dir.display()))?;
    }
    for camera in &cameras {
        let named = args.out_dir.join(&camera.image_name).with_extension("png");
        let exr = args.output.clone().unwrap_or_else(|| named.with_extension("exr"));
        let png = match (&args.png, &args.output) {
            (Some(png), _) => png.clone(),
            (None, Some(_)) => args.png_path(),
            (None, None) => named,
        };
        render_one(args, &camera.scene, &exr, &png)?;
    }
    Ok(())
}

/// Renders `scene`; writes the EXR and the PNG, prints the summary and the statistics.
fn render_one(args: &RenderArgs, scene: &SceneDesc, exr: &Path, png: &Path) -> Result<()> {
    let options = args.to_options(scene)?;
    let output = render(scene, &options)?;
    write_exr(&output.film, exr)?;
    let curve = args.tonemap.resolve(scene.settings.integrator);
    write_png(&output.film, png, curve, args.exposure)?;
    if !args.quiet {
        eprintln!("{}", summary(&output, &options, exr, png));
    }
    if args.stats {
        print!("{}", stats_table(&output.stats, output.observes));
    }
    if let Some(path) = &args.stats_json {
        let json = serde_json::json!({
            "backend": output.backend,
            "render_space": options.render_space.name(),
            "spp": options.spp,
            "build_quality": options.accel.build_quality,
            "compact": options.accel.compact,
            "batch": options.accel.batch,
            "render_seconds": output.render_time.as_secs_f64(),
            "build_seconds": output.build_time.as_secs_f64(),
            "observes": output.observes,
            "stats": output.stats,
        });
        std::fs::write(path, serde_json::to_string_pretty(&json)? + "\n")
            .with_context(|| format!("cannot write '{}'", path.display()))?;
    }
    Ok(())
}

/// A scene shipped in `scenes/`: found from the working directory (a checkout), else from
/// the source tree this binary was built from.
fn bundled_scene(name: &str) -> std::path::PathBuf {
    let local = std::path::Path::new("scenes").join(name);
    if local.exists() {
        local
    } else {
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes").join(name)
    }
}

/// The checkout the bundled scenes live in (working directory first, then the source tree).
fn bundled_root() -> std::path::PathBuf {
    if std::path::Path::new("scenes/cornell.toml").exists() {
        ".".into()
    } else {
        env!("CARGO_MANIFEST_DIR").into()
    }
}

fn bench_effects(args: &EffectsArgs) -> Result<()> {
    use embray::bench::effects_cost;
    anyhow::ensure!(args.spp > 0, "--spp must be at least 1");
    let scene = load_scene(args.scene.as_deref())?;
    let mut base = embray::render::RenderOptions::for_scene(&scene);
    base.spp = args.spp;
    let rows =
        effects_cost::measure(&scene, &base, &embray::accel::BackendKind::compiled(), args.runs)?;
    print!("{}", effects_cost::markdown(&rows));
    Ok(())
}

fn bench_speed(args: &SpeedArgs) -> Result<()> {
    use embray::bench::{procedural, speed};
    anyhow::ensure!(args.spp > 0 && args.size > 0 && args.large > 0, "sizes must be positive");
    const NAMES: [&str; 4] = ["cornell", "city_block", "instances", "large"];
    if let Some(unknown) = args.only.iter().find(|n| !NAMES.contains(&n.as_str())) {
        bail!("--only: unknown scene '{unknown}' (expected some of {})", NAMES.join(", "));
    }
    let wanted = |name: &str| args.only.is_empty() || args.only.iter().any(|n| n == name);
    let root = bundled_root();
    let mut scenes = Vec::new();
    for name in NAMES[..3].iter().filter(|n| wanted(n)) {
        let path = root.join("scenes").join(format!("{name}.toml"));
        if path.exists() {
            scenes.push((name.to_string(), embray::scene::load(&path)?));
        }
    }
    if wanted("large") {
        let large = format!("sphere_{}k", args.large / 1000);
        scenes.push((large, procedural::displaced_sphere_scene(args.large, 256, 256)));
    }
    let mut rows = Vec::new();
    let bar = indicatif::ProgressBar::new(scenes.len() as u64);
    for (name, mut scene) in scenes {
        let longest = scene.camera.width.max(scene.camera.height);
        if longest > args.size {
            let scale = args.size as f64 / longest as f64;
            scene.camera.width = ((scene.camera.width as f64 * scale) as u32).max(1);
            scene.camera.height = ((scene.camera.height as f64 * scale) as u32).max(1);
        }
        bar.set_message(name.clone());
        let backends = embray::accel::BackendKind::compiled();
        rows.extend(speed::measure_scene(
            &name,
            &scene,
            &backends,
            args.spp,
            args.runs,
            args.build_quality,
        )?);
        bar.inc(1);
    }
    bar.finish_and_clear();
    print!("{}", speed::markdown(&rows));
    Ok(())
}

fn bench_accuracy(args: &AccuracyArgs) -> Result<()> {
    use embray::bench::{accuracy, table};
    anyhow::ensure!(args.spp > 0, "--spp must be at least 1");
    anyhow::ensure!(args.max_size > 0, "--max-size must be at least 1");
    anyhow::ensure!(!args.offsets.is_empty(), "--offsets needs at least one value");
    anyhow::ensure!(args.offsets.iter().all(|o| o.is_finite()), "--offsets must be finite numbers");
    let root = bundled_root();
    let scenes =
        if args.scenes.is_empty() { accuracy::default_scenes(&root) } else { args.scenes.clone() };
    let grazing = root.join("scenes/precision/grazing_plane.toml");
    let thin = root.join("scenes/precision/thin_walls.toml");
    let options = accuracy::AccuracyOptions {
        scenes,
        offsets: args.offsets.clone(),
        backends: embray::accel::BackendKind::compiled(),
        runs: args.runs,
        spp: args.spp,
        max_size: args.max_size,
        threads: args.threads,
        out_dir: args.out.clone(),
        spawn_scenes: (grazing.exists() && thin.exists()).then_some((grazing, thin)),
        spawn_methods: args.spawn.clone(),
    };
    let total = options.scenes.len() * options.offsets.len() * 3 * options.backends.len();
    let bar = indicatif::ProgressBar::new(total as u64 + 1);
    let report = accuracy::run(&options, |message| {
        bar.set_message(message.to_string());
        bar.inc(1);
    })?;
    bar.finish_and_clear();
    print!("{}", table::markdown(&report.rows));
    if !report.spawn_rows.is_empty() {
        println!();
        print!("{}", embray::bench::spawn_report::markdown(&report.spawn_rows));
    }
    for warning in &report.warnings {
        eprintln!("warning: {warning}");
    }
    for file in &report.files {
        eprintln!("wrote {}", file.display());
    }
    Ok(())
}

fn bench_spaces(args: &BenchArgs) -> Result<()> {
    use embray::bench::{grid, table};
    use embray::render_space::RenderSpace;
    let path = args.scene.clone().unwrap_or_else(|| bundled_scene("city_block.toml"));
    let scene = load_scene(Some(&path))?;
    let mut options = embray::render::RenderOptions::for_scene(&scene);
    if let Some(spp) = args.spp {
        anyhow::ensure!(spp > 0, "--spp must be at least 1");
        options.spp = spp;
    }
    options.threads = args.threads;
    anyhow::ensure!(args.offsets.iter().all(|o| o.is_finite()), "--offsets must be finite numbers");
    let backends = embray::accel::BackendKind::compiled();
    let spaces = vec![RenderSpace::World, RenderSpace::Camera, RenderSpace::Cameraworld];
    let grid = grid::Grid { backends, spaces, offsets: args.offsets.clone(), runs: args.runs };
    let total = (grid.backends.len() * grid.spaces.len() * grid.offsets.len()) as u64;
    let bar = indicatif::ProgressBar::new(total);
    let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let rows = grid::measure(&name, &scene, &options, &grid, |row| {
        bar.set_message(format!("{} {} {:e}", row.backend, row.render_space, row.offset));
        bar.inc(1);
    })?;
    bar.finish_and_clear();
    print!("{}", table::markdown(&rows));
    if let Some(csv) = &args.csv {
        std::fs::write(csv, table::csv(&rows))
            .with_context(|| format!("cannot write '{}'", csv.display()))?;
    }
    Ok(())
}

fn convert_command(args: &ConvertArgs) -> Result<()> {
    if !ceng795::is_ceng795_path(&args.input) {
        bail!("convert reads CENG795 scenes (.xml); '{}' is not one", args.input.display());
    }
    let cameras = ceng795::load(&args.input)?;
    let stem = args.output.file_stem().map(|s| s.to_string_lossy().into_owned());
    let Some(stem) = stem.filter(|s| !s.is_empty()) else {
        bail!("-o '{}' is not a file name", args.output.display());
    };
    let dir = args.output.parent().map(Path::to_path_buf).unwrap_or_default();
    let mesh_dir = dir.join(format!("{stem}_meshes"));
    let mut writer = embray::scene::toml_writer::TomlWriter::new(mesh_dir);
    for camera in &cameras {
        let path: PathBuf = if cameras.len() == 1 {
            args.output.clone()
        } else {
            let image = Path::new(&camera.image_name).file_stem().unwrap_or_default();
            dir.join(format!("{stem}_{}.toml", image.to_string_lossy()))
        };
        let note = format!(
            "Converted by embray from '{}' (camera '{}').",
            args.input.display(),
            camera.image_name
        );
        writer.write(&camera.scene, &path, &note)?;
        eprintln!("wrote {}", path.display());
    }
    let meshes = writer.mesh_files();
    if let Some(first) = meshes.first() {
        let folder = first.parent().unwrap_or(Path::new("."));
        eprintln!("wrote {} mesh file(s) in {}", meshes.len(), folder.display());
    }
    Ok(())
}

fn compare_command(args: &CompareArgs) -> Result<()> {
    use embray::compare::{compare_images, read_rgb, write_heatmap};
    let c = compare_images(&read_rgb(&args.a)?, &read_rgb(&args.b)?, args.tolerance)?;
    println!(
        "{}x{}: mean abs error {:.4}/255, max {}/255; {:.4} % of pixels off by more than {}/255 \
         ({:.4} % within)",
        c.width,
        c.height,
        c.mean_abs_error,
        c.max_abs_error,
        100.0 * c.fraction_over,
        c.tolerance,
        100.0 * c.fraction_within()
    );
    if let Some(path) = &args.heatmap {
        write_heatmap(&c, path)?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

fn summary(
    output: &RenderOutput,
    options: &embray::render::RenderOptions,
    exr: &std::path::Path,
    png: &std::path::Path,
) -> String {
    let seconds = output.render_time.as_secs_f64();
    let rays = output.stats.total_rays();
    format!(
        "{}x{} @ {} spp on {} ({}): build {:.1} ms, render {:.3} s, {} rays, {:.2} Mrays/s → {}, {}",
        output.film.width,
        output.film.height,
        options.spp,
        output.backend,
        options.render_space.name(),
        output.build_time.as_secs_f64() * 1e3,
        seconds,
        rays,
        rays as f64 / seconds.max(1e-9) / 1e6,
        exr.display(),
        png.display(),
    )
}

/// Counters as a plain-text table.
pub fn stats_table(stats: &RenderStats, observes: embray::accel::Observes) -> String {
    let mut out = String::from("ray kind   rays          hits\n");
    for (name, c) in
        [("camera", stats.camera), ("shadow", stats.shadow), ("indirect", stats.indirect)]
    {
        out += &format!("{name:<10} {:<13} {}\n", c.rays, c.hits);
    }
    let shown = |value: u64, observed: bool| {
        if observed { value.to_string() } else { "not observable".to_string() }
    };
    out += &format!(
        "node visits      {}\nprimitive tests  {}\n",
        shown(stats.traversal.node_visits, observes.node_visits),
        shown(stats.traversal.prim_tests, observes.prim_tests)
    );
    out
}

fn describe(scene: &SceneDesc) -> String {
    let c = &scene.camera;
    let mut out = format!("scene: {}\n", scene.source.display());
    out += &format!(
        "camera: {}x{}, vfov {}°, lookfrom {:?}, lookat {:?}, aperture {}\n",
        c.width,
        c.height,
        c.vfov_deg,
        c.lookfrom.to_array(),
        c.lookat.to_array(),
        c.aperture
    );
    out += &format!("render: {} spp, max depth {}\n", scene.settings.spp, scene.settings.max_depth);
    let (mut meshes, mut triangles, mut spheres) = (0, 0, 0);
    for object in &scene.objects {
        match &object.shape {
            ShapeDesc::Mesh(m) => {
                meshes += 1;
                triangles += m.indices.len();
            }
            ShapeDesc::Sphere { .. } => spheres += 1,
        }
    }
    let points = scene.lights.iter().filter(|l| matches!(l, LightDesc::Point { .. })).count();
    let directional =
        scene.lights.iter().filter(|l| matches!(l, LightDesc::Directional { .. })).count();
    let emissive = scene
        .objects
        .iter()
        .filter(|o| scene.materials[o.material as usize].emission.max_element() > 0.0)
        .count();
    out += &format!("objects: {meshes} meshes ({triangles} triangles), {spheres} spheres\n");
    out += &format!(
        "materials: {}\nlights: {points} point, {directional} directional, {emissive} emissive objects\n",
        scene.materials.len()
    );
    let area = scene.lights.iter().filter(|l| matches!(l, LightDesc::Area { .. })).count();
    if area > 0 {
        out += &format!("area lights (invisible squares): {area}\n");
    }
    let moving = scene.objects.iter().filter(|o| o.is_moving()).count();
    out += &format!("moving objects: {moving}\n");
    match embray::render_space::to_render_scene(
        scene,
        embray::render_space::RenderSpace::Cameraworld,
        embray::render_space::EffectsMode::Auto,
    ) {
        Ok(render_scene) => {
            out += &format!(
                "prototypes: {}, instances: {}\neffects: {}\n",
                render_scene.prototypes.len(),
                render_scene.instances.len(),
                render_scene.effects
            );
        }
        Err(e) => out += &format!("effects: cannot prepare the scene: {e}\n"),
    }
    out
}
