//! Which effects a scene calls for, decided once when the render scene is built. Everything
//! downstream reads this instead of re-deriving it, so a scene pays (random dimensions,
//! motion BVHs, extra rays) only for what it uses.

use std::fmt;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Effects {
    /// The camera has an aperture: lens samples are drawn.
    pub depth_of_field: bool,
    /// Some object moves: rays carry times and moving objects get motion BVHs.
    pub motion_blur: bool,
    /// Some geometry emits: emitters are sampled (soft shadows).
    pub area_lights: bool,
    /// Point or directional lights: one shadow ray each, no sampling.
    pub delta_lights: bool,
    /// Rough conductors or mirrors.
    pub glossy: bool,
    /// Perfect mirrors or glass.
    pub specular: bool,
    /// Dielectrics (refraction).
    pub refraction: bool,
    pub textures: bool,
    /// Some prototype is placed by a transform (shared meshes, moving objects, ellipsoids).
    pub instancing: bool,
    /// Meshes with per-vertex normals.
    pub smooth_shading: bool,
}

impl Effects {
    /// Everything on: used to measure what the effects machinery costs a static scene.
    pub fn all() -> Self {
        Effects {
            depth_of_field: true,
            motion_blur: true,
            area_lights: true,
            delta_lights: true,
            glossy: true,
            specular: true,
            refraction: true,
            textures: true,
            instancing: true,
            smooth_shading: true,
        }
    }

    pub fn names(&self) -> Vec<&'static str> {
        let all = [
            (self.depth_of_field, "depth of field"),
            (self.motion_blur, "motion blur"),
            (self.area_lights, "area lights"),
            (self.delta_lights, "point/directional lights"),
            (self.glossy, "glossy"),
            (self.specular, "mirror/glass"),
            (self.refraction, "refraction"),
            (self.textures, "textures"),
            (self.instancing, "instancing"),
            (self.smooth_shading, "smooth shading"),
        ];
        all.iter().filter(|(on, _)| *on).map(|(_, name)| *name).collect()
    }
}

impl fmt::Display for Effects {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names = self.names();
        if names.is_empty() { write!(f, "none") } else { write!(f, "{}", names.join(", ")) }
    }
}
