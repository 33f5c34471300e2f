//! `<sensor>` (perspective, thinlens, orthographic) with its `<film>` and `<sampler>`: the
//! camera, the sample count, the filter and the crop.

use super::transform::transform;
use super::tree::Element;
use super::values::{float, numbers, property, refuse_second, refuse_unread, string};
use crate::sampling::filter::PixelFilter;
use crate::scene::desc::{CameraDesc, LensShape, MAX_LENS_EXTENT, lens_extent_requirement};
use crate::scene::error::SceneError;

/// A camera and what its sampler asks for.
pub(super) struct Sensor {
    pub camera: CameraDesc,
    pub sampler: Option<super::sampler::Sampler>,
    pub filter: PixelFilter,
    pub crop: Option<crate::film::Tile>,
}

/// The x field of view in degrees (Mitsuba's `parse_fov`): `fov` along `fov_axis`, or a
/// 35 mm-equivalent `focal_length` (default 50mm) along the film's diagonal.
pub(super) fn x_fov(sensor: &Element, aspect: f64) -> Result<f64, SceneError> {
    if let (Some(_), Some(focal)) = (float(sensor, "fov")?, string(sensor, "focal_length")?) {
        // As Mitsuba: one of them would be dropped unseen.
        return Err(focal.error("give either fov or focal_length, not both"));
    }
    let (fov, axis, at) = match float(sensor, "fov")? {
        Some(fov) => {
            let axis = string(sensor, "fov_axis")?;
            // Mitsuba lowers its case.
            let name = axis.map_or(Ok("x"), |a| a.required("value"))?.to_ascii_lowercase();
            (fov, name, axis.unwrap_or(sensor))
        }
        None => {
            let length = match string(sensor, "focal_length")? {
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
            (fov, "diagonal".to_owned(), sensor)
        }
    };
    if !(fov > 0.0 && fov < 180.0) {
        return Err(sensor.error(format!("fov is {fov}, but must be between 0 and 180 degrees")));
    }
    let half_tan = (0.5 * fov).to_radians().tan();
    let x_half_tan = match axis.as_str() {
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
    check_sensor_properties(element, kind)?;
    let (mut width, mut height, mut sampler) = (768u32, 576u32, None);
    // Mitsuba's default film: 768 × 576 with a Gaussian filter.
    let mut filter = PixelFilter::Gaussian { stddev: 0.5 };
    let mut crop = None;
    refuse_second(element, "film", "a sensor")?;
    refuse_second(element, "sampler", "a sensor")?;
    for child in &element.children {
        match child.tag.as_str() {
            "film" => {
                let film = super::film::film(child, warnings)?;
                (width, height, filter, crop) = (film.width, film.height, film.filter, film.crop);
            }
            "sampler" => sampler = Some(super::sampler::sampler(child)?),
            _ => {}
        }
    }
    let to_world = match property(element, "transform", "to_world") {
        Some(t) => transform(t)?,
        None => glam::DAffine3::IDENTITY,
    };
    if kind != "orthographic" {
        // Mitsuba's test (`has_scale`).
        if !crate::transform::is_orthonormal(to_world.matrix3) {
            let at = property(element, "transform", "to_world").unwrap_or(element);
            return Err(at.error(
                "scale factors (or shear) in a camera's to_world are not allowed (as in Mitsuba)",
            ));
        }
    }
    let origin = to_world.translation;
    let dir = to_world.matrix3.col(2).normalize();
    let up = to_world.matrix3.col(1).normalize();
    let left = to_world.matrix3.col(0);
    // Mitsuba renders a mirroring to_world flipped left to right (old exporters write
    // `<scale x="-1"/>` before the `<lookat>`).
    let mirrored = left.dot(up.cross(dir)) <= 0.0;
    let near = float(element, "near_clip")?.unwrap_or(1e-2);
    let far = float(element, "far_clip")?.unwrap_or(1e4);
    if !(near >= 0.0 && far > near && far.is_finite()) {
        return Err(element.error(format!(
            "near_clip {near} and far_clip {far} must be 0 <= near_clip < far_clip"
        )));
    }
    let aspect = f64::from(width) / f64::from(height);
    if kind != "thinlens" {
        // Read (without a lens it has no use), so that it is a number as Mitsuba requires.
        float(element, "focus_distance")?;
    }
    if kind == "orthographic" {
        // Mitsuba's film spans x in [−1, 1] and y in [−1/aspect, 1/aspect] of the camera's
        // space, which to_world may scale.
        let (sx, sy) = (left.length(), to_world.matrix3.col(1).length());
        let mut camera = CameraDesc::pinhole(origin, origin + dir, 90.0, width, height);
        camera.up = up;
        camera.ortho_half_height = Some(sy / aspect);
        camera.clip = (near, far);
        camera.pixel_aspect = sx / sy;
        camera.mirrored = mirrored;
        return Ok(Sensor { camera, sampler, filter, crop });
    }
    let x_fov = x_fov(element, aspect)?;
    let vfov = (2.0 * ((0.5 * x_fov).to_radians().tan() / aspect).atan()).to_degrees();
    let mut camera = CameraDesc::pinhole(origin, origin + dir, vfov, width, height);
    camera.up = up;
    camera.clip = (near, far);
    camera.mirrored = mirrored;
    // Mitsuba shifts the film sample by the offset, in film widths and heights: the window
    // moves right and down (embray's shift is along right and up at unit distance).
    let offset = |name| float(element, name).map(|v| v.unwrap_or(0.0));
    let x_extent = 2.0 * (0.5 * x_fov).to_radians().tan();
    camera.shift = glam::DVec2::new(
        offset("principal_point_offset_x")? * x_extent,
        -offset("principal_point_offset_y")? * x_extent / aspect,
    );
    // A lens beyond the coordinate range around the camera puts ray origins beyond it.
    let beyond_as = |name: &str, value: f64, requirement: String| {
        let at = element.children.iter().find(|c| c.attr("name") == Some(name));
        at.unwrap_or(element).error(format!("{name} is {value}, but must be {requirement}"))
    };
    let beyond = |name: &str, value: f64| beyond_as(name, value, lens_extent_requirement());
    // An offset is in film widths (heights): its shift is the offset times the film's size
    // at unit distance.
    let widths =
        [("principal_point_offset_x", x_extent), ("principal_point_offset_y", x_extent / aspect)];
    for (name, film_size) in widths {
        let value = offset(name)?;
        if !((value * film_size).abs() <= MAX_LENS_EXTENT) {
            let bound = MAX_LENS_EXTENT / film_size;
            let requirement = format!(
                "at most {bound:e} in size (a shift of {MAX_LENS_EXTENT:e}, the supported coordinate range around the camera)"
            );
            return Err(beyond_as(name, value, requirement));
        }
    }
    if kind == "thinlens" {
        let radius = float(element, "aperture_radius")?.unwrap_or(0.0);
        if 2.0 * radius > MAX_LENS_EXTENT {
            return Err(beyond("aperture_radius", radius));
        }
        camera.aperture = 2.0 * radius;
        // The plane in focus: Mitsuba's default is the far clip plane; one not in front of
        // the lens would focus nowhere.
        let focus = float(element, "focus_distance")?.unwrap_or(far);
        if !(focus > 0.0 && focus.is_finite()) {
            return Err(element.error(format!(
                "focus_distance is {focus}, but a thin lens needs one > 0 (in front of it)"
            )));
        }
        if radius > 0.0 && focus > MAX_LENS_EXTENT {
            return Err(beyond("focus_distance", focus));
        }
        camera.focus_distance = Some(focus);
        camera.lens_shape = LensShape::Disk;
    }
    Ok(Sensor { camera, sampler, filter, crop })
}

/// Refuses a parameter the sensor does not read (`shutter_open`/`shutter_close` are read
/// and unused: no Mitsuba scene embray reads moves).
fn check_sensor_properties(element: &Element, kind: &str) -> Result<(), SceneError> {
    // Every projective camera of Mitsuba's reads `focus_distance` (the orthographic one
    // too); only a thin lens has a use for it.
    let mut known = vec!["to_world", "near_clip", "far_clip", "shutter_open", "shutter_close"];
    known.push("focus_distance");
    if kind != "orthographic" {
        known.extend(["fov", "fov_axis", "focal_length"]);
        known.extend(["principal_point_offset_x", "principal_point_offset_y"]);
    }
    if kind == "thinlens" {
        known.push("aperture_radius");
    }
    for child in &element.children {
        if child.tag == "medium" {
            return Err(child.error("participating media (<medium>) are not supported"));
        }
    }
    refuse_unread(element, &format!("the {kind} sensor"), &known, &["film", "sampler"])
}
