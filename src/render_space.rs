//! The space the committed scene lives in, and the one conversion from world space into it.
//!
//! Every object's `render_from_object = render_from_world * world_from_object` is composed in
//! f64 and only then applied to vertices and rounded to f32, so in `cameraworld` a scene and
//! camera 10⁷ units from the origin cancel exactly and render like a scene at the origin.

use crate::camera::{Camera, camera_basis};
use crate::light::{LightSet, PointLight};
use crate::material::Material;
use crate::render_scene::{Geometry, RenderScene, Shape, Sphere, TriangleMesh};
use crate::scene::{CameraDesc, LightDesc, MeshData, SceneDesc, ShapeDesc};
use crate::transform::{normal_matrix, uniform_scale};
use glam::{DAffine3, DMat3, DVec3, Vec3};

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
    #[error(
        "{0}: a sphere's transform must be a similarity (rotation, uniform scale, translation); \
         use a mesh for ellipsoids"
    )]
    NonUniformSphere(String),
    #[error("{0}: transform is singular or not finite")]
    SingularTransform(String),
    #[error("{0}: geometry does not fit in f32 render space (a coordinate overflows or is NaN)")]
    NotRepresentable(String),
}

fn to_f32(v: DVec3) -> Vec3 {
    v.as_vec3()
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
    }
}

/// Converts a world-space scene description into the render-space scene the backends build.
pub fn to_render_scene(
    desc: &SceneDesc,
    space: RenderSpace,
) -> Result<RenderScene, RenderSpaceError> {
    let camera_transform = CameraTransform::new(space, &desc.camera);
    let render_from_world = camera_transform.render_from_world;
    let mut shapes = Vec::with_capacity(desc.objects.len());
    for object in &desc.objects {
        let render_from_object = render_from_world * object.world_from_object;
        let geometry = match &object.shape {
            ShapeDesc::Mesh(mesh) => {
                Geometry::Triangles(place_mesh(mesh, &render_from_object, &object.name)?)
            }
            ShapeDesc::Sphere { center, radius } => {
                let scale = uniform_scale(&object.world_from_object)
                    .ok_or_else(|| RenderSpaceError::NonUniformSphere(object.name.clone()))?;
                let sphere = Sphere {
                    center: to_f32(render_from_object.transform_point3(*center)),
                    radius: (radius * scale) as f32,
                };
                if !sphere.center.is_finite() || !sphere.radius.is_finite() || sphere.radius <= 0.0
                {
                    return Err(RenderSpaceError::NotRepresentable(object.name.clone()));
                }
                Geometry::Sphere(sphere)
            }
        };
        shapes.push(Shape { geometry, material: object.material, name: object.name.clone() });
    }
    let materials: Vec<Material> = desc
        .materials
        .iter()
        .map(|m| Material { albedo: m.albedo, emission: m.emission })
        .collect();
    let points = desc
        .lights
        .iter()
        .filter_map(|light| match light {
            LightDesc::Point { position, intensity } => Some(PointLight {
                position: to_f32(render_from_world.transform_point3(*position)),
                intensity: *intensity,
            }),
            _ => None,
        })
        .collect();
    let lights = LightSet::new(points, &shapes, &materials);
    Ok(RenderScene {
        camera: place_camera(&desc.camera, &camera_transform),
        shapes,
        materials,
        lights,
        background: desc.settings.background,
    })
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
