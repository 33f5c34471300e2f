//! Where a CENG795 camera's images go: its `ImageName` (PNG) in the output folder and an EXR
//! of the same stem, unless the command line names the files.

use std::path::{Component, Path, PathBuf};

/// Why a scene's `ImageName` cannot be used, if it cannot: it must stay inside the output
/// folder (a scene file must not write anywhere else), so it may not be absolute or climb
/// with `..`, and it must name a file.
pub fn image_name_problem(image_name: &str) -> Option<String> {
    let path = Path::new(image_name);
    let shown = crate::excerpt::excerpt(image_name);
    for component in path.components() {
        match component {
            Component::Normal(_) | Component::CurDir => {}
            Component::ParentDir => {
                return Some(format!(
                    "ImageName '{shown}' climbs out of the output folder with '..'; image \
                     names are relative to --out-dir and stay inside it"
                ));
            }
            Component::RootDir | Component::Prefix(_) => {
                return Some(format!(
                    "ImageName '{shown}' is an absolute path; image names are relative to \
                     --out-dir and stay inside it"
                ));
            }
        }
    }
    match path.file_name() {
        None => Some(format!("ImageName '{shown}' does not name a file")),
        Some(name) if name.len() > super::NAME_MAX - 4 => Some(format!(
            "ImageName '{shown}' is longer than {} bytes, too long for a file name",
            super::NAME_MAX - 4
        )),
        Some(_) => None,
    }
}

/// What two image names must differ in to give different files: the path without `.`
/// components and without its extension (the EXR and PNG replace it).
pub fn image_name_key(image_name: &str) -> PathBuf {
    let path: PathBuf =
        Path::new(image_name).components().filter(|c| !matches!(c, Component::CurDir)).collect();
    path.with_extension("")
}

/// The (EXR, PNG) paths of the camera whose `ImageName` is `image_name`. `exr` and `png` are
/// the files named on the command line, if any (a named EXR alone puts the PNG beside it).
pub fn camera_outputs(
    image_name: &str,
    out_dir: &Path,
    exr: Option<&Path>,
    png: Option<&Path>,
) -> (PathBuf, PathBuf) {
    let named = out_dir.join(image_name).with_extension("png");
    let exr_path = exr.map(Path::to_path_buf).unwrap_or_else(|| named.with_extension("exr"));
    let png_path = match (png, exr) {
        (Some(png), _) => png.to_path_buf(),
        (None, Some(exr)) => exr.with_extension("png"),
        (None, None) => named,
    };
    (exr_path, png_path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn image_names_stay_inside_the_output_folder() {
        assert!(image_name_problem("a/b.png").is_none());
        assert!(image_name_problem("../../x.png").unwrap().contains("'..'"));
        assert!(image_name_problem("/abs/x.png").unwrap().contains("absolute"));
        assert!(image_name_problem("a/..").is_some());
        assert_eq!(image_name_key("./a.png"), image_name_key("a.jpg"));
        assert_ne!(image_name_key("a.png"), image_name_key("b/a.png"));
    }

    #[test]
    fn image_name_decides_unless_files_are_named() {
        let dir = Path::new("out");
        assert_eq!(
            camera_outputs("a/b.png", dir, None, None),
            (PathBuf::from("out/a/b.exr"), PathBuf::from("out/a/b.png"))
        );
        assert_eq!(
            camera_outputs("b.png", dir, Some(Path::new("x.exr")), None),
            (PathBuf::from("x.exr"), PathBuf::from("x.png"))
        );
        assert_eq!(
            camera_outputs("b.png", dir, None, Some(Path::new("y.png"))),
            (PathBuf::from("out/b.exr"), PathBuf::from("y.png"))
        );
    }
}
