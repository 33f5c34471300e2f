//! The scenes shipped with embray, embedded in the binary so an installed `embray` finds
//! them wherever it runs. They live under a virtual folder, [`ROOT`]: a path below it is read
//! from the binary (by the scene loaders, through `input_file`), so bundled scenes
//! name their meshes by relative paths exactly as files on disk do.

use std::path::{Path, PathBuf};

/// The virtual folder the bundled files appear in.
pub const ROOT: &str = "(built in)";

/// Every bundled file, by its path below [`ROOT`].
static FILES: &[(&str, &[u8])] = &[
    ("scenes/city_block.toml", include_bytes!("../scenes/city_block.toml")),
    ("scenes/cornell.toml", include_bytes!("../scenes/cornell.toml")),
    ("scenes/dof_spheres.toml", include_bytes!("../scenes/dof_spheres.toml")),
    ("scenes/glass.toml", include_bytes!("../scenes/glass.toml")),
    ("scenes/glossy_plates.toml", include_bytes!("../scenes/glossy_plates.toml")),
    ("scenes/instances.toml", include_bytes!("../scenes/instances.toml")),
    ("scenes/models/city_block.obj", include_bytes!("../scenes/models/city_block.obj")),
    ("scenes/moving_boxes.toml", include_bytes!("../scenes/moving_boxes.toml")),
    ("scenes/precision/degenerate.toml", include_bytes!("../scenes/precision/degenerate.toml")),
    (
        "scenes/precision/grazing_plane.toml",
        include_bytes!("../scenes/precision/grazing_plane.toml"),
    ),
    ("scenes/precision/inside_mesh.toml", include_bytes!("../scenes/precision/inside_mesh.toml")),
    (
        "scenes/precision/models/degenerate.obj",
        include_bytes!("../scenes/precision/models/degenerate.obj"),
    ),
    ("scenes/precision/scales.toml", include_bytes!("../scenes/precision/scales.toml")),
    ("scenes/precision/thin_walls.toml", include_bytes!("../scenes/precision/thin_walls.toml")),
    ("scenes/precision/tiny_in_huge.toml", include_bytes!("../scenes/precision/tiny_in_huge.toml")),
    ("scenes/precision/up_parallel.toml", include_bytes!("../scenes/precision/up_parallel.toml")),
    ("scenes/textured_instances.toml", include_bytes!("../scenes/textured_instances.toml")),
];

/// The path of bundled file `name` (e.g. `scenes/cornell.toml`).
pub fn path(name: &str) -> PathBuf {
    Path::new(ROOT).join(name)
}

/// The default scene: the Cornell box.
pub fn default_scene() -> PathBuf {
    path("scenes/cornell.toml")
}

/// The contents of `path` if it names a bundled file.
pub fn file(path: &Path) -> Option<&'static [u8]> {
    let name = path.strip_prefix(ROOT).ok()?;
    FILES.iter().find(|(n, _)| Path::new(n) == name).map(|(_, bytes)| *bytes)
}

/// The bundled scenes (`.toml`) directly in `folder` (e.g. `scenes/precision`), sorted.
pub fn scenes_in(folder: &str) -> Vec<PathBuf> {
    FILES
        .iter()
        .map(|(name, _)| Path::new(*name))
        .filter(|name| name.parent() == Some(Path::new(folder)))
        .filter(|name| name.extension().is_some_and(|e| e == "toml"))
        .map(|name| Path::new(ROOT).join(name))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bundled_files_are_found_by_path_and_listed_by_folder() {
        let cornell = default_scene();
        assert!(
            file(&cornell).is_some_and(|bytes| bytes.starts_with(b"#") || bytes.starts_with(b"["))
        );
        assert!(file(Path::new("scenes/cornell.toml")).is_none(), "only paths below ROOT");
        let precision = scenes_in("scenes/precision");
        assert!(precision.len() >= 7 && precision.windows(2).all(|w| w[0] < w[1]));
        assert!(precision.iter().all(|p| file(p).is_some()));
        assert!(file(&path("scenes/models/city_block.obj")).is_some());
    }
}
