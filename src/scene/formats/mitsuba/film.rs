//! `<film>` (`hdrfilm`): the image size, its crop window and the reconstruction filter.

use super::tree::Element;
use super::values::{boolean, float, integer, refuse_second, refuse_unread};
use crate::film::Tile;
use crate::sampling::filter::{FILTER_SIZES, PixelFilter};
use crate::scene::error::SceneError;

/// What `hdrfilm` reads. The output's format, channels and precision are embray's own
/// (`-o`, `--aovs`), so those are only checked.
const FILM_PARAMETERS: [&str; 12] = [
    "width",
    "height",
    "crop_offset_x",
    "crop_offset_y",
    "crop_width",
    "crop_height",
    "file_format",
    "pixel_format",
    "component_format",
    "sample_border",
    "compensate",
    // Mitsuba 3 accepts it (Mitsuba 0.6's), of any type, and draws no banner.
    "banner",
];

/// The values Mitsuba accepts for the film's string parameters (in any case).
const FILM_CHOICES: [(&str, &[&str]); 3] = [
    ("file_format", &["openexr", "exr", "rgbe", "pfm"]),
    ("pixel_format", &["luminance", "luminance_alpha", "rgb", "rgba", "xyz", "xyza"]),
    ("component_format", &["float16", "float32", "uint32"]),
];

pub(super) struct Film {
    pub width: u32,
    pub height: u32,
    pub filter: PixelFilter,
    /// The window `crop_offset_x/y`, `crop_width/height` keep (Mitsuba's crop), if smaller
    /// than the film.
    pub crop: Option<Tile>,
}

/// Mitsuba's film crop: a window of the image, offsets from its top left corner.
fn film_crop(film: &Element, width: u32, height: u32) -> Result<Option<Tile>, SceneError> {
    let read = |name: &str, default: u32| -> Result<u32, SceneError> {
        let value = integer(film, name)?.unwrap_or(i64::from(default));
        let range = format!("{name} is {value}, but must be 0 to {}", u32::MAX);
        u32::try_from(value).map_err(|_| film.error(range))
    };
    let (x0, y0) = (read("crop_offset_x", 0)?, read("crop_offset_y", 0)?);
    let (w, h) = (read("crop_width", width)?, read("crop_height", height)?);
    let (x1, y1) = (x0.saturating_add(w), y0.saturating_add(h));
    if w == 0 || h == 0 || x1 > width || y1 > height {
        return Err(film.error(format!(
            "the crop {w} × {h} at ({x0}, {y0}) does not lie within the {width} × {height} film"
        )));
    }
    let whole = (x0, y0, x1, y1) == (0, 0, width, height);
    Ok((!whole).then_some(Tile { x0, y0, x1, y1 }))
}

/// `hdrfilm`: the image size, the reconstruction filter and the crop window.
pub(super) fn film(film: &Element, warnings: &mut Vec<String>) -> Result<Film, SceneError> {
    let kind = film.required("type")?;
    if kind != "hdrfilm" {
        let kind = crate::excerpt::excerpt(kind);
        return Err(film.error(format!("the film type '{kind}' is not supported (hdrfilm is)")));
    }
    refuse_unread(film, "the hdrfilm film", &FILM_PARAMETERS, &["rfilter"])?;
    for (name, values) in FILM_CHOICES {
        let Some(choice) = film.children.iter().find(|c| c.attr("name") == Some(name)) else {
            continue;
        };
        let value = match choice.tag.as_str() {
            "string" => choice.required("value")?.to_lowercase(),
            _ => return Err(choice.error(format!("`{name}` must be a <string>"))),
        };
        if !values.contains(&value.as_str()) {
            let known = values.join(", ");
            return Err(choice.error(format!("{name} must be one of {known}")));
        }
    }
    boolean(film, "sample_border")?;
    boolean(film, "compensate")?;
    refuse_second(film, "rfilter", "a film")?;
    let size = |name: &str, default: i64| -> Result<u32, SceneError> {
        let value = integer(film, name)?.unwrap_or(default);
        let max = i64::from(crate::limits::MAX_RESOLUTION);
        if !(1..=max).contains(&value) {
            return Err(film.error(format!("{name} is {value}, but must be 1 to {max}")));
        }
        Ok(value as u32)
    };
    let (width, height) = (size("width", 768)?, size("height", 576)?);
    let crop = film_crop(film, width, height)?;
    let filter = film.children.iter().find(|c| c.tag == "rfilter");
    let filter_type = filter.map_or(Ok("gaussian"), |f| f.required("type"))?;
    let parameter = |name: &str, default: f64| -> Result<f32, SceneError> {
        let value = filter.map_or(Ok(None), |f| float(f, name))?.unwrap_or(default);
        if !FILTER_SIZES.contains(&value) {
            let at = filter.unwrap_or(film);
            let value = crate::excerpt::short_number(value.to_string());
            let range = crate::sampling::filter::filter_sizes_text();
            return Err(at.error(format!("{name} is {value}, but must be {range}")));
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
    // Each filter's own parameters, and no other (Mitsuba refuses what it does not read).
    // (An unsupported filter is warned about below, its parameters unread.)
    let takes: Option<&[&str]> = match filter_type {
        "gaussian" => Some(&["stddev"]),
        "tent" => Some(&["radius"]),
        "mitchell" => Some(&["B", "C"]),
        "lanczos" => Some(&["lobes"]),
        "box" | "catmullrom" => Some(&[]),
        _ => None,
    };
    let unread = |takes: &[&str], c: &Element| !takes.contains(&c.attr("name").unwrap_or(""));
    if let (Some(filter), Some(takes)) = (filter, takes)
        && let Some(other) = filter.children.iter().find(|c| unread(takes, c))
    {
        let known = if takes.is_empty() { "none".to_owned() } else { takes.join(", ") };
        return Err(other.error(format!(
            "the {filter_type} filter does not take it (its parameters: {known})"
        )));
    }
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
    if let Some(problem) = pixel_filter.problem() {
        return Err(filter.unwrap_or(film).error(problem));
    }
    Ok(Film { width, height, filter: pixel_filter, crop })
}
