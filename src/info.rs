//! `embray info`: what a scene contains and which effects it calls for. The effects are the
//! scene compiler's own decision, so the scene is compiled (in `cameraworld`) to report them.

use crate::compile::effects::{FeatureList, features};
use crate::compile::{EffectsMode, to_render_scene};
use crate::render_space::RenderSpace;
use crate::scene::{LightDesc, SceneDesc, ShapeDesc};

/// A few lines describing `scene`.
pub fn describe(scene: &SceneDesc) -> String {
    let c = &scene.camera;
    let mut out = format!("scene: {}\n", scene.source.display());
    out += &format!(
        "camera: {}x{}, vfov {}°, lookfrom {:?}, lookat {:?}, aperture {}\n",
        c.width,
        c.height,
        c.vfov_deg,
        c.lookfrom.to_array(),
        c.lookat.to_array(),
        c.aperture
    );
    out += &format!("render: {} spp, max depth {}\n", scene.settings.spp, scene.settings.max_depth);
    let (mut meshes, mut triangles, mut spheres) = (0, 0, 0);
    for object in &scene.objects {
        match &object.shape {
            ShapeDesc::Mesh(m) => {
                meshes += 1;
                triangles += m.indices.len();
            }
            ShapeDesc::Sphere { .. } => spheres += 1,
        }
    }
    let points = scene.lights.iter().filter(|l| matches!(l, LightDesc::Point { .. })).count();
    let directional =
        scene.lights.iter().filter(|l| matches!(l, LightDesc::Directional { .. })).count();
    let emissive = scene
        .objects
        .iter()
        .filter(|o| scene.materials[o.material as usize].emission.max_element() > 0.0)
        .count();
    out += &format!("objects: {meshes} meshes ({triangles} triangles), {spheres} spheres\n");
    out += &format!(
        "materials: {}\nlights: {points} point, {directional} directional, {emissive} emissive objects\n",
        scene.materials.len()
    );
    let area = scene.lights.iter().filter(|l| matches!(l, LightDesc::Area { .. })).count();
    if area > 0 {
        out += &format!("area lights (invisible squares): {area}\n");
    }
    let moving = scene.objects.iter().filter(|o| o.is_moving()).count();
    out += &format!("moving objects: {moving}\n");
    match to_render_scene(scene, RenderSpace::Cameraworld, EffectsMode::Auto) {
        Ok(render_scene) => {
            out += &format!(
                "prototypes: {}, instances: {}\neffects: {}\n",
                render_scene.prototypes.len(),
                render_scene.instances.len(),
                FeatureList(features(&render_scene))
            );
        }
        Err(e) => out += &format!("effects: cannot prepare the scene: {e}\n"),
    }
    out
}
