//! The space the committed scene lives in, and the one conversion from world space into it.
//!
//! Every object's `render_from_object = render_from_world * world_from_object` is composed in
//! f64 and only then applied to vertices and rounded to f32, so in `cameraworld` a scene and
//! camera 10⁷ units from the origin cancel exactly and render like a scene at the origin.

use crate::camera::{Camera, camera_basis};
use crate::effects::Effects;
use crate::light::{DirectionalLight, EmitterShape, LightSet, PointLight};
use crate::material::{Material, Specular};
use crate::render_scene::{
    Geometry, Instance, Placement, Prototype, RenderScene, Sphere, TriangleMesh, Trs,
};
use crate::scene::{CameraDesc, LensShape, LightDesc, MeshData, SceneDesc, ShapeDesc};
use crate::transform::{normal_matrix, uniform_scale};
use glam::{Affine3A, DAffine3, DMat3, DMat4, DVec3, Vec3};
use std::collections::HashMap;
use std::sync::Arc;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum RenderSpace {
    /// World space translated so the camera sits at the origin; axes stay world-aligned.
    #[default]
    Cameraworld,
    /// Full camera space: translated and rotated (axis-aligned geometry becomes oblique).
    Camera,
    /// World space unchanged: loses precision far from the origin.
    World,
}

impl RenderSpace {
    pub fn name(self) -> &'static str {
        match self {
            RenderSpace::Cameraworld => "cameraworld",
            RenderSpace::Camera => "camera",
            RenderSpace::World => "world",
        }
    }
}

/// Where render space sits relative to the world and to the camera.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraTransform {
    pub render_from_world: DAffine3,
    /// Camera basis (right, up, back) expressed in world space.
    pub world_from_camera_rotation: DMat3,
}

impl CameraTransform {
    pub fn new(space: RenderSpace, camera: &CameraDesc) -> Self {
        let basis = camera_basis(camera.lookat - camera.lookfrom, camera.up);
        let render_from_world = match space {
            RenderSpace::World => DAffine3::IDENTITY,
            RenderSpace::Cameraworld => DAffine3::from_translation(-camera.lookfrom),
            RenderSpace::Camera => {
                // Inverse of a rigid transform: Rᵀ · translate(-origin).
                let camera_from_world_rotation = basis.transpose();
                DAffine3 {
                    matrix3: camera_from_world_rotation,
                    translation: camera_from_world_rotation * -camera.lookfrom,
                }
            }
        };
        CameraTransform { render_from_world, world_from_camera_rotation: basis }
    }

    pub fn render_from_camera_rotation(&self) -> DMat3 {
        self.render_from_world.matrix3 * self.world_from_camera_rotation
    }
}

#[derive(Debug, thiserror::Error)]
pub enum RenderSpaceError {
    #[error("{0}: transform is singular or not finite")]
    SingularTransform(String),
    #[error("{0}: geometry does not fit in f32 render space (a coordinate overflows or is NaN)")]
    NotRepresentable(String),
    #[error(
        "{0}: a moving object's transform must be translation · rotation · scale (no shear) \
         at both ends of the shutter interval"
    )]
    MotionShear(String),
}

fn to_f32(v: DVec3) -> Vec3 {
    v.as_vec3()
}

fn to_affine_f32(m: &DAffine3) -> Affine3A {
    Affine3A::from_mat4(DMat4::from(*m).as_mat4())
}

fn place_mesh(
    mesh: &MeshData,
    render_from_object: &DAffine3,
    name: &str,
) -> Result<TriangleMesh, RenderSpaceError> {
    let positions: Vec<Vec3> =
        mesh.positions.iter().map(|&p| to_f32(render_from_object.transform_point3(p))).collect();
    if positions.iter().any(|p| !p.is_finite()) {
        return Err(RenderSpaceError::NotRepresentable(name.to_string()));
    }
    let normals = match &mesh.normals {
        Some(normals) => {
            let normal_from_object = normal_matrix(render_from_object)
                .ok_or_else(|| RenderSpaceError::SingularTransform(name.to_string()))?;
            Some(
                normals
                    .iter()
                    .map(|&n| to_f32((normal_from_object * n).normalize_or_zero()))
                    .collect(),
            )
        }
        None => None,
    };
    Ok(TriangleMesh { positions, indices: mesh.indices.clone(), normals, uvs: mesh.uvs.clone() })
}

fn place_camera(desc: &CameraDesc, camera_transform: &CameraTransform) -> Camera {
    let position = camera_transform.render_from_world.transform_point3(desc.lookfrom);
    let focus_distance =
        desc.focus_distance.unwrap_or_else(|| (desc.lookat - desc.lookfrom).length());
    Camera {
        position: to_f32(position),
        render_from_camera: camera_transform.render_from_camera_rotation().as_mat3(),
        world_from_render: camera_transform.render_from_world.matrix3.inverse().as_mat3(),
        width: desc.width,
        height: desc.height,
        tan_half_vfov: (desc.vfov_deg.to_radians() * 0.5).tan() as f32,
        lens_radius: (desc.aperture * 0.5) as f32,
        focus_distance: focus_distance as f32,
        square_lens: desc.lens_shape == LensShape::Square,
    }
}

