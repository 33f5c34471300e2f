//! The `[camera]` and `[render]` tables → `CameraDesc` and `RenderSettings`, validated.

use crate::scene::Sides;
use crate::scene::desc::{
    CameraDesc, IntegratorKind, LensShape, MAX_LENS_EXTENT, RenderSettings, lens_extent_requirement,
};
use crate::scene::error::SceneError;
use crate::scene::formats::toml::format::{
    CameraToml, IntegratorToml, LensToml, RenderToml, SidesToml,
};
use crate::scene::formats::toml::source_map::FieldPath;
use crate::scene::formats::toml::transform_list::fmt_vec;
use crate::scene::formats::toml::validate::Ctx;
use glam::{DVec2, DVec3};

use crate::limits::MAX_RESOLUTION;

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
        let reason = format!("camera.up {} has no direction (zero, or too short)", fmt_vec(&up));
        return Err(degenerate("up", reason));
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
    let aperture = aperture(cam, ctx)?;
    let lens_limit = lens_extent_requirement();
    let focus_distance = match cam.focus_distance {
        Some(d) => {
            let field = path.key("focus_distance");
            ctx.positive(&field, d)?;
            ctx.require(d <= MAX_LENS_EXTENT, &field, d, &lens_limit)?;
            Some(d)
        }
        None => None,
    };
    let shift = cam.shift.unwrap_or([0.0; 2]);
    for (i, &s) in shift.iter().enumerate() {
        let requirement = format!("in [-{MAX_LENS_EXTENT:e}, {MAX_LENS_EXTENT:e}]");
        ctx.require(s.abs() <= MAX_LENS_EXTENT, &path.key("shift").index(i), s, &requirement)?;
    }
    let clip = cam.clip.unwrap_or([0.0, f64::INFINITY]);
    let [near, far] = clip;
    let clip_ok = near >= 0.0 && near.is_finite() && far > near;
    ctx.require(clip_ok, &path.key("clip"), fmt_vec(&clip), "[near, far] with 0 <= near < far")?;
    Ok(CameraDesc {
        ortho_half_height: None,
        clip: (near, far),
        mirrored: cam.mirrored.unwrap_or(false),
        lookfrom,
        lookat,
        up: DVec3::from_array(up),
        vfov_deg: cam.vfov,
        width: cam.resolution[0],
        height: cam.resolution[1],
        aperture,
        focus_distance,
        lens_shape: match cam.lens {
            None | Some(LensToml::Disk) => LensShape::Disk,
            Some(LensToml::Square) => LensShape::Square,
        },
        shift: DVec2::from_array(shift),
        pixel_aspect: match cam.pixel_aspect {
            Some(a) => {
                let field = path.key("pixel_aspect");
                ctx.require((1e-3..=1e3).contains(&a), &field, a, "between 0.001 and 1000")?;
                a
            }
            None => 1.0,
        },
    })
}

/// The lens diameter: `aperture`, or `focal_length / f_number`, or 0 (a pinhole).
fn aperture(cam: &CameraToml, ctx: &Ctx) -> Result<f64, SceneError> {
    let path = FieldPath::root("camera");
    match (cam.aperture, cam.f_number, cam.focal_length) {
        (Some(_), Some(_), _) => Err(ctx.conflict(&path, "camera", "aperture", "f_number")),
        (Some(_), None, Some(_)) => Err(ctx.conflict(&path, "camera", "aperture", "focal_length")),
        (Some(aperture), None, None) => {
            let field = path.key("aperture");
            ctx.non_negative(&field, aperture)?;
            ctx.require(aperture <= MAX_LENS_EXTENT, &field, aperture, &lens_extent_requirement())?;
            Ok(aperture)
        }
        (None, Some(f_number), focal_length) => {
            let min = crate::limits::MIN_F_NUMBER;
            let requirement = format!("at least {min} (a faster lens is an infinite aperture)");
            ctx.require(f_number >= min, &path.key("f_number"), f_number, &requirement)?;
            let item = "camera (with f_number)";
            let focal_length =
                ctx.required(&path.key("f_number"), item, "focal_length", focal_length)?;
            let focal_length = ctx.positive(&path.key("focal_length"), focal_length)?;
            let aperture = focal_length / f_number;
            let requirement = format!(
                "large enough that the lens diameter focal_length / f_number is at most \
                 {MAX_LENS_EXTENT:e} (the supported coordinate range around the camera)"
            );
            ctx.require(
                aperture <= MAX_LENS_EXTENT,
                &path.key("f_number"),
                f_number,
                &requirement,
            )?;
            Ok(aperture)
        }
        (None, None, Some(_)) => {
            Err(ctx.missing(&path.key("focal_length"), "camera (with focal_length)", "f_number"))
        }
        (None, None, None) => Ok(0.0),
    }
}

