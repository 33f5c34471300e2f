//! Which effects a scene calls for, decided once when the render scene is built. The
//! renderer reads this instead of re-deriving it, so a scene pays (random dimensions, motion
//! BVHs) only for what it uses. [`features`] lists, for `embray info`, everything the scene
//! simulates.

use crate::camera::Camera;
use crate::render_scene::Instance;
use crate::render_scene::{Geometry, Placement, RenderScene};
use crate::scene::Specular;
use crate::shading::material::Material;
use std::fmt;

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

    /// What the camera and the placements call for.
    pub fn decide(camera: &Camera, instances: &[Instance]) -> Self {
        Effects {
            depth_of_field: camera.has_lens(),
            motion_blur: instances.iter().any(|i| i.placement.is_moving()),
        }
    }
}

/// Everything `scene` simulates, by name: its effects, then its lights, materials and
/// geometry features.
pub fn features(scene: &RenderScene) -> Vec<&'static str> {
    let used = |f: &dyn Fn(&Material) -> bool| {
        scene.instances.iter().any(|i| f(&scene.materials[i.material as usize]))
    };
    let all = [
        (scene.effects.depth_of_field, "depth of field"),
        (scene.effects.motion_blur, "motion blur"),
        (scene.lights.has_emitters(), "area lights"),
        (scene.lights.has_delta_lights(), "point/directional lights"),
        (used(&|m| m.specular != Specular::None && !m.specular_is_delta()), "glossy"),
        (used(&|m| m.specular != Specular::None && m.specular_is_delta()), "mirror/glass"),
        (used(&|m| m.is_dielectric()), "refraction"),
        (used(&|m| m.texture.is_some()), "textures"),
        (
            scene.instances.iter().any(|i| !matches!(i.placement, Placement::Baked { .. })),
            "instancing",
        ),
        (
            scene
                .prototypes
                .iter()
                .any(|p| matches!(&p.geometry, Geometry::Triangles(m) if m.normals.is_some())),
            "smooth shading",
        ),
    ];
    all.iter().filter(|(on, _)| *on).map(|(_, name)| *name).collect()
}

/// `features` joined for one line of text ("none" when empty).
pub struct FeatureList(pub Vec<&'static str>);

impl fmt::Display for FeatureList {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() { write!(f, "none") } else { write!(f, "{}", self.0.join(", ")) }
    }
}
