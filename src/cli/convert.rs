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
    let images: Vec<&str> = cameras.iter().map(|c| c.image_name.as_str()).collect();
    let paths = match images.len() {
        1 => vec![args.output.clone()],
        _ => camera_toml_names(&stem, &images).into_iter().map(|name| dir.join(name)).collect(),
    };
    for (k, (camera, path)) in cameras.iter().zip(paths).enumerate() {
        let provenance = format!(
            "Converted by embray from '{}' (camera '{}').",
            args.input.display(),
            camera.image_name
        );
        let text = writer.toml(&camera.scene, &path, &provenance)?;
        let what = format!("the TOML file of camera {} ('{}')", k + 1, camera.image_name);
        texts.push((what, path, text));
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
    for (_, path, _) in texts.iter().filter(|(what, ..)| what.starts_with("the TOML file")) {
        note(format!("wrote {}", path.display()));
    }
    let meshes = writer.mesh_files();
    if let Some(first) = meshes.first() {
        let folder = first.parent().unwrap_or(Path::new("."));
        note(format!("wrote {} mesh file(s) in {}", meshes.len(), folder.display()));
    }
    Ok(())
}

/// The TOML file names of a file's cameras, rendering `images`: `{stem}_{image stem}.toml`,
/// and where two images share a stem (`a.png`, `sub/a.png`, `a.exr`), each of those with
/// its camera's number too, so that no camera's scene overwrites another's.
fn camera_toml_names(stem: &str, images: &[&str]) -> Vec<String> {
    let image_stem = |image: &str| {
        Path::new(image).file_stem().unwrap_or_default().to_string_lossy().into_owned()
    };
    let stems: Vec<String> = images.iter().map(|image| image_stem(image)).collect();
    stems
        .iter()
        .enumerate()
        .map(|(k, image)| match stems.iter().filter(|other| *other == image).count() {
            1 => format!("{stem}_{image}.toml"),
            _ => format!("{stem}_{image}_camera{}.toml", k + 1),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::camera_toml_names;

    #[test]
    fn cameras_whose_images_share_a_stem_get_their_numbers() {
        let names = camera_toml_names("o", &["a.png", "b.png", "sub/a.png", "a.exr"]);
        assert_eq!(names, ["o_a_camera1.toml", "o_b.toml", "o_a_camera3.toml", "o_a_camera4.toml"]);
        assert_eq!(camera_toml_names("o", &["x.png", "y.png"]), ["o_x.toml", "o_y.toml"]);
    }
}
