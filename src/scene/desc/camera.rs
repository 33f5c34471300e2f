//! The camera: pose, field of view, lens, image size.

use glam::{DVec2, DVec3};

/// The largest lens diameter (or side), focus distance and lens shift (either component):
/// ray origins on the lens stay within the render-space coordinate limit around the camera
/// (a 1e12 lens put them beyond it; at 1e20 no ray was traced and the image was black),
/// and directions towards the focus point or the shifted window stay within what f32
/// holds (a 1e20 shift squared overflows it).
pub const MAX_LENS_EXTENT: f64 = crate::limits::MAX_COORDINATE;

/// The requirement `MAX_LENS_EXTENT` sets, for messages.
pub fn lens_extent_requirement() -> String {
    format!("at most {MAX_LENS_EXTENT:e} (the supported coordinate range around the camera)")
}

#[derive(Clone, Debug, PartialEq)]
pub struct CameraDesc {
    pub lookfrom: DVec3,
    pub lookat: DVec3,
    pub up: DVec3,
    /// Vertical field of view in degrees.
    pub vfov_deg: f64,
    pub width: u32,
    pub height: u32,
    /// Lens diameter; 0 is a pinhole.
    pub aperture: f64,
    /// Distance to the plane in focus; `None` means the lookat distance.
    pub focus_distance: Option<f64>,
    pub lens_shape: LensShape,
    /// Lens shift: the image window's centre, at unit distance in front of the lens, along
    /// the camera's right and up axes (0 = centred; an off-axis projection otherwise, as the
    /// course's off-centre near planes need).
    pub shift: DVec2,
    /// A pixel's width over its height in the scene (1: square). The horizontal field of
    /// view is the vertical one's extent times width / height × this: the course stretches
    /// a near plane whose aspect differs from the resolution's over the image.
    pub pixel_aspect: f64,
    /// An orthographic camera's half-height of view (world units): rays run parallel to the
    /// view direction from the image plane through `lookfrom`; `vfov_deg` is then unused.
    /// `None`: a perspective camera.
    pub ortho_half_height: Option<f64>,
    /// Camera rays see only what lies between these distances along the view axis
    /// (Mitsuba's `near_clip`, `far_clip`); everything by default.
    pub clip: (f64, f64),
    /// The image flipped left to right: the camera's right axis reversed (Mitsuba's sensor
    /// whose `to_world` mirrors, as old exporters write it).
    pub mirrored: bool,
}

impl CameraDesc {
    /// A pinhole camera at `lookfrom` looking at `lookat` (up +Y, no lens shift).
    pub fn pinhole(lookfrom: DVec3, lookat: DVec3, vfov_deg: f64, width: u32, height: u32) -> Self {
        CameraDesc {
            lookfrom,
            lookat,
            up: DVec3::Y,
            vfov_deg,
            width,
            height,
            aperture: 0.0,
            focus_distance: None,
            lens_shape: LensShape::Disk,
            shift: DVec2::ZERO,
            pixel_aspect: 1.0,
            ortho_half_height: None,
            clip: (0.0, f64::INFINITY),
            mirrored: false,
        }
    }
}

/// The shape of the lens aperture (`aperture` is its diameter, or its side for a square).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LensShape {
    #[default]
    Disk,
    /// The course's square lens.
    Square,
}