/// Translation · rotation · scale of `m`, or `None` if `m` shears.
fn decompose(m: &DAffine3) -> Option<Trs> {
    let (scale, rotation, translation) = m.to_scale_rotation_translation();
    let back = DAffine3::from_scale_rotation_translation(scale, rotation, translation);
    let tolerance = 1e-9 * m.matrix3.abs().to_cols_array().iter().fold(1.0f64, |a, &b| a.max(b));
    if !back.matrix3.abs_diff_eq(m.matrix3, tolerance) || !scale.is_finite() {
        return None;
    }
    Some(Trs {
        translation: to_f32(translation),
        rotation: rotation.as_quat().normalize(),
        scale: to_f32(scale),
    })
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
) -> Result<RenderScene, RenderSpaceError> {
    let camera_transform = CameraTransform::new(space, &desc.camera);
    let render_from_world = camera_transform.render_from_world;
    let force_motion = mode == EffectsMode::ForceAll;
    let mut mesh_users: HashMap<*const MeshData, usize> = HashMap::new();
    for object in &desc.objects {
        if let ShapeDesc::Mesh(mesh) = &object.shape {
            *mesh_users.entry(Arc::as_ptr(mesh)).or_default() += 1;
        }
    }
    let mut shared_prototypes: HashMap<*const MeshData, u32> = HashMap::new();
    let mut prototypes: Vec<Prototype> = Vec::new();
    let mut instances = Vec::with_capacity(desc.objects.len());
    for object in &desc.objects {
        let name = &object.name;
        let render_from_object = render_from_world * object.world_from_object;
        if !render_from_object.is_finite() || render_from_object.matrix3.determinant() == 0.0 {
            return Err(RenderSpaceError::SingularTransform(name.clone()));
        }
        let moving = object.is_moving() || force_motion;
        let transformed = || -> Result<Placement, RenderSpaceError> {
            if moving {
                let end = render_from_world
                    * object.world_from_object_end.unwrap_or(object.world_from_object);
                let start = decompose(&render_from_object)
                    .ok_or_else(|| RenderSpaceError::MotionShear(name.clone()))?;
                let end =
                    decompose(&end).ok_or_else(|| RenderSpaceError::MotionShear(name.clone()))?;
                Ok(Placement::Moving { start, end })
            } else {
                Ok(Placement::Static {
                    render_from_object: to_affine_f32(&render_from_object),
                    object_from_render: to_affine_f32(&render_from_object.inverse()),
                })
            }
        };
        let baked =
            Placement::Baked { object_from_render: to_affine_f32(&render_from_object.inverse()) };
        let (prototype, placement) = match &object.shape {
            ShapeDesc::Mesh(mesh) => {
                let key = Arc::as_ptr(mesh);
                if mesh_users[&key] == 1 && !moving {
                    let geometry =
                        Geometry::Triangles(place_mesh(mesh, &render_from_object, name)?);
                    prototypes.push(Prototype { geometry, name: name.clone() });
                    ((prototypes.len() - 1) as u32, baked)
                } else {
                    let index = match shared_prototypes.get(&key) {
                        Some(&index) => index,
                        None => {
                            let geometry =
                                Geometry::Triangles(place_mesh(mesh, &DAffine3::IDENTITY, name)?);
                            prototypes.push(Prototype { geometry, name: name.clone() });
                            let index = (prototypes.len() - 1) as u32;
                            shared_prototypes.insert(key, index);
                            index
                        }
                    };
                    (index, transformed()?)
                }
            }
            ShapeDesc::Sphere { center, radius } => {
                match uniform_scale(&object.world_from_object).filter(|_| !moving) {
                    Some(scale) => {
                        let sphere = Sphere {
                            center: to_f32(render_from_object.transform_point3(*center)),
                            radius: (radius * scale) as f32,
                        };
                        if !sphere.center.is_finite()
                            || !(sphere.radius > 0.0)
                            || !sphere.radius.is_finite()
                        {
                            return Err(RenderSpaceError::NotRepresentable(name.clone()));
                        }
                        prototypes.push(Prototype {
                            geometry: Geometry::Sphere(sphere),
                            name: name.clone(),
                        });
                        ((prototypes.len() - 1) as u32, baked)
                    }
                    None => {
                        // Ellipsoids and moving spheres: an object-space sphere, transformed.
                        let sphere = Sphere { center: to_f32(*center), radius: *radius as f32 };
                        prototypes.push(Prototype {
                            geometry: Geometry::Sphere(sphere),
                            name: name.clone(),
                        });
                        ((prototypes.len() - 1) as u32, transformed()?)
                    }
                }
            }
        };
        instances.push(Instance {
            prototype,
            material: object.material,
            placement,
            name: name.clone(),
        });
    }
    let materials: Vec<Material> = desc.materials.iter().map(Material::from_desc).collect();
    let mut points = Vec::new();
    let mut directional = Vec::new();
    let mut ambient = Vec3::ZERO;
    let mut squares = Vec::new();
    for light in &desc.lights {
        match light {
            LightDesc::Point { position, intensity } => points.push(PointLight {
                position: to_f32(render_from_world.transform_point3(*position)),
                intensity: *intensity,
            }),
            LightDesc::Directional { direction, irradiance } => {
                directional.push(DirectionalLight {
                    direction: to_f32(render_from_world.transform_vector3(*direction).normalize()),
                    irradiance: *irradiance,
                })
            }
            LightDesc::Ambient { radiance } => ambient += *radiance,
            LightDesc::Area { center, normal, size, radiance } => {
                let (u, v) = crate::transform::course_square_axes(*normal);
                let half = 0.5 * size;
                let edge = |e: DVec3| to_f32(render_from_world.transform_vector3(e * half));
                squares.push((
                    EmitterShape::Square {
                        center: to_f32(render_from_world.transform_point3(*center)),
                        edge_u: edge(u),
                        edge_v: edge(v),
                        normal: to_f32(render_from_world.transform_vector3(*normal).normalize()),
                    },
                    *radiance,
                ));
            }
        }
    }
    let mut lights = LightSet::new(points, directional, &prototypes, &instances, &materials);
    lights.add_squares(squares);
    lights.ambient = ambient;
    let camera = place_camera(&desc.camera, &camera_transform);
    let effects = match mode {
        EffectsMode::ForceAll => Effects::all(),
        EffectsMode::Auto => decide_effects(&camera, &prototypes, &instances, &materials, &lights),
    };
    Ok(RenderScene {
        camera,
        prototypes,
        instances,
        materials,
        lights,
        background: desc.settings.background,
        effects,
    })
}

