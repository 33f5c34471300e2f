//! `<sensor>` (perspective, thinlens) with its `<film>` and `<sampler>`, and `<integrator>`
//! (path, direct, ptracer, moment): the camera and the render settings.

use super::transform::transform;
use super::tree::Element;
use super::values::{boolean, float, integer, numbers, property};
use crate::limits::MAX_DEPTH;
use crate::sampling::filter::PixelFilter;
use crate::scene::desc::{CameraDesc, IntegratorKind, LensShape, RenderSettings};
use crate::scene::error::SceneError;

/// A camera and the sample count its sampler asks for.
pub(super) struct Sensor {
    pub camera: CameraDesc,
    pub spp: Option<u32>,
    pub filter: PixelFilter,
}

fn string<'a>(plugin: &'a Element, name: &str) -> Option<&'a Element> {
    property(plugin, "string", name)
}

/// The x field of view in degrees (Mitsuba's `parse_fov`): `fov` along `fov_axis`, or a
/// 35 mm-equivalent `focal_length` (default 50mm) along the film's diagonal.
pub(super) fn x_fov(sensor: &Element, aspect: f64) -> Result<f64, SceneError> {
    let (fov, axis, at) = match float(sensor, "fov")? {
        Some(fov) => {
            let axis = string(sensor, "fov_axis");
            let name = axis.map_or(Ok("x"), |a| a.required("value"))?;
            (fov, name, axis.unwrap_or(sensor))
        }
        None => {
            let length = match string(sensor, "focal_length") {
                Some(element) => {
                    let text = element.required("value")?;
                    let mm = text.trim().strip_suffix("mm").unwrap_or(text.trim());
                    match numbers(element, mm)?[..] {
                        [f] if f > 0.0 => f,
                        _ => return Err(element.error("focal_length must be like \"50mm\"")),
                    }
                }
                None => 50.0,
            };
            let diagonal = (36.0f64 * 36.0 + 24.0 * 24.0).sqrt();
            let fov = (2.0 * (diagonal / (2.0 * length)).atan()).to_degrees();
            (fov, "diagonal", sensor)
        }
    };
    if !(fov > 0.0 && fov < 180.0) {
        return Err(sensor.error(format!("fov is {fov}, but must be between 0 and 180 degrees")));
    }
    let half_tan = (0.5 * fov).to_radians().tan();
    let x_half_tan = match axis {
        "x" => half_tan,
        "y" => half_tan * aspect,
        "diagonal" => half_tan / (1.0 + 1.0 / (aspect * aspect)).sqrt(),
        "smaller" if aspect > 1.0 => half_tan * aspect,
        "larger" if aspect < 1.0 => half_tan * aspect,
        "smaller" | "larger" => half_tan,
        other => {
            return Err(
                at.error(format!("fov_axis '{other}' is none of x, y, diagonal, smaller, larger"))
            );
        }
    };
    Ok((2.0 * x_half_tan.atan()).to_degrees())
}

pub(super) fn sensor(element: &Element, warnings: &mut Vec<String>) -> Result<Sensor, SceneError> {
    let kind = element.required("type")?;
    if !matches!(kind, "perspective" | "thinlens" | "orthographic") {
        return Err(element.error(format!(
            "the sensor type '{kind}' is not supported (perspective, thinlens and orthographic \
             are)"
        )));
    }
    let (mut width, mut height, mut spp) = (768u32, 576u32, None);
    // Mitsuba's default film: 768 × 576 with a Gaussian filter.
    let mut filter = PixelFilter::Gaussian { stddev: 0.5 };
    for child in &element.children {
        match child.tag.as_str() {
            "film" => (width, height, filter) = film(child, warnings)?,
            "sampler" => {
                let count = integer(child, "sample_count")?.unwrap_or(4);
                if !(1..=i64::from(u32::MAX)).contains(&count) {
                    return Err(child.error("sample_count must be at least 1"));
                }
                spp = Some(count as u32);
            }
            _ => {}
        }
    }
    let to_world = match property(element, "transform", "to_world") {
        Some(t) => transform(t)?,
        None => glam::DAffine3::IDENTITY,
    };
    let origin = to_world.translation;
    let dir = to_world.matrix3.col(2).normalize();
    let up = to_world.matrix3.col(1).normalize();
    let left = to_world.matrix3.col(0);
    if left.dot(up.cross(dir)) <= 0.0 {
        return Err(element.error("a mirrored camera transform is not supported"));
    }
    for name in ["principal_point_offset_x", "principal_point_offset_y"] {
        if float(element, name)?.is_some_and(|v| v != 0.0) {
            return Err(element.error(format!("`{name}` is not supported")));
        }
    }
    let aspect = f64::from(width) / f64::from(height);
    if kind == "orthographic" {
        // Mitsuba's film spans x in [−1, 1] and y in [−1/aspect, 1/aspect] of the camera's
        // space, which to_world may scale.
        let (sx, sy) = (left.length(), to_world.matrix3.col(1).length());
        let mut camera = CameraDesc::pinhole(origin, origin + dir, 90.0, width, height);
        camera.up = up;
        camera.ortho_half_height = Some(sy / aspect);
        camera.pixel_aspect = sx / sy;
        return Ok(Sensor { camera, spp, filter });
    }
    let x_fov = x_fov(element, aspect)?;
    let vfov = (2.0 * ((0.5 * x_fov).to_radians().tan() / aspect).atan()).to_degrees();
    let mut camera = CameraDesc::pinhole(origin, origin + dir, vfov, width, height);
    camera.up = up;
    if kind == "thinlens" {
        let radius = float(element, "aperture_radius")?.unwrap_or(0.0);
        camera.aperture = 2.0 * radius;
        camera.focus_distance = Some(float(element, "focus_distance")?.unwrap_or(0.0));
        camera.lens_shape = LensShape::Disk;
    }
    Ok(Sensor { camera, spp, filter })
}

