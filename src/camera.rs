//! The camera in render space: position, rotation, field of view and thin lens. Rays are
//! generated in camera space (looking down -Z, +Y up) and rotated into render space.

use crate::ray::Ray;
use crate::sampling::concentric_disk;
use glam::{Mat3, Vec2, Vec3};

#[derive(Clone, Debug)]
pub struct Camera {
    /// Lens centre in render space (exactly zero in `cameraworld`).
    pub position: Vec3,
    /// Rotation from camera space to render space (identity in `camera` render space),
    /// after a mirror of x for a mirrored camera (`CameraDesc::mirrored`).
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
    #[inline(always)]
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

    /// The unit render-space direction of the camera-space direction `dir_camera`.
    #[inline(always)]
    fn render_direction(&self, dir_camera: Vec3) -> Vec3 {
        (self.render_from_camera_rotation * dir_camera).normalize()
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
        let dir = self.render_direction(dir_camera);
        let origin = self.position + self.render_from_camera_rotation * origin_camera;
        self.clipped(Ray::new(origin, dir, f32::INFINITY), || along_axis(dir_camera))
    }

    /// Whether `generate_ray` is a pinhole's: perspective and no lens (its sample is
    /// ignored); clipped or not.
    pub fn is_pinhole(&self) -> bool {
        self.ortho_half_height.is_none() && !self.has_lens()
    }

    /// Whether `clipped` limits rays.
    fn clips(&self) -> bool {
        let (near, far) = self.clip;
        near > 0.0 || far.is_finite()
    }

    /// `generate_ray(raster, None)` of each of `rasters`, bit for bit, appended to `rays`, for
    /// a pinhole camera (`is_pinhole`). The directions are computed 16 lanes at a time, in
    /// columns the compiler vectorises (for the widest vector unit the CPU has, `pulp`): one
    /// camera ray at a time, they were most of the camera-ray phase of a Cornell box render.
    pub(crate) fn pinhole_rays(&self, rasters: &[Vec2], rays: &mut Vec<Ray>) {
        debug_assert!(self.is_pinhole());
        pulp::Arch::new().dispatch(PinholeRays { camera: self, rasters, rays });
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

/// The component along the view axis of the unit direction of the camera-space
/// `dir_camera`: what a clip distance is divided by.
#[inline(always)]
fn along_axis(dir_camera: Vec3) -> f32 {
    -dir_camera.z / dir_camera.length()
}

/// Camera rays computed together: AVX-512's width (two AVX2 registers).
const RAY_LANES: usize = 16;

/// `Camera::pinhole_rays`, compiled once per instruction set `pulp` dispatches to.
struct PinholeRays<'a> {
    camera: &'a Camera,
    rasters: &'a [Vec2],
    rays: &'a mut Vec<Ray>,
}

impl pulp::WithSimd for PinholeRays<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let camera = self.camera;
        // `generate_ray`'s origin for a pinhole: the same sum, once.
        let origin = camera.position + camera.render_from_camera_rotation * Vec3::ZERO;
        self.rays.reserve(self.rasters.len());
        let clips = camera.clips();
        for block in self.rasters.chunks(RAY_LANES) {
            let mut dirs = [[0.0f32; RAY_LANES]; 3];
            // Each lane's camera-space direction and its `along_axis`, for a clipping
            // camera's ray limits.
            let mut dirs_camera = [Vec3::ZERO; RAY_LANES];
            let mut along = [1.0f32; RAY_LANES];
            // A full block of lanes (the spare ones from the block's first raster), so that
            // the loops have a fixed length and vectorise.
            for j in 0..RAY_LANES {
                let raster = block[if j < block.len() { j } else { 0 }];
                dirs_camera[j] = camera.camera_direction(raster);
                let dir = camera.render_direction(dirs_camera[j]);
                (dirs[0][j], dirs[1][j], dirs[2][j]) = (dir.x, dir.y, dir.z);
            }
            if clips {
                for (along, &dir_camera) in along.iter_mut().zip(&dirs_camera) {
                    *along = along_axis(dir_camera);
                }
            }
            let [xs, ys, zs] = &dirs;
            let lanes = xs.iter().zip(ys).zip(zs).zip(&along).take(block.len());
            for (((&x, &y), &z), &along) in lanes {
                let ray = Ray::new(origin, Vec3::new(x, y, z), f32::INFINITY);
                self.rays.push(if clips { camera.clipped(ray, || along) } else { ray });
            }
        }
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

