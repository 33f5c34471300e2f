//! What each subcommand does.

use crate::cli::{Cli, Command, RenderArgs, load_scene};
use anyhow::Result;
use embray::output::{write_exr, write_png};
use embray::render::{RenderOutput, render};
use embray::scene::{LightDesc, SceneDesc, ShapeDesc};
use embray::stats::RenderStats;

pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Render(args) => render_command(&args),
        Command::Info { scene } => {
            let scene = load_scene(scene.as_deref())?;
            print!("{}", describe(&scene));
            Ok(())
        }
    }
}

fn render_command(args: &RenderArgs) -> Result<()> {
    let scene = load_scene(args.scene.as_deref())?;
    let options = args.to_options(&scene)?;
    let output = render(&scene, &options)?;
    write_exr(&output.film, &args.output)?;
    let png = args.png_path();
    write_png(&output.film, &png, args.tonemap, args.exposure)?;
    if !args.quiet {
        eprintln!("{}", summary(&output, &options, args, &png));
    }
    if args.stats {
        print!("{}", stats_table(&output.stats));
    }
    Ok(())
}

fn summary(
    output: &RenderOutput,
    options: &embray::render::RenderOptions,
    args: &RenderArgs,
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
        args.output.display(),
        png.display(),
    )
}

/// Counters as a plain-text table.
pub fn stats_table(stats: &RenderStats) -> String {
    let mut out = String::from("ray kind   rays          hits\n");
    for (name, c) in [("camera", stats.camera), ("shadow", stats.shadow), ("indirect", stats.indirect)] {
        out += &format!("{name:<10} {:<13} {}\n", c.rays, c.hits);
    }
    out += &format!("node visits      {}\nprimitive tests  {}\n", stats.traversal.node_visits, stats.traversal.prim_tests);
    out
}

fn describe(scene: &SceneDesc) -> String {
    let c = &scene.camera;
    let mut out = format!("scene: {}\n", scene.source.display());
    out += &format!(
        "camera: {}x{}, vfov {}°, lookfrom {:?}, lookat {:?}, aperture {}\n",
        c.width, c.height, c.vfov_deg, c.lookfrom.to_array(), c.lookat.to_array(), c.aperture
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
    let emissive = scene.objects.iter()
        .filter(|o| scene.materials[o.material as usize].emission.max_element() > 0.0)
        .count();
    out += &format!("objects: {meshes} meshes ({triangles} triangles), {spheres} spheres\n");
    out += &format!("materials: {}\nlights: {points} point, {emissive} emissive objects\n", scene.materials.len());
    out
}
