//! The camera in render space: position, rotation, field of view and thin lens. Rays are
//! generated in camera space (looking down -Z, +Y up) and rotated into render space.

use crate::ray::Ray;
use crate::sampling::concentric_disk;
use glam::{Mat3, Vec2, Vec3};

#[derive(Clone, Debug)]
pub struct Camera {
    /// Lens centre in render space (exactly zero in `cameraworld`).
    pub position: Vec3,
    /// Rotation from camera space to render space (identity in `camera` render space).
    pub render_from_camera_rotation: Mat3,
    /// Rotation from render space back to world space, for world-space normal AOVs.
    pub world_from_render_rotation: Mat3,
    pub width: u32,
    pub height: u32,
    pub tan_half_vfov: f32,
    /// Half the aperture: the disk's radius, or half the side of a square lens.
    pub lens_radius: f32,
    pub focus_distance: f32,
    /// The course's square lens instead of a disk.
    pub square_lens: bool,
    /// Lens shift: the window centre at unit distance (camera space x, y).
    pub shift: Vec2,
    /// A pixel's width over its height (see `CameraDesc::pixel_aspect`).
    pub pixel_aspect: f32,
    /// An orthographic camera's half-height of view; `None` for a perspective one.
    pub ortho_half_height: Option<f32>,
    /// The near and far clip distances along the view axis (`CameraDesc::clip`).
    pub clip: (f32, f32),
}

impl Default for Camera {
    fn default() -> Self {
        Camera {
            position: Vec3::ZERO,
            render_from_camera_rotation: Mat3::IDENTITY,
            world_from_render_rotation: Mat3::IDENTITY,
            width: 1,
            height: 1,
            tan_half_vfov: 1.0,
            lens_radius: 0.0,
            focus_distance: 1.0,
            square_lens: false,
            shift: Vec2::ZERO,
            pixel_aspect: 1.0,
            ortho_half_height: None,
            clip: (0.0, f32::INFINITY),
        }
    }
}

impl Camera {
    pub fn has_lens(&self) -> bool {
        self.lens_radius > 0.0
    }

    /// Direction (camera space, not normalised, z = -1) through raster position `raster`
    /// (pixel centres at +0.5, y pointing down).
    fn camera_direction(&self, raster: Vec2) -> Vec3 {
        let aspect = self.width as f32 / self.height as f32 * self.pixel_aspect;
        let ndc_x = 2.0 * raster.x / self.width as f32 - 1.0;
        let ndc_y = 1.0 - 2.0 * raster.y / self.height as f32;
        Vec3::new(
            ndc_x * self.tan_half_vfov * aspect + self.shift.x,
            ndc_y * self.tan_half_vfov + self.shift.y,
            -1.0,
        )
    }

    /// The primary ray through `raster`. `lens` is a uniform sample in [0,1)² and is only
    /// read when the camera has an aperture.
    #[inline(always)]
    pub fn generate_ray(&self, raster: Vec2, lens: Option<Vec2>) -> Ray {
        if let Some(half_height) = self.ortho_half_height {
            // Parallel rays from the image plane: the perspective direction's x and y at unit
            // distance, scaled from tan(vfov/2) to the half-height, are the offset.
            let offset = self.camera_direction(raster) * (half_height / self.tan_half_vfov);
            let origin_camera = Vec3::new(offset.x, offset.y, 0.0);
            let origin = self.position + self.render_from_camera_rotation * origin_camera;
            let dir = (self.render_from_camera_rotation * Vec3::NEG_Z).normalize();
            return self.clipped(Ray::new(origin, dir, f32::INFINITY), || 1.0);
        }
        let dir_camera = self.camera_direction(raster);
        let (origin_camera, dir_camera) = match lens {
            Some(u) if self.has_lens() => {
                let unit = if self.square_lens { 2.0 * u - Vec2::ONE } else { concentric_disk(u) };
                let on_lens = unit * self.lens_radius;
                let origin = Vec3::new(on_lens.x, on_lens.y, 0.0);
                // dir_camera has z = -1, so scaling by the focus distance lands on the focal plane.
                let focus = dir_camera * self.focus_distance;
                (origin, focus - origin)
            }
            _ => (Vec3::ZERO, dir_camera),
        };
        let dir = (self.render_from_camera_rotation * dir_camera).normalize();
        let origin = self.position + self.render_from_camera_rotation * origin_camera;
        self.clipped(Ray::new(origin, dir, f32::INFINITY), || -dir_camera.z / dir_camera.length())
    }

    /// `ray` limited to the clip distances, measured along the view axis (the unit
    /// direction's component along it is `along_axis`, computed only for a clipping camera).
    #[inline]
    fn clipped(&self, mut ray: Ray, along_axis: impl Fn() -> f32) -> Ray {
        let (near, far) = self.clip;
        if near > 0.0 {
            ray.tmin = near / along_axis();
        }
        if far.is_finite() {
            ray.tmax = far / along_axis();
        }
        ray
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_pixel_looks_forward() {
        let cam = Camera { width: 3, height: 3, ..Default::default() };
        let ray = cam.generate_ray(Vec2::new(1.5, 1.5), None);
        assert!((ray.dir - Vec3::NEG_Z).length() < 1e-6);
    }

    #[test]
    fn thin_lens_rays_converge_on_the_focal_plane() {
        let cam = Camera {
            width: 4,
            height: 4,
            lens_radius: 0.5,
            focus_distance: 10.0,
            ..Default::default()
        };
        let raster = Vec2::new(0.7, 3.1);
        let pinhole = cam.generate_ray(raster, None);
        let focal_point = pinhole.origin + pinhole.dir * (10.0 / -pinhole.dir.z);
        for u in [Vec2::new(0.1, 0.9), Vec2::new(0.8, 0.3)] {
            let r = cam.generate_ray(raster, Some(u));
            let p = r.origin + r.dir * (10.0 / -r.dir.z);
            assert!((p - focal_point).length() < 1e-4);
        }
    }
}