    /// The rays computed together are `generate_ray`'s, bit for bit, for cameras turned,
    /// shifted, off the origin and with non-square pixels, at rasters inside and outside
    /// the image, for any number of rays (full and partial blocks).
    #[test]
    fn pinhole_rays_are_generate_rays_bit_for_bit() {
        let turned = Mat3::from_euler(glam::EulerRot::YXZ, 0.7, -0.3, 0.2);
        let cameras = [
            Camera { width: 256, height: 256, tan_half_vfov: 0.357, ..Default::default() },
            Camera {
                position: Vec3::new(-0.0, 3.25, -17.5),
                render_from_camera_rotation: turned,
                width: 640,
                height: 360,
                tan_half_vfov: 0.7,
                shift: Vec2::new(0.125, -0.3),
                pixel_aspect: 1.25,
                ..Default::default()
            },
            // Mitsuba's near and far clip planes.
            Camera { width: 48, height: 32, clip: (10.0, 2800.0), ..Default::default() },
            Camera { width: 48, height: 32, clip: (0.25, f32::INFINITY), ..Default::default() },
        ];
        let mut state = 0x9e37_79b9_u32;
        let mut unit = || {
            state = state.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
            (state >> 8) as f32 / (1 << 24) as f32
        };
        for camera in &cameras {
            assert!(camera.is_pinhole());
            for count in [0, 1, 15, 16, 17, 256, 300] {
                let size = Vec2::new(camera.width as f32, camera.height as f32);
                let rasters: Vec<Vec2> = (0..count)
                    .map(|_| Vec2::new(unit(), unit()) * size * 1.2 - 0.1 * size)
                    .collect();
                let mut rays = vec![Ray::new(Vec3::ONE, Vec3::X, 1.0)];
                camera.pinhole_rays(&rasters, &mut rays);
                assert_eq!(rays.len(), count + 1, "appended");
                for (raster, ray) in rasters.iter().zip(&rays[1..]) {
                    let one = camera.generate_ray(*raster, Some(Vec2::new(0.3, 0.6)));
                    let bits = |r: &Ray| [r.origin, r.dir].map(|v| v.to_array().map(f32::to_bits));
                    assert_eq!(bits(ray), bits(&one), "{raster}");
                    assert_eq!((ray.tmin, ray.tmax, ray.time), (one.tmin, one.tmax, one.time));
                }
            }
        }
    }

    /// Only a perspective camera without a lens is a pinhole, clipped or not.
    #[test]
    fn pinholes_have_no_lens_or_projection() {
        let pinhole = Camera { width: 4, height: 4, ..Default::default() };
        assert!(pinhole.is_pinhole() && !pinhole.clips());
        assert!(!Camera { lens_radius: 0.1, ..pinhole.clone() }.is_pinhole());
        assert!(!Camera { ortho_half_height: Some(2.0), ..pinhole.clone() }.is_pinhole());
        for clip in [(0.5, f32::INFINITY), (0.0, 100.0)] {
            let camera = Camera { clip, ..pinhole.clone() };
            assert!(camera.is_pinhole() && camera.clips(), "{clip:?}");
        }
        // Clip distances `generate_ray` does not apply clip nothing.
        for clip in [(-1.0, f32::INFINITY), (f32::NAN, f32::NAN), (0.0, f32::NEG_INFINITY)] {
            let camera = Camera { clip, ..pinhole.clone() };
            assert!(camera.is_pinhole() && !camera.clips(), "{clip:?}");
            let ray = camera.generate_ray(Vec2::new(1.0, 3.0), None);
            assert_eq!((ray.tmin, ray.tmax), (0.0, f32::INFINITY), "{clip:?}: unclipped");
        }
    }
}