/// `hdrfilm`: the image size and the reconstruction filter (a crop is refused).
fn film(film: &Element, warnings: &mut Vec<String>) -> Result<(u32, u32, PixelFilter), SceneError> {
    let size = |name: &str, default: i64| -> Result<u32, SceneError> {
        let value = integer(film, name)?.unwrap_or(default);
        let max = i64::from(crate::limits::MAX_RESOLUTION);
        if !(1..=max).contains(&value) {
            return Err(film.error(format!("{name} is {value}, but must be 1 to {max}")));
        }
        Ok(value as u32)
    };
    let (width, height) = (size("width", 768)?, size("height", 576)?);
    for name in ["crop_width", "crop_height", "crop_offset_x", "crop_offset_y"] {
        if float(film, name)?.is_some() {
            return Err(film.error(format!("`{name}` is not supported yet")));
        }
    }
    let filter = film.children.iter().find(|c| c.tag == "rfilter");
    let filter_type = filter.map_or(Ok("gaussian"), |f| f.required("type"))?;
    let parameter = |name: &str, default: f64| -> Result<f32, SceneError> {
        let value = filter.map_or(Ok(None), |f| float(f, name))?.unwrap_or(default);
        if !(value > 0.0 && value <= 16.0) {
            let at = filter.unwrap_or(film);
            return Err(at.error(format!("{name} is {value}, but must be in (0, 16] pixels")));
        }
        Ok(value as f32)
    };
    // The cubics' B and C may be 0 or negative.
    let parameter_any = |name: &str, default: f64| -> Result<f32, SceneError> {
        let value = filter.map_or(Ok(None), |f| float(f, name))?.unwrap_or(default);
        if !(value.abs() <= 16.0) {
            let at = filter.unwrap_or(film);
            return Err(at.error(format!("{name} is {value}, but must be in [-16, 16]")));
        }
        Ok(value as f32)
    };
    let pixel_filter = match filter_type {
        "box" => PixelFilter::Box,
        "gaussian" => PixelFilter::Gaussian { stddev: parameter("stddev", 0.5)? },
        "tent" => PixelFilter::Tent { radius: parameter("radius", 1.0)? },
        "mitchell" => PixelFilter::Mitchell {
            b: parameter_any("B", 1.0 / 3.0)?,
            c: parameter_any("C", 1.0 / 3.0)?,
        },
        "catmullrom" => PixelFilter::Mitchell { b: 0.0, c: 0.5 },
        "lanczos" => PixelFilter::Lanczos { lobes: parameter("lobes", 3.0)? },
        other => {
            warnings.push(format!(
                "{}: line {}: the {other} reconstruction filter is not supported yet: the box \
                 filter is used (each pixel averages its own samples)",
                film.file.display(),
                film.line
            ));
            PixelFilter::Box
        }
    };
    Ok((width, height, pixel_filter))
}

