//! The space the committed scene lives in, and where it sits relative to the world and the
//! camera.
//!
//! Every object's `render_from_object = render_from_world * world_from_object` is composed in
//! f64 and only then applied to vertices and rounded to f32 (by `compile`), so in
//! `cameraworld` a scene and camera 10⁷ units from the origin cancel exactly and render like
//! a scene at the origin.

use crate::choice::named_choices;
use crate::transform::camera_basis;
use glam::{DAffine3, DMat3, DVec3};

/// The space the committed scene lives in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RenderSpace {
    /// World space translated so the camera sits at the origin; axes stay world-aligned.
    #[default]
    Cameraworld,
    /// Full camera space: translated and rotated (axis-aligned geometry becomes oblique).
    Camera,
    /// World space unchanged: loses precision far from the origin.
    World,
}

named_choices!(RenderSpace, "render space", {
    Cameraworld => "cameraworld",
    Camera => "camera",
    World => "world",
});

impl RenderSpace {
    /// How a coordinate limit of this space is measured, for messages.
    pub fn frame(self) -> &'static str {
        match self {
            RenderSpace::World => "world render space, from the world origin",
            RenderSpace::Cameraworld => "cameraworld render space, from the camera",
            RenderSpace::Camera => "camera render space, from the camera",
        }
    }

    /// What to do about a scene beyond this space's coordinate limit.
    pub fn advice(self) -> &'static str {
        match self {
            RenderSpace::World => {
                "render in cameraworld (the default), which subtracts the camera position in \
                 f64 first, or move the scene nearer the origin"
            }
            RenderSpace::Cameraworld | RenderSpace::Camera => {
                "the camera cannot see that far in f32 without losing the geometry's shape: \
                 scale the scene down or split it"
            }
        }
    }
}

/// Where render space sits relative to the world and to the camera.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraTransform {
    pub render_from_world: DAffine3,
    pub world_from_render: DAffine3,
    /// Camera basis (right, up, back) expressed in world space.
    pub world_from_camera_rotation: DMat3,
}

impl CameraTransform {
    /// For a camera at `lookfrom` looking at `lookat` with `up` (all world space).
    pub fn new(space: RenderSpace, lookfrom: DVec3, lookat: DVec3, up: DVec3) -> Self {
        let world_from_camera_rotation = camera_basis(lookat - lookfrom, up);
        let render_from_world = match space {
            RenderSpace::World => DAffine3::IDENTITY,
            RenderSpace::Cameraworld => DAffine3::from_translation(-lookfrom),
            RenderSpace::Camera => {
                // Inverse of a rigid transform: Rᵀ · translate(-origin).
                let camera_from_world_rotation = world_from_camera_rotation.transpose();
                DAffine3 {
                    matrix3: camera_from_world_rotation,
                    translation: camera_from_world_rotation * -lookfrom,
                }
            }
        };
        CameraTransform {
            render_from_world,
            world_from_render: render_from_world.inverse(),
            world_from_camera_rotation,
        }
    }

    /// Rotation from camera space into render space (identity in `camera` render space).
    pub fn render_from_camera_rotation(&self) -> DMat3 {
        self.render_from_world.matrix3 * self.world_from_camera_rotation
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A camera at `lookfrom` looking along (1, −0.5, 2), y up.
    fn transform_at(space: RenderSpace, lookfrom: DVec3) -> (CameraTransform, DVec3) {
        let lookat = lookfrom + DVec3::new(1.0, -0.5, 2.0);
        (CameraTransform::new(space, lookfrom, lookat, DVec3::Y), lookat)
    }

    #[test]
    fn cameraworld_puts_the_camera_at_the_origin_without_rotation() {
        let (t, _) = transform_at(RenderSpace::Cameraworld, DVec3::splat(1e7));
        assert_eq!(t.render_from_world.transform_point3(DVec3::splat(1e7)), DVec3::ZERO);
        assert_eq!(t.render_from_world.matrix3, DMat3::IDENTITY);
    }

    #[test]
    fn camera_space_maps_the_view_direction_to_minus_z() {
        let (t, lookat) = transform_at(RenderSpace::Camera, DVec3::new(3.0, 4.0, 5.0));
        let ahead = t.render_from_world.transform_point3(lookat);
        assert!(ahead.x.abs() < 1e-12 && ahead.y.abs() < 1e-12 && ahead.z < 0.0);
        assert!(
            (t.render_from_camera_rotation() - DMat3::IDENTITY).abs_diff_eq(DMat3::ZERO, 1e-12)
        );
    }

    #[test]
    fn far_translation_cancels_exactly_in_f64() {
        let offset = DVec3::new(1e7, -1e7, 1e7);
        let world_from_object = DAffine3::from_translation(offset + DVec3::new(0.25, 1.5, 3.0));
        let (t, _) = transform_at(RenderSpace::Cameraworld, offset);
        let render_from_object = t.render_from_world * world_from_object;
        assert_eq!(render_from_object.translation, DVec3::new(0.25, 1.5, 3.0));
    }
}
