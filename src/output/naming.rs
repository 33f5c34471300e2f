//! Where a CENG795 camera's images go: its `ImageName` in the output folder (a PNG, or a
//! JPEG or EXR where the name says so) and the other image beside it, unless the command
//! line names the files.

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
    // `Path` forgets a trailing '/' or '.', and an extension alone is no name: `sub/`,
    // `sub/.` and `sub/.png` would give hidden files `sub/.exr`, `sub/..exr`, `sub/.png.exr`.
    let last = image_name.rsplit('/').next().unwrap_or_default();
    let extension_alone = last
        .strip_prefix('.')
        .is_some_and(|e| ["png", "jpg", "jpeg", "exr"].contains(&e.to_ascii_lowercase().as_str()));
    if last.is_empty() || last == "." {
        return Some(format!("ImageName '{shown}' ends in a folder, not a file name"));
    }
    if extension_alone {
        return Some(format!("ImageName '{shown}' has no name before its extension"));
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

/// The image name without its extension where that names an image embray writes (`.png`,
/// `.jpg`, `.jpeg`, `.exr`: the EXR and the display image take the stem, a JPEG display
/// image where the name says so); a name with any other extension, or a dot inside it
/// (`img_1.5`), is kept whole and both images are named after it (`img_1.5.exr`,
/// `img_1.5.png`), not cut at its last dot.
fn image_stem(image_name: &Path) -> PathBuf {
    let known = image_name
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| ["png", "jpg", "jpeg", "exr"].contains(&e.to_ascii_lowercase().as_str()));
    if known { image_name.with_extension("") } else { image_name.to_path_buf() }
}

/// The display image an image name asks for: its own name where it is a PNG or JPEG name,
/// else the stem's PNG.
fn display_image(image_name: &Path) -> PathBuf {
    let extension = image_name.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("png" | "jpg" | "jpeg") => image_name.to_path_buf(),
        _ => with_suffix(&image_stem(image_name), "png"),
    }
}

/// `path` with `.extension` added (never replacing a part of its name).
fn with_suffix(path: &Path, extension: &str) -> PathBuf {
    let mut name = path.as_os_str().to_owned();
    name.push(".");
    name.push(extension);
    PathBuf::from(name)
}

/// What two image names must differ in to give different files: the path without `.`
/// components and without the extension of an image embray writes (`image_stem`).
pub fn image_name_key(image_name: &str) -> PathBuf {
    let path: PathBuf =
        Path::new(image_name).components().filter(|c| !matches!(c, Component::CurDir)).collect();
    image_stem(&path)
}

/// The (EXR, PNG) paths of the camera whose `ImageName` is `image_name`. `exr` and `png` are
/// the files named on the command line, if any (a named EXR alone puts the PNG beside it).
pub fn camera_outputs(
    image_name: &str,
    out_dir: &Path,
    exr: Option<&Path>,
    png: Option<&Path>,
) -> (PathBuf, PathBuf) {
    let named = out_dir.join(display_image(Path::new(image_name)));
    let stem = out_dir.join(image_stem(Path::new(image_name)));
    let exr_path = exr.map(Path::to_path_buf).unwrap_or_else(|| with_suffix(&stem, "exr"));
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
        for hidden in ["sub/", "sub/.", ".PNG", "sub/.exr", "/"] {
            assert!(image_name_problem(hidden).is_some(), "{hidden}");
        }
        assert!(image_name_problem("sub/.x").is_none());
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
        // A JPEG name gives a JPEG; an EXR name the EXR; other names are kept whole.
        for (name, exr, display) in [
            ("c.JPG", "out/c.exr", "out/c.JPG"),
            ("d.exr", "out/d.exr", "out/d.png"),
            ("img_1.5", "out/img_1.5.exr", "out/img_1.5.png"),
            ("e.tga", "out/e.tga.exr", "out/e.tga.png"),
            ("f", "out/f.exr", "out/f.png"),
        ] {
            let expected = (PathBuf::from(exr), PathBuf::from(display));
            assert_eq!(camera_outputs(name, dir, None, None), expected, "{name}");
        }
        assert_ne!(image_name_key("img_1.5"), image_name_key("img_1.6"));
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
