//! The render-space camera from its world-space description.

use crate::camera::Camera;
use crate::render_space::CameraTransform;
use crate::scene::{CameraDesc, LensShape};

pub(super) fn place_camera(desc: &CameraDesc, camera_transform: &CameraTransform) -> Camera {
    let position = camera_transform.render_from_world.transform_point3(desc.lookfrom);
    let focus_distance =
        desc.focus_distance.unwrap_or_else(|| (desc.lookat - desc.lookfrom).length());
    // A mirrored camera's x axis reversed: the linear map stays orthogonal (its transpose
    // its inverse), and every ray the camera makes, lens and orthographic offsets included,
    // is mirrored with it.
    let mirror = glam::DMat3::from_diagonal(glam::DVec3::new(-1.0, 1.0, 1.0));
    let rotation = camera_transform.render_from_camera_rotation();
    let rotation = if desc.mirrored { rotation * mirror } else { rotation };
    Camera {
        position: position.as_vec3(),
        render_from_camera_rotation: rotation.as_mat3(),
        world_from_render_rotation: camera_transform.world_from_render.matrix3.as_mat3(),
        width: desc.width,
        height: desc.height,
        tan_half_vfov: (desc.vfov_deg.to_radians() * 0.5).tan() as f32,
        lens_radius: (desc.aperture * 0.5) as f32,
        focus_distance: focus_distance as f32,
        square_lens: desc.lens_shape == LensShape::Square,
        shift: desc.shift.as_vec2(),
        pixel_aspect: desc.pixel_aspect as f32,
        ortho_half_height: desc.ortho_half_height.map(|h| h as f32),
        clip: (desc.clip.0 as f32, desc.clip.1 as f32),
    }
}
