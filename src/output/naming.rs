//! Where a CENG795 camera's images go: its `ImageName` (PNG) in the output folder and an EXR
//! of the same stem, unless the command line names the files.

use std::path::{Path, PathBuf};

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
