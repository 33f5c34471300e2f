//! Where an image is named (the file, the scene and the texture that names it), for its
//! messages: errors, and the memory its decoding needs checked before it is spent.

use crate::scene::error::{Line, SceneError};
use std::path::{Path, PathBuf};

/// Where an image is named, for messages.
pub struct ImageRef<'a> {
    pub image: PathBuf,
    pub scene: &'a Path,
    /// The texture that names it (`materials.wood.texture.file`, `<TextureMap id="2">`).
    pub item: String,
    pub line: Line,
}

impl ImageRef<'_> {
    pub(crate) fn error(&self, problem: impl Into<String>) -> SceneError {
        SceneError::Image {
            image: self.image.clone(),
            scene: self.scene.to_path_buf(),
            item: self.item.clone(),
            problem: problem.into(),
            line: self.line,
        }
    }

    /// Refuses to decode the `width` × `height` image, at `per_texel` bytes a texel while
    /// it is decoded, when it and the images held already would not fit in memory.
    pub(crate) fn check_room(
        &self,
        width: u64,
        height: u64,
        per_texel: u64,
    ) -> Result<(), SceneError> {
        let size = crate::scene::budget::size;
        let decoding = (width * height).saturating_mul(per_texel);
        super::image_cache::check_room(decoding).map_err(|(held, available)| {
            let beside = match held {
                0 => String::new(),
                held => format!(", beside {} of images read already,", size(held)),
            };
            self.error(format!(
                "decoding its {width} × {height} texels needs about {} of memory{beside} but \
                 only {} are available",
                size(decoding),
                size(available)
            ))
        })
    }
}