/// `[render]`; `camera` for the size a crop must lie within.
pub(crate) fn settings(
    render: Option<&RenderToml>,
    camera: &crate::scene::desc::CameraDesc,
    ctx: &Ctx,
) -> Result<RenderSettings, SceneError> {
    let mut settings = RenderSettings::default();
    let Some(render) = render else {
        return Ok(settings);
    };
    let path = FieldPath::root("render");
    if let Some(spp) = render.spp {
        let max = crate::limits::MAX_SPP;
        ctx.require(
            (1..=max).contains(&spp),
            &path.key("spp"),
            spp,
            &format!("between 1 and {max}"),
        )?;
        settings.spp = spp;
    }
    if let Some(max_depth) = render.max_depth {
        let max = crate::limits::MAX_DEPTH;
        ctx.require(
            max_depth <= max,
            &path.key("max_depth"),
            max_depth,
            &format!("at most {max}"),
        )?;
        settings.max_depth = max_depth;
    }
    if let Some(background) = render.background {
        settings.background = ctx.color(&path.key("background"), background, false)?;
    }
    if let Some(light_samples) = render.light_samples {
        let max = crate::limits::MAX_LIGHT_SAMPLES;
        let requirement = format!("between 1 and {max}");
        let ok = (1..=max).contains(&light_samples);
        ctx.require(ok, &path.key("light_samples"), light_samples, &requirement)?;
        settings.light_samples = light_samples;
    }
    if let Some(integrator) = render.integrator {
        settings.integrator = match integrator {
            IntegratorToml::Path => IntegratorKind::Path,
            IntegratorToml::Whitted => IntegratorKind::Whitted,
        };
    }
    settings.hide_emitters = render.hide_emitters.unwrap_or(false);
    settings.sides = match render.sides {
        None | Some(SidesToml::Both) => Sides::Both,
        Some(SidesToml::Shading) => Sides::Shading,
    };
    if let Some([x0, y0, x1, y1]) = render.crop {
        let ok = x0 < x1 && y0 < y1 && x1 <= camera.width && y1 <= camera.height;
        let requirement = format!(
            "x0 < x1 ≤ {} and y0 < y1 ≤ {} (pixels of the image, the second corner excluded)",
            camera.width, camera.height
        );
        ctx.require(ok, &path.key("crop"), format!("[{x0}, {y0}, {x1}, {y1}]"), &requirement)?;
        settings.crop = Some(crate::film::Tile { x0, y0, x1, y1 });
    }
    if let Some(rr_depth) = render.rr_depth {
        ctx.require(rr_depth >= 1, &path.key("rr_depth"), rr_depth, "at least 1")?;
        settings.rr_depth = rr_depth;
    }
    settings.seed = render.seed.unwrap_or(0);
    settings.jitter = render.jitter.unwrap_or(true);
    if let Some(filter) = &render.filter {
        settings.filter = pixel_filter(ctx, &path.key("filter"), filter)?;
    }
    if let Some(t) = &render.tonemap {
        let path = path.key("tonemap");
        // The one operator there is; the field makes the choice explicit in the file.
        let crate::scene::formats::toml::format::TonemapOperatorToml::Photographic = t.operator;
        let mut p = crate::output::Photographic::default();
        for (field, value, target) in [
            ("key", t.key, &mut p.key),
            ("burn_out", t.burn_out, &mut p.burn_out),
            ("saturation", t.saturation, &mut p.saturation),
            ("gamma", t.gamma, &mut p.gamma),
        ] {
            if let Some(v) = value {
                *target = ctx.f32(&path.key(field), v)?;
            }
        }
        if let Some((field, value, requirement)) = p.out_of_range() {
            return Err(ctx.out_of_range(&path.key(field), value, requirement));
        }
        settings.tonemap = Some(p);
    }
    Ok(settings)
}

/// `[render] filter`: the type and its one size (Mitsuba's defaults: σ = 0.5, r = 1).
fn pixel_filter(
    ctx: &Ctx,
    path: &FieldPath,
    filter: &crate::scene::formats::toml::format::FilterToml,
) -> Result<crate::sampling::filter::PixelFilter, SceneError> {
    use crate::sampling::filter::{FILTER_SIZES, PixelFilter, filter_sizes_text};
    use crate::scene::formats::toml::format::FilterKindToml;
    let item = format!("{path} ({:?} filter)", filter.kind).to_lowercase();
    let size = |name: &str, value: Option<f64>, default: f64| -> Result<f32, SceneError> {
        let value = value.unwrap_or(default);
        let ok = FILTER_SIZES.contains(&value);
        ctx.require(ok, &path.key(name), value, &filter_sizes_text())?;
        Ok(value as f32)
    };
    let present = [
        ("stddev", filter.stddev.is_some()),
        ("radius", filter.radius.is_some()),
        ("b", filter.b.is_some()),
        ("c", filter.c.is_some()),
        ("lobes", filter.lobes.is_some()),
    ];
    let coefficient = |name: &str, value: Option<f64>, default: f64| -> Result<f32, SceneError> {
        let value = value.unwrap_or(default);
        ctx.require(value.abs() <= 16.0, &path.key(name), value, "in [-16, 16]")?;
        Ok(value as f32)
    };
    let built = match filter.kind {
        FilterKindToml::Box => {
            ctx.check_fields(path, &item, &present, &["type"])?;
            PixelFilter::Box
        }
        FilterKindToml::Gaussian => {
            ctx.check_fields(path, &item, &present, &["type", "stddev"])?;
            PixelFilter::Gaussian { stddev: size("stddev", filter.stddev, 0.5)? }
        }
        FilterKindToml::Tent => {
            ctx.check_fields(path, &item, &present, &["type", "radius"])?;
            PixelFilter::Tent { radius: size("radius", filter.radius, 1.0)? }
        }
        FilterKindToml::Mitchell => {
            ctx.check_fields(path, &item, &present, &["type", "b", "c"])?;
            PixelFilter::Mitchell {
                b: coefficient("b", filter.b, 1.0 / 3.0)?,
                c: coefficient("c", filter.c, 1.0 / 3.0)?,
            }
        }
        FilterKindToml::Catmullrom => {
            ctx.check_fields(path, &item, &present, &["type"])?;
            PixelFilter::Mitchell { b: 0.0, c: 0.5 }
        }
        FilterKindToml::Lanczos => {
            ctx.check_fields(path, &item, &present, &["type", "lobes"])?;
            PixelFilter::Lanczos { lobes: size("lobes", filter.lobes, 3.0)? }
        }
    };
    ctx.require(built.problem().is_none(), &path.key("b"), filter.b.unwrap_or(0.0), "below 3")?;
    Ok(built)
}