fn decide_effects(
    camera: &Camera,
    prototypes: &[Prototype],
    instances: &[Instance],
    materials: &[Material],
    lights: &LightSet,
) -> Effects {
    let used = |f: &dyn Fn(&Material) -> bool| {
        instances.iter().any(|i| f(&materials[i.material as usize]))
    };
    Effects {
        depth_of_field: camera.has_lens(),
        motion_blur: instances.iter().any(|i| i.placement.is_moving()),
        area_lights: lights.has_emitters(),
        delta_lights: lights.has_delta_lights(),
        glossy: used(&|m| m.specular != Specular::None && !m.specular_is_delta()),
        specular: used(&|m| m.specular != Specular::None && m.specular_is_delta()),
        refraction: used(&|m| m.is_dielectric()),
        textures: used(&|m| m.texture.is_some()),
        instancing: instances.iter().any(|i| !matches!(i.placement, Placement::Baked { .. })),
        smooth_shading: prototypes
            .iter()
            .any(|p| matches!(&p.geometry, Geometry::Triangles(m) if m.normals.is_some())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera_at(lookfrom: DVec3) -> CameraDesc {
        CameraDesc {
            lookfrom,
            lookat: lookfrom + DVec3::new(1.0, -0.5, 2.0),
            up: DVec3::Y,
            vfov_deg: 40.0,
            width: 8,
            height: 8,
            aperture: 0.0,
            focus_distance: None,
            lens_shape: LensShape::Disk,
        }
    }

    #[test]
    fn cameraworld_puts_the_camera_at_the_origin_without_rotation() {
        let t = CameraTransform::new(RenderSpace::Cameraworld, &camera_at(DVec3::splat(1e7)));
        assert_eq!(t.render_from_world.transform_point3(DVec3::splat(1e7)), DVec3::ZERO);
        assert_eq!(t.render_from_world.matrix3, DMat3::IDENTITY);
    }

    #[test]
    fn camera_space_maps_the_view_direction_to_minus_z() {
        let desc = camera_at(DVec3::new(3.0, 4.0, 5.0));
        let t = CameraTransform::new(RenderSpace::Camera, &desc);
        let ahead = t.render_from_world.transform_point3(desc.lookat);
        assert!(ahead.x.abs() < 1e-12 && ahead.y.abs() < 1e-12 && ahead.z < 0.0);
        assert!(
            (t.render_from_camera_rotation() - DMat3::IDENTITY).abs_diff_eq(DMat3::ZERO, 1e-12)
        );
    }

    #[test]
    fn far_translation_cancels_exactly_in_f64() {
        let offset = DVec3::new(1e7, -1e7, 1e7);
        let desc = camera_at(offset);
        let world_from_object = DAffine3::from_translation(offset + DVec3::new(0.25, 1.5, 3.0));
        let t = CameraTransform::new(RenderSpace::Cameraworld, &desc);
        let render_from_object = t.render_from_world * world_from_object;
        assert_eq!(render_from_object.translation, DVec3::new(0.25, 1.5, 3.0));
    }
}
