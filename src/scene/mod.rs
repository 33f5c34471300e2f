//! Scene files → `SceneDesc`.
pub mod desc;
pub use desc::*;
