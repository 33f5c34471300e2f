//! Mitsuba 3 property elements (`<float name=… value=…>`, `<rgb>`, `<point>`, …) read into
//! values, and a plugin's properties as the `Params` a kind reads (each named by its
//! element and line).

use super::spectrum;
use super::tree::Element;
use crate::params::{Entry, Params, Value};
use crate::scene::error::SceneError;
use glam::DVec3;

/// The tags of property elements (everything else in a plugin is a nested object).
pub(super) const PROPERTY_TAGS: [&str; 9] =
    ["integer", "float", "boolean", "string", "point", "vector", "rgb", "spectrum", "color"];

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

/// A point or vector: `x`, `y`, `z` attributes (each 0 when absent) or `value="x, y, z"`
/// (one number for all three when `splat`).
pub(super) fn vec3(element: &Element, splat: bool) -> Result<DVec3, SceneError> {
    if let Some(text) = element.attr("value") {
        return match numbers(element, text)?[..] {
            [x, y, z] => Ok(DVec3::new(x, y, z)),
            [v] if splat => Ok(DVec3::splat(v)),
            _ => Err(element.error("`value` must be three numbers")),
        };
    }
    let coordinate = |name: &str| match element.attr(name) {
        Some(_) => number_attr(element, name),
        None => Ok(0.0),
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

/// The RGB of an `<rgb>` or `<spectrum>` element.
pub(super) fn color(element: &Element, usage: ColorUse) -> Result<DVec3, SceneError> {
    match element.tag.as_str() {
        "rgb" | "color" => {
            let text = element.required("value")?;
            match numbers(element, text)?[..] {
                [r, g, b] => Ok(DVec3::new(r, g, b)),
                [v] => Ok(DVec3::splat(v)),
                _ => Err(element.error("`value` must be one or three numbers")),
            }
        }
        "spectrum" => spectrum::to_rgb(element, usage),
        _ => Err(element.error("expected an <rgb> or <spectrum>")),
    }
}

/// The value of a property element, as a kind reads it.
pub(super) fn property_value(element: &Element, usage: ColorUse) -> Result<Value, SceneError> {
    Ok(match element.tag.as_str() {
        "integer" | "float" => Value::Number(number_attr(element, "value")?),
        "boolean" => match element.required("value")?.trim() {
            "true" => Value::Bool(true),
            "false" => Value::Bool(false),
            other => {
                return Err(element.error(format!("'{}' is not true or false", excerpt(other))));
            }
        },
        "string" => Value::Text(element.required("value")?.to_owned()),
        "point" | "vector" => Value::Numbers(vec3(element, false)?.to_array().to_vec()),
        "rgb" | "color" | "spectrum" => Value::Numbers(color(element, usage)?.to_array().to_vec()),
        _ => return Err(element.error("not a property")),
    })
}

/// The properties of `plugin` (its property children) as a kind's parameters; nested
/// objects and the properties named in `skip` are left to the caller.
pub(super) fn params(
    plugin: &Element,
    skip: &[&str],
    usage: ColorUse,
) -> Result<Params, SceneError> {
    let mut entries = Vec::new();
    for child in plugin.children.iter().filter(|c| PROPERTY_TAGS.contains(&c.tag.as_str())) {
        let name = child.required("name")?;
        if skip.contains(&name) {
            continue;
        }
        if entries.iter().any(|e: &Entry| e.name == name) {
            return Err(child.error(format!("the property `{name}` is given twice")));
        }
        entries.push(Entry {
            name: name.to_owned(),
            value: property_value(child, usage)?,
            field: child.describe(),
            line: Some(child.line),
            indexed: false,
        });
    }
    Ok(Params::new(plugin.describe(), Some(plugin.line), entries))
}
