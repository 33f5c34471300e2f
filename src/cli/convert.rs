//! `embray convert`: a CENG795 XML scene to native TOML (and OBJ meshes).

use anyhow::{Result, bail};
use clap::Args;
use embray::scene::ceng795;
use embray::scene::toml_writer::TomlWriter;
use std::path::{Path, PathBuf};

use super::console::note;

#[derive(Args, Debug)]
pub struct ConvertArgs {
    /// The CENG795 scene (.xml).
    pub input: PathBuf,
    /// The TOML file to write.
    #[arg(short, long)]
    pub output: PathBuf,
}

pub fn run(args: &ConvertArgs) -> Result<()> {
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
    let mut writer = TomlWriter::new(mesh_dir);
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
        writer.write(&camera.scene, &path, &provenance)?;
        note(format!("wrote {}", path.display()));
    }
    let meshes = writer.mesh_files();
    if let Some(first) = meshes.first() {
        let folder = first.parent().unwrap_or(Path::new("."));
        note(format!("wrote {} mesh file(s) in {}", meshes.len(), folder.display()));
    }
    Ok(())
}
