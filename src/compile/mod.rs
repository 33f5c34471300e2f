//! The scene compiler: a world-space `SceneDesc` (f64) into the render-space `RenderScene`
//! (f32) the backends build, composing every `render_from_object` in f64 first. Split by
//! concept: placements and instancing, lights, the camera, and the effects decision.

mod camera;
pub mod effects;
mod lights;
mod placement;

use crate::camera::Camera;
use crate::render_scene::{Geometry, Instance, Placement, Prototype, RenderScene};
use crate::render_space::{CameraTransform, RenderSpace};
use crate::sampling::filter::FilterSampler;
use crate::scene::SceneDesc;
use crate::shading::material::Material;
use crate::shading::texture::Texture;
use effects::Effects;
use glam::{Affine3A, DAffine3, Vec3};

#[derive(Debug, thiserror::Error)]
pub enum CompileError {
    #[error("{0}: transform is singular or not finite")]
    SingularTransform(String),
    #[error("{0}: geometry does not fit in f32 render space (a coordinate overflows or is NaN)")]
    NotRepresentable(String),
    /// An object that cannot move as asked (`transform::motion_problem`).
    #[error("{0}: {1}")]
    Motion(String, String),
    #[error("{0}: the signed distance grid has no voxel the surface passes through")]
    EmptySdfGrid(String),
}

/// Whether effects are decided by the scene or all forced on.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EffectsMode {
    /// Simulate only what the scene calls for.
    #[default]
    Auto,
    /// Sample every dimension and give every object a motion BVH, to measure what the
    /// effects machinery costs a scene that does not need it.
    ForceAll,
}

/// Converts a world-space scene description into the render-space scene the backends build.
pub fn to_render_scene(
    desc: &SceneDesc,
    space: RenderSpace,
    mode: EffectsMode,
) -> Result<RenderScene, CompileError> {
    let camera = &desc.camera;
    let camera_transform = CameraTransform::new(space, camera.lookfrom, camera.lookat, camera.up);
    let render_from_world = camera_transform.render_from_world;
    let mut placer =
        placement::Placer::new(&desc.objects, render_from_world, mode == EffectsMode::ForceAll);
    for object in &desc.objects {
        placer.place(object)?;
    }
    let placement::Placer { prototypes, instances, .. } = placer;
    let mut coatings = crate::shading::coating::CoatingTables::default();
    let materials: Vec<Material> =
        desc.materials.iter().map(|m| Material::from_desc_sharing(m, &mut coatings)).collect();
    let lights = lights::compile_lights(
        &desc.lights,
        &render_from_world,
        &prototypes,
        &instances,
        &materials,
    );
    let camera = camera::place_camera(&desc.camera, &camera_transform);
    let effects = match mode {
        EffectsMode::ForceAll => Effects::all(),
        EffectsMode::Auto => Effects {
            depth_of_field: camera.has_lens(),
            motion_blur: instances.iter().any(|i| i.placement.is_moving()),
        },
    };
    let settings = &desc.settings;
    let pixel_filter =
        FilterSampler::new(settings.filter, camera.width, camera.height, settings.filter_edges);
    Ok(RenderScene {
        camera,
        prototypes,
        instances,
        materials,
        lights,
        background: desc.settings.background,
        backdrop: desc.settings.background_texture.as_ref().map(Texture::from_desc),
        effects,
        pixel_filter,
        hide_emitters: desc.settings.hide_emitters,
        sides: desc.settings.sides,
    })
}

/// A scene of baked shapes (one prototype per instance), for tests and tools.
pub fn baked_scene(
    camera: Camera,
    shapes: Vec<(Geometry, u32)>,
    materials: Vec<Material>,
) -> RenderScene {
    let mut prototypes = Vec::new();
    let mut instances = Vec::new();
    for (i, (geometry, material)) in shapes.into_iter().enumerate() {
        prototypes.push(Prototype { geometry, name: format!("shape {i}") });
        instances.push(Instance {
            prototype: i as u32,
            material,
            placement: Placement::Baked { object_from_render: Affine3A::IDENTITY },
            name: format!("shape {i}"),
        });
    }
    let lights =
        lights::compile_lights(&[], &DAffine3::IDENTITY, &prototypes, &instances, &materials);
    let pixel_filter =
        FilterSampler::new(Default::default(), camera.width, camera.height, Default::default());
    RenderScene {
        camera,
        prototypes,
        instances,
        materials,
        lights,
        background: Vec3::ZERO,
        backdrop: None,
        effects: Effects::default(),
        pixel_filter,
        hide_emitters: false,
        sides: Default::default(),
    }
}
