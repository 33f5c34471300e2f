//! `embray convert`: a CENG795 XML scene to native TOML (and OBJ meshes).

use anyhow::{Result, bail};
use clap::Args;
use embray::output::{OutputPlan, OutputSet};
use embray::scene::ceng795;
use embray::scene::toml_writer::TomlWriter;
use std::path::{Path, PathBuf};

use super::console::note;

#[derive(Args, Debug)]
pub struct ConvertArgs {
    /// The CENG795 or Mitsuba 3 scene (.xml).
    pub input: PathBuf,
    /// The TOML file to write.
    #[arg(short, long)]
    pub output: PathBuf,
    /// A Mitsuba scene's parameter (its `<default>`, `$name`), as Mitsuba's `-D`.
    #[arg(short = 'D', long = "define", value_name = "NAME=VALUE", value_parser = super::render_args::parse_define)]
    pub defines: Vec<(String, String)>,
}

pub fn run(args: &ConvertArgs) -> Result<()> {
    if !ceng795::is_ceng795_path(&args.input) {
        bail!(
            "convert reads XML scenes (CENG795 or Mitsuba 3); '{}' is not one",
            args.input.display()
        );
    }
    let mut plan = OutputPlan::new();
    plan.input("the input scene", &args.input);
    // Checked before the scene is read: a wrong -o costs nothing.
    plan.output("-o", &args.output, true)?;
    let cameras = embray::scene::xml::load(&args.input, &args.defines)?;
    let stem = args.output.file_stem().map(|s| s.to_string_lossy().into_owned());
    let Some(stem) = stem.filter(|s| !s.is_empty()) else {
        bail!("-o '{}' is not a file name", args.output.display());
    };
    let dir = args.output.parent().map(Path::to_path_buf).unwrap_or_default();
    let mesh_dir = dir.join(format!("{stem}_meshes"));
    let mut writer = TomlWriter::new(mesh_dir);
    // Every TOML and OBJ text is produced first, then all are checked and committed together.
    let mut texts = Vec::new();
    for camera in &cameras {
        let path: PathBuf = if cameras.len() == 1 {
            args.output.clone()
        } else {
            let image = Path::new(&camera.image_name).file_stem().unwrap_or_default();
            dir.join(format!("{stem}_{}.toml", image.to_string_lossy()))
        };
        let provenance = format!(
            "Converted by embray from '{}' (camera '{}').",
            args.input.display(),
            camera.image_name
        );
        let text = writer.toml(&camera.scene, &path, &provenance)?;
        texts.push(("a TOML file".to_owned(), path, text));
    }
    for (mesh, text) in writer.take_pending_meshes() {
        texts.push(("an OBJ file".to_owned(), mesh, text));
    }
    let mut plan = OutputPlan::new();
    plan.input("the input scene", &args.input);
    plan.inputs_read(&embray::input_file::files_read());
    let mut files = OutputSet::new();
    for (what, path, text) in &texts {
        let target = plan.output(what, path, true)?;
        files.write(&target, |w| w.write_all(text.as_bytes()))?;
    }
    files.commit()?;
    for (_, path, _) in texts.iter().filter(|(what, ..)| what == "a TOML file") {
        note(format!("wrote {}", path.display()));
    }
    let meshes = writer.mesh_files();
    if let Some(first) = meshes.first() {
        let folder = first.parent().unwrap_or(Path::new("."));
        note(format!("wrote {} mesh file(s) in {}", meshes.len(), folder.display()));
    }
    Ok(())
}
