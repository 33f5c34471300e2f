//! The `[camera]` and `[render]` tables → `CameraDesc` and `RenderSettings`, validated.

use super::desc::{CameraDesc, RenderSettings};
use super::error::SceneError;
use super::source_map::FieldPath;
use super::toml_format::{CameraToml, RenderToml};
use super::transform_list::fmt_vec;
use super::validate::Ctx;
use glam::DVec3;

/// The largest width or height accepted.
pub const MAX_RESOLUTION: u32 = 16384;

pub(crate) fn camera(cam: &CameraToml, ctx: &Ctx) -> Result<CameraDesc, SceneError> {
    let path = FieldPath::root("camera");
    let degenerate = |field: &str, reason: String| SceneError::DegenerateCamera {
        file: ctx.file.to_path_buf(),
        reason,
        line: ctx.line(&path.key(field)),
    };
    let (lookfrom, lookat) = (DVec3::from_array(cam.lookfrom), DVec3::from_array(cam.lookat));
    if lookfrom == lookat {
        return Err(degenerate(
            "lookat",
            format!(
                "camera.lookfrom and camera.lookat are the same point {}, so there is no view \
                 direction",
                fmt_vec(&cam.lookfrom)
            ),
        ));
    }
    if !(lookat - lookfrom).length().is_finite() {
        return Err(degenerate(
            "lookat",
            "the distance from camera.lookfrom to camera.lookat overflows".to_owned(),
        ));
    }
    let up = cam.up.unwrap_or([0.0, 1.0, 0.0]);
    if DVec3::from_array(up).try_normalize().is_none() {
        return Err(degenerate("up", format!("camera.up {} is the zero vector", fmt_vec(&up))));
    }
    let vfov = path.key("vfov");
    ctx.require(
        cam.vfov > 0.0 && cam.vfov < 180.0,
        &vfov,
        cam.vfov,
        "between 0 and 180 degrees (exclusive)",
    )?;
    for (i, &r) in cam.resolution.iter().enumerate() {
        let requirement = format!("between 1 and {MAX_RESOLUTION}");
        ctx.require(
            (1..=MAX_RESOLUTION).contains(&r),
            &path.key("resolution").index(i),
            r,
            &requirement,
        )?;
    }
    let aperture = ctx.non_negative(&path.key("aperture"), cam.aperture.unwrap_or(0.0))?;
    let focus_distance =
        cam.focus_distance.map(|d| ctx.positive(&path.key("focus_distance"), d)).transpose()?;
    Ok(CameraDesc {
        lookfrom,
        lookat,
        up: DVec3::from_array(up),
        vfov_deg: cam.vfov,
        width: cam.resolution[0],
        height: cam.resolution[1],
        aperture,
        focus_distance,
        lens_shape: Default::default(),
    })
}

pub(crate) fn settings(
    render: Option<&RenderToml>,
    ctx: &Ctx,
) -> Result<RenderSettings, SceneError> {
    let mut settings = RenderSettings::default();
    let Some(render) = render else {
        return Ok(settings);
    };
    let path = FieldPath::root("render");
    if let Some(spp) = render.spp {
        ctx.require(spp >= 1, &path.key("spp"), spp, ">= 1")?;
        settings.spp = spp;
    }
    if let Some(max_depth) = render.max_depth {
        settings.max_depth = max_depth;
    }
    if let Some(background) = render.background {
        settings.background = ctx.color(&path.key("background"), background, false)?;
    }
    Ok(settings)
}