/// The render settings an `<integrator>` asks for (wrappers such as `moment` unwrapped).
pub(super) fn integrator(
    element: &Element,
    settings: &mut RenderSettings,
    warnings: &mut Vec<String>,
) -> Result<(), SceneError> {
    let kind = element.required("type")?;
    let known: &[&str] = match kind {
        "path" | "volpath" => &["max_depth", "rr_depth", "hide_emitters"],
        "ptracer" => &["max_depth", "rr_depth", "hide_emitters", "samples_per_pass"],
        "direct" => &["shading_samples", "emitter_samples", "bsdf_samples", "hide_emitters"],
        "aov" => &["aovs"],
        _ => &[],
    };
    for child in &element.children {
        match child.attr("name") {
            Some(name) if !known.contains(&name) => {
                return Err(child.error(format!(
                    "the {kind} integrator does not take `{name}` (it takes: {})",
                    known.join(", ")
                )));
            }
            None if child.tag != "integrator" => {
                return Err(child.error(format!("an integrator does not take a <{}>", child.tag)));
            }
            _ => {}
        }
    }
    match kind {
        "moment" => match element.children.iter().find(|c| c.tag == "integrator") {
            Some(inner) => integrator(inner, settings, warnings),
            None => Err(element.error("a moment integrator wraps an <integrator>")),
        },
        "path" | "ptracer" | "volpath" => {
            if kind != "path" {
                warnings.push(format!(
                    "{}: line {}: the {kind} integrator is rendered with embray's path tracer \
                     (the same expectation, other noise)",
                    element.file.display(),
                    element.line
                ));
            }
            settings.hide_emitters = boolean(element, "hide_emitters")?.unwrap_or(false);
            settings.integrator = IntegratorKind::Path;
            settings.rr_depth = match integer(element, "rr_depth")?.unwrap_or(5) {
                depth if (1..=i64::from(MAX_DEPTH) + 1).contains(&depth) => depth as u32,
                depth => {
                    return Err(element.error(format!("rr_depth is {depth}, but must be > 0")));
                }
            };
            settings.max_depth = match integer(element, "max_depth")?.unwrap_or(-1) {
                -1 => MAX_DEPTH,
                depth if (1..=i64::from(MAX_DEPTH)).contains(&depth) => depth as u32 - 1,
                depth => {
                    return Err(element.error(format!(
                        "max_depth is {depth}, but must be -1 (no limit) or 1 to {MAX_DEPTH}"
                    )));
                }
            };
            Ok(())
        }
        "aov" => aov_integrator(element, settings, warnings),
        "direct" => direct_integrator(element, settings, warnings),
        other => Err(element.error(format!(
            "the integrator '{other}' is not supported (path, direct, ptracer, moment, aov are)"
        ))),
    }
}

/// Mitsuba's `aov` integrator: its nested integrator renders the image, and its `aovs`
/// (`label:type, …`) become the EXR's AOVs where embray has them (`depth`, `albedo`,
/// `sh_normal` as embray's `Z`, `albedo.*`, `N.*` channels); the others are named in a
/// warning.
fn aov_integrator(
    element: &Element,
    settings: &mut RenderSettings,
    warnings: &mut Vec<String>,
) -> Result<(), SceneError> {
    let nested: Vec<&Element> = element.children.iter().filter(|c| c.tag == "integrator").collect();
    match nested[..] {
        [] => {}
        [inner] => integrator(inner, settings, warnings)?,
        _ => {
            return Err(element
                .error("an aov integrator with more than one nested integrator is not supported"));
        }
    }
    let list = super::values::property(element, "string", "aovs")
        .ok_or_else(|| element.error("an aov integrator needs `aovs` (label:type, …)"))?;
    let mut aovs = crate::output::Aovs::parse("none").expect("none is an AOV list");
    let mut skipped = Vec::new();
    for entry in list.required("value")?.split(',').map(str::trim).filter(|e| !e.is_empty()) {
        let Some((_, kind)) = entry.split_once(':') else {
            return Err(
                list.error(format!("'{}' is not label:type", crate::excerpt::excerpt(entry)))
            );
        };
        match kind.trim() {
            "depth" => aovs.depth = true,
            "albedo" => aovs.albedo = true,
            "sh_normal" => aovs.normal = true,
            other => skipped.push(other.to_owned()),
        }
    }
    if !skipped.is_empty() {
        warnings.push(format!(
            "{}: line {}: the AOVs {} are not written (embray writes depth, albedo and sh_normal)",
            element.file.display(),
            element.line,
            skipped.join(", ")
        ));
    }
    settings.aovs = Some(aovs);
    Ok(())
}

/// Mitsuba's `direct`: the path tracer with one interaction, `emitter_samples` (or
/// `shading_samples`) shadow rays towards the emitters per hit and, MIS-weighted with them,
/// one BSDF sample (`bsdf_samples` other than 1: the same image, other noise, said so).
fn direct_integrator(
    element: &Element,
    settings: &mut RenderSettings,
    warnings: &mut Vec<String>,
) -> Result<(), SceneError> {
    settings.hide_emitters = boolean(element, "hide_emitters")?.unwrap_or(false);
    settings.integrator = IntegratorKind::Path;
    settings.max_depth = 1;
    let shading = integer(element, "shading_samples")?.unwrap_or(1);
    let max = i64::from(crate::limits::MAX_LIGHT_SAMPLES);
    for (name, count) in [
        ("emitter_samples", integer(element, "emitter_samples")?.unwrap_or(shading)),
        ("bsdf_samples", integer(element, "bsdf_samples")?.unwrap_or(shading)),
    ] {
        if !(0..=max).contains(&count) {
            return Err(element.error(format!("{name} is {count}, but must be 0 to {max}")));
        }
        let (taken, as_taken) = match name {
            "emitter_samples" => (count.max(1), "one emitter sample"),
            _ => (1, "one BSDF sample"),
        };
        if name == "emitter_samples" {
            settings.light_samples = taken as u32;
        }
        if taken != count {
            warnings.push(format!(
                "{}: line {}: {name} = {count} is rendered as {as_taken} (the same image, \
                 other noise)",
                element.file.display(),
                element.line
            ));
        }
    }
    Ok(())
}
