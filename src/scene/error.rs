//! `SceneError`: everything that can go wrong while loading a scene. Each message names the
//! file (scene, OBJ or MTL), the field and value, and ends with the line when it is known.

use crate::excerpt::{excerpt, shorten_message};

/// A message part that may quote input (another library's message, a token, an element's
/// attributes): lines beyond 300 characters are cut.
fn brief(text: &str) -> String {
    shorten_message(text, 300)
}
use std::fmt;
use std::path::{Path, PathBuf};

/// A line number in the scene (or OBJ/MTL) file, when known. Displays as ` (line N)` or as
/// nothing, so that messages read the same either way.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Line(pub Option<usize>);

impl fmt::Display for Line {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Some(line) => write!(f, " (line {line})"),
            None => Ok(()),
        }
    }
}

#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The scene file is missing or unreadable.
    #[error("scene file '{}': {error}", .path.display())]
    Read { path: PathBuf, error: std::io::Error },

    /// Reading the file would need more memory than the process may use.
    #[error(
        "{}: reading it needs about {} of memory ({what}), but only {} are available",
        .file.display(), crate::scene::budget::size(*.needed), crate::scene::budget::size(*.available)
    )]
    ReadMemory { file: PathBuf, needed: u64, what: String, available: u64 },

    /// TOML syntax error, unknown key or wrong value type. `message` is toml's own report,
    /// which gives the line and column and quotes the offending text.
    #[error("{}: {message}", .file.display())]
    Toml { file: PathBuf, message: String },

    /// A NaN or infinite float (TOML accepts `nan` and `inf`).
    #[error("{}: {field} is {}{line}", .file.display(), excerpt(.value))]
    NonFinite { file: PathBuf, field: String, value: String, line: Line },

    /// A number outside its allowed range.
    #[error("{}: {field} is {}, but must be {requirement}{line}", .file.display(), excerpt(.value))]
    OutOfRange { file: PathBuf, field: String, value: String, requirement: String, line: Line },

    /// A field that the object, light or material type needs is absent.
    #[error("{}: {item} is missing the field `{field}`{line}", .file.display())]
    MissingField { file: PathBuf, item: String, field: String, line: Line },

    /// A field that exists in the format but means nothing for this object, light or
    /// material type.
    #[error("{}: {item} does not take the field `{field}` (it takes: {allowed}){line}", .file.display())]
    FieldNotAllowed { file: PathBuf, item: String, field: String, allowed: String, line: Line },

    /// lookfrom == lookat, or a zero up vector.
    #[error("{}: degenerate camera: {reason}{line}", .file.display())]
    DegenerateCamera { file: PathBuf, reason: String, line: Line },

    #[error(
        "{}: {field} '{}' is not defined; defined: {}{line}",
        .file.display(), excerpt(.name), excerpt(.defined)
    )]
    UnknownMaterial { file: PathBuf, field: String, name: String, defined: String, line: Line },

    /// A singular transform entry, a matrix whose last row is not 0 0 0 1, a zero rotation
    /// axis, or a composed transform that is singular or overflows.
    #[error("{}: {field}: {}{line}", .file.display(), brief(.problem))]
    Transform { file: PathBuf, field: String, problem: String, line: Line },

    /// A quad without area or a box with min >= max.
    #[error("{}: {item}: {}{line}", .file.display(), brief(.problem))]
    DegenerateShape { file: PathBuf, item: String, problem: String, line: Line },

    /// The OBJ file named by a mesh object is missing or unreadable.
    #[error(
        "OBJ file '{}': {error}; named by {item}.file in '{}'{line}",
        .obj.display(), .scene.display()
    )]
    ObjRead { obj: PathBuf, scene: PathBuf, item: String, error: std::io::Error, line: Line },

    /// The OBJ or MTL data is invalid: parse error (tobj's message), out-of-range vertex
    /// index, non-finite coordinate, no triangles, bad MTL colour. `file` is the OBJ file, or
    /// the MTL file for a bad material; `line` is in that file.
    #[error("{}: {}{line}; named by {item} in '{}'", .file.display(), brief(.problem), .scene.display())]
    ObjData { file: PathBuf, scene: PathBuf, item: String, problem: String, line: Line },

    /// The PLY file named by a mesh object or light is missing or unreadable.
    #[error(
        "PLY file '{}': {error}; named by {item}.file in '{}'{line}",
        .ply.display(), .scene.display()
    )]
    PlyRead { ply: PathBuf, scene: PathBuf, item: String, error: std::io::Error, line: Line },

    /// The PLY data is invalid: bad header, unsupported property type, truncated binary
    /// data, out-of-range index, non-finite number, no faces. `ply_line` is the line in an
    /// ASCII PLY file (or its header).
    #[error(
        "PLY file '{}'{ply_line}: {}; named by {item}.file in '{}'{line}",
        .ply.display(), brief(.problem), .scene.display()
    )]
    PlyData {
        /// Boxed paths, so that this variant, the largest, keeps `SceneError` small.
        ply: Box<Path>,
        ply_line: Line,
        scene: Box<Path>,
        item: String,
        problem: String,
        /// The line of the scene that names the file.
        line: Line,
    },

    /// An image a texture names is missing, unreadable, not a PNG, JPEG or BMP, corrupt or too
    /// large.
    #[error(
        "image file '{}': {}; named by {item} in '{}'{line}",
        .image.display(), brief(.problem), .scene.display()
    )]
    Image { image: PathBuf, scene: PathBuf, item: String, problem: String, line: Line },

    /// Two fields that exclude each other (`aperture` and `f_number`; a conductor's
    /// `preset` and `eta`/`k`).
    #[error("{}: {item} takes `{first}` or `{second}`, not both{line}", .file.display())]
    Conflict { file: PathBuf, item: String, first: String, second: String, line: Line },

    /// An XML scene (CENG795 or Mitsuba 3): malformed XML, an unsupported element, a value
    /// that cannot be read or a reference to something undefined; also a `-D` parameter no
    /// scene can use (`element` is then the `-D`). `element` is the element's path below the
    /// root (`<Objects > Mesh id="3" > Faces>`) or its tag.
    #[error("{}: {}: {}{line}", .file.display(), brief(.element), brief(.problem))]
    Xml { file: PathBuf, element: String, problem: String, line: Line },

    /// A transform list entry without exactly one of scale, rotate, translate, matrix.
    #[error("{}: {field} must have exactly one of the keys scale, rotate, translate, matrix; it has {found}{line}", .file.display())]
    TransformEntry { file: PathBuf, field: String, found: String, line: Line },
}

impl SceneError {
    /// A kind's parameter error, in the scene `file`.
    pub fn from_param(file: &std::path::Path, error: crate::params::ParamError) -> Self {
        use crate::params::ParamError;
        let file = file.to_path_buf();
        match error {
            ParamError::OutOfRange { field, value, requirement, line } => {
                SceneError::OutOfRange { file, field, value, requirement, line: Line(line) }
            }
            ParamError::Missing { item, field, line } => {
                SceneError::MissingField { file, item, field, line: Line(line) }
            }
            ParamError::NotAllowed { item, field, allowed, line } => {
                SceneError::FieldNotAllowed { file, item, field, allowed, line: Line(line) }
            }
            ParamError::Conflict { item, first, second, line } => {
                SceneError::Conflict { file, item, first, second, line: Line(line) }
            }
            ParamError::Reader(error) => match error.downcast::<SceneError>() {
                Ok(error) => *error,
                Err(other) => SceneError::Toml { file, message: other.to_string() },
            },
        }
    }
}
