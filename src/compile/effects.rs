//! Which effects a scene calls for, decided once when the render scene is built. The
//! renderer reads this instead of re-deriving it, so a scene pays (random dimensions, motion
//! BVHs) only for what it uses.

/// The effects that change how samples are drawn and what the backends build.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Effects {
    /// The camera has an aperture: lens samples are drawn.
    pub depth_of_field: bool,
    /// Some object moves: rays carry times and moving objects get motion BVHs.
    pub motion_blur: bool,
}

impl Effects {
    /// Everything on: used to measure what the effects machinery costs a static scene.
    pub fn all() -> Self {
        Effects { depth_of_field: true, motion_blur: true }
    }
}
