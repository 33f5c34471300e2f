//! `embray info`: what a scene contains and which effects it calls for. The effects are the
//! scene compiler's own decision, so the scene is compiled (in `cameraworld`) to report them.

use crate::compile::{EffectsMode, to_render_scene};
use crate::render_scene::{Geometry, Placement, RenderScene};
use crate::render_space::RenderSpace;
use crate::scene::{Environment, LightDesc, SceneDesc, ShapeDesc, Specular};
use crate::shading::material::Material;
use std::fmt;

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
    out += &format!(
        "render: {} spp, max depth {}, {} sampler (the default; `render --sampler` chooses), \
         seed {}{}\n",
        scene.settings.spp,
        scene.settings.max_depth,
        crate::sampling::SamplerKind::default(),
        scene.settings.seed,
        if scene.settings.jitter { "" } else { ", samples at stratum centres (not jittered)" }
    );
    let (mut meshes, mut triangles, mut spheres, mut grids) = (0, 0, 0, 0);
    for object in &scene.objects {
        match &object.shape {
            ShapeDesc::Mesh(m) => {
                meshes += 1;
                triangles += m.indices.len();
            }
            ShapeDesc::Sphere { .. } => spheres += 1,
            ShapeDesc::SdfGrid(_) => grids += 1,
        }
    }
    let emissive = scene
        .objects
        .iter()
        .filter(|o| scene.materials[o.material as usize].emission.max_element() > 0.0)
        .count();
    out += &format!("objects: {meshes} meshes ({triangles} triangles), {spheres} spheres");
    if grids > 0 {
        out += &format!(", {grids} signed distance grids");
    }
    out += "\n";
    out += &format!("materials: {}\n", scene.materials.len());
    // Each kind once, in the order the scene first names it.
    let mut counts: Vec<(&str, usize)> = Vec::new();
    for light in &scene.lights {
        match counts.iter_mut().find(|(label, _)| *label == light.label()) {
            Some((_, n)) => *n += 1,
            None => counts.push((light.label(), 1)),
        }
    }
    let mut lights: Vec<String> = counts.iter().map(|(label, n)| format!("{n} {label}")).collect();
    lights.push(format!("{emissive} emissive objects"));
    out += &format!("lights: {}\n", lights.join(", "));
    for light in &scene.lights {
        if let LightDesc::Environment(Environment { map, .. }) = light {
            out += &match map {
                crate::scene::EnvironmentMap::Constant(c) => {
                    format!("environment: constant {} {} {}\n", c.x, c.y, c.z)
                }
                crate::scene::EnvironmentMap::Image(image) => format!(
                    "environment: {} ({} × {})\n",
                    image.file.display(),
                    image.width,
                    image.height
                ),
            };
        }
    }
    let moving = scene.objects.iter().filter(|o| o.is_moving()).count();
    out += &format!("moving objects: {moving}\n");
    // A render's default: a worker thread per core.
    let threads = rayon::current_num_threads();
    let needed = |bytes_per_triangle| {
        crate::scene::budget::memory_needed(scene, bytes_per_triangle, threads)
    };
    let mib = |backend: crate::accel::BackendKind| {
        needed(backend.bytes_per_triangle()).bytes as f64 / 1048576.0
    };
    out += &format!(
        "memory estimate: {:.1} MiB on embree, {:.1} MiB on obvhs ({})\n",
        mib(crate::accel::BackendKind::Embree),
        mib(crate::accel::BackendKind::Obvhs),
        needed(0)
    );
    // Compiling builds the scene (a grid's voxels, baked meshes): not when the estimate of
    // that alone (no BVH) is more memory than there is.
    let compiled = crate::scene::budget::check_memory(scene, 0, threads)
        .map_err(|e| e.to_string())
        .and_then(|()| {
            to_render_scene(scene, RenderSpace::Cameraworld, EffectsMode::Auto)
                .map_err(|e| e.to_string())
        });
    match compiled {
        Ok(render_scene) => {
            out += &format!(
                "prototypes: {}, instances: {}\neffects: {}\n",
                render_scene.prototypes.len(),
                render_scene.instances.len(),
                FeatureList(features(&render_scene))
            );
        }
        Err(e) => out += &format!("effects: not prepared: {e}\n"),
    }
    out
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
        (used(&|m| m.principled.is_some()), "principled BSDF"),
        (used(&|m| m.texture.is_some()), "textures"),
        (has_instancing(scene), "instancing"),
        (
            scene.prototypes.iter().any(|p| matches!(p.geometry, Geometry::SdfGrid(_))),
            "signed distance grids",
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

/// Whether any instance is placed by a transform as instancing is. A grid is always placed
/// by one (its prototype is in grid units), so a grid counts only when its prototype is
/// shared by several instances.
fn has_instancing(scene: &RenderScene) -> bool {
    let mut uses = vec![0u32; scene.prototypes.len()];
    for instance in &scene.instances {
        if let Some(n) = uses.get_mut(instance.prototype as usize) {
            *n = n.saturating_add(1);
        }
    }
    scene.instances.iter().any(|i| {
        let prototype = i.prototype as usize;
        let grid = matches!(
            scene.prototypes.get(prototype).map(|p| &p.geometry),
            Some(Geometry::SdfGrid(_))
        );
        !matches!(i.placement, Placement::Baked { .. }) && (!grid || uses[prototype] > 1)
    })
}

/// `features` joined for one line of text ("none" when empty).
pub struct FeatureList(pub Vec<&'static str>);

impl fmt::Display for FeatureList {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() { write!(f, "none") } else { write!(f, "{}", self.0.join(", ")) }
    }
}
