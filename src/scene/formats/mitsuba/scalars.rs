//! Numbers in Mitsuba attributes (`value="1, 2, 3"`, `x=… y=… z=…`), and what a colour
//! stands for (Mitsuba converts spectra differently for each use).

use super::tree::Element;
use crate::scene::error::SceneError;
use glam::DVec3;

/// The numbers of `text`, separated by commas and/or whitespace.
pub(super) fn numbers(element: &Element, text: &str) -> Result<Vec<f64>, SceneError> {
    text.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .map(|token| {
            let value: f64 = token
                .parse()
                .map_err(|_| element.error(format!("'{}' is not a number", excerpt(token))))?;
            if value.is_finite() {
                Ok(value)
            } else {
                Err(element.error(format!("'{}' is not a finite number", excerpt(token))))
            }
        })
        .collect()
}

fn excerpt(text: &str) -> String {
    crate::excerpt::excerpt(text)
}

/// One number from the attribute `name`.
pub(super) fn number_attr(element: &Element, name: &str) -> Result<f64, SceneError> {
    match numbers(element, element.required(name)?)?[..] {
        [x] => Ok(x),
        _ => Err(element.error(format!("`{name}` must be one number"))),
    }
}

/// A point, vector or transform step: `x`, `y`, `z` attributes or `value="x, y, z"` (one
/// number for all three), as Mitsuba expands them. A coordinate left out is `missing`, or
/// refused when `missing` is `None` (a `<point>`/`<vector>` needs all three).
pub(super) fn vec3(element: &Element, missing: Option<f64>) -> Result<DVec3, SceneError> {
    if let Some(text) = element.attr("value") {
        // Mitsuba refuses the mix rather than letting one of them win.
        if let Some(axis) = ["x", "y", "z"].into_iter().find(|a| element.attr(a).is_some()) {
            return Err(element.error(format!("give `value` or `x`/`y`/`z`, not both (`{axis}`)")));
        }
        return match numbers(element, text)?[..] {
            [x, y, z] => Ok(DVec3::new(x, y, z)),
            [v] => Ok(DVec3::splat(v)),
            _ => Err(element.error("`value` must be one or three numbers")),
        };
    }
    let coordinate = |name: &str| match (element.attr(name), missing) {
        (Some(_), _) => number_attr(element, name),
        (None, Some(default)) => Ok(default),
        (None, None) => Err(element.error(format!("the attribute `{name}` is missing"))),
    };
    Ok(DVec3::new(coordinate("x")?, coordinate("y")?, coordinate("z")?))
}

/// What the colour of an `<rgb>` or `<spectrum>` stands for: Mitsuba converts a spectrum
/// differently for reflectances (bounded to [0, 1]) and for emission.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum ColorUse {
    Reflectance,
    Emission,
    /// Neither bounded nor emitted: a conductor's eta and k.
    Unbounded,
}
