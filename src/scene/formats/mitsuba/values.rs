//! Mitsuba 3 property elements (`<float name=… value=…>`, `<rgb>`, `<point>`, …) read into
//! values, and a plugin's properties as the `Params` a kind reads (each named by its
//! element and line).

pub(super) use super::scalars::{ColorUse, number_attr, numbers, vec3};
use super::spectrum;
use super::tree::Element;
use crate::params::{Entry, Params, Value};
use crate::scene::error::SceneError;
use glam::DVec3;

/// The tags of property elements (everything else in a plugin is a nested object).
pub(super) const PROPERTY_TAGS: [&str; 9] =
    ["integer", "float", "boolean", "string", "point", "vector", "rgb", "spectrum", "color"];

/// The RGB of an `<rgb>`, `<spectrum>`, `<float>` or `<integer>` element: Mitsuba makes a
/// number a constant grey, for a reflectance and for emission alike (its `uniform` or
/// `srgb` texture).
pub(super) fn color(element: &Element, usage: ColorUse) -> Result<DVec3, SceneError> {
    f32_sized(element, color_of_any_size(element, usage)?)
}

/// `value`, refused if a component would not fit an f32: colours and textures are kept as
/// f32, where a larger value becomes infinite (and the render NaN).
pub(super) fn f32_sized(element: &Element, value: DVec3) -> Result<DVec3, SceneError> {
    match value.to_array().into_iter().find(|&c| !(c as f32).is_finite()) {
        Some(c) => {
            let name = crate::excerpt::excerpt(element.attr("name").unwrap_or("the value"));
            Err(element
                .error(format!("`{name}` is {c:e}, but must be within f32's range (±3.4e38)")))
        }
        None => Ok(value),
    }
}

fn color_of_any_size(element: &Element, usage: ColorUse) -> Result<DVec3, SceneError> {
    match element.tag.as_str() {
        "float" | "integer" => Ok(DVec3::splat(number_attr(element, "value")?)),
        "rgb" | "color" => {
            let text = element.required("value")?;
            match numbers(element, text)?[..] {
                [r, g, b] => Ok(DVec3::new(r, g, b)),
                [v] => Ok(DVec3::splat(v)),
                _ => Err(element.error("`value` must be one or three numbers")),
            }
        }
        "spectrum" => spectrum::to_rgb(element, usage),
        "texture" | "ref" => Err(element.error(format!(
            "a textured `{}` is not supported here",
            crate::excerpt::excerpt(element.attr("name").unwrap_or("colour"))
        ))),
        other => {
            let name = element.attr("name").unwrap_or("the colour");
            Err(element.error(format!(
                "`{}` must be a colour (an <rgb>, <spectrum> or <float>) or a <texture>, not a \
                 <{other}>",
                crate::excerpt::excerpt(name)
            )))
        }
    }
}

/// The property child `name` of `plugin` with tag `tag`.
pub(super) fn property<'a>(plugin: &'a Element, tag: &str, name: &str) -> Option<&'a Element> {
    plugin.children.iter().find(|c| c.tag == tag && c.attr("name") == Some(name))
}

pub(super) fn float(plugin: &Element, name: &str) -> Result<Option<f64>, SceneError> {
    match plugin.children.iter().find(|c| c.attr("name") == Some(name)) {
        Some(child) if child.tag == "float" || child.tag == "integer" => {
            Ok(Some(number_attr(child, "value")?))
        }
        Some(child) => Err(child.error(format!("`{name}` must be a <float>"))),
        None => Ok(None),
    }
}

pub(super) fn integer(plugin: &Element, name: &str) -> Result<Option<i64>, SceneError> {
    if let Some(child) = plugin.children.iter().find(|c| c.attr("name") == Some(name))
        && !matches!(child.tag.as_str(), "integer" | "float")
    {
        return Err(child.error(format!("`{name}` must be an <integer>")));
    }
    let Some(value) = float(plugin, name)? else { return Ok(None) };
    if value.fract() != 0.0 || value.abs() > 1e15 {
        let child = plugin.children.iter().find(|c| c.attr("name") == Some(name)).unwrap();
        return Err(child.error(format!("`{name}` must be a whole number")));
    }
    Ok(Some(value as i64))
}

/// The `<string>` property `name`; another element under that name is refused, not
/// passed over.
pub(super) fn string<'a>(
    plugin: &'a Element,
    name: &str,
) -> Result<Option<&'a Element>, SceneError> {
    match plugin.children.iter().find(|c| c.attr("name") == Some(name)) {
        Some(found) if found.tag != "string" => {
            Err(found.error(format!("`{name}` must be a <string>")))
        }
        found => Ok(found),
    }
}

/// The `<boolean>` property `name` (`true` or `false` in any case, as Mitsuba reads them);
/// anything else is refused rather than read as false.
pub(super) fn boolean(plugin: &Element, name: &str) -> Result<Option<bool>, SceneError> {
    match plugin.children.iter().find(|c| c.attr("name") == Some(name)) {
        None => Ok(None),
        Some(child) => match property_value(child, ColorUse::Reflectance)? {
            Value::Bool(value) if child.tag == "boolean" => Ok(Some(value)),
            _ => Err(child.error(format!("`{name}` must be a <boolean> true or false"))),
        },
    }
}

/// Refuses a child of `plugin` that `label` (the plugin, as the message names it) does not
/// read, as Mitsuba refuses an unreferenced property: a child whose tag is not in `nested`
/// (nested objects, named or not) and whose name is not in `known`.
pub(super) fn refuse_unread(
    plugin: &Element,
    label: &str,
    known: &[&str],
    nested: &[&str],
) -> Result<(), SceneError> {
    for child in plugin.children.iter().filter(|c| !nested.contains(&c.tag.as_str())) {
        match child.attr("name") {
            Some(name) if !known.contains(&name) => {
                let takes = if known.is_empty() { "nothing".to_owned() } else { known.join(", ") };
                return Err(
                    child.error(format!("{label} does not take `{name}` (it takes: {takes})"))
                );
            }
            None => {
                return Err(child.error(format!("{label} does not take a <{}>", child.tag)));
            }
            _ => {}
        }
    }
    Ok(())
}

/// Refuses a second child `<tag>` of `parent` (`owner` names the parent in the message), as
/// Mitsuba refuses it: read one after another, the last would win unseen.
pub(super) fn refuse_second(parent: &Element, tag: &str, owner: &str) -> Result<(), SceneError> {
    match parent.children.iter().filter(|c| c.tag == tag).nth(1) {
        Some(second) => Err(second.error(format!("{owner} takes one <{tag}>"))),
        None => Ok(()),
    }
}

/// The value of a property element, as a kind reads it.
pub(super) fn property_value(element: &Element, usage: ColorUse) -> Result<Value, SceneError> {
    Ok(match element.tag.as_str() {
        "integer" | "float" => Value::Number(number_attr(element, "value")?),
        // As Mitsuba's parser compares them: ignoring case, not spaces.
        "boolean" => match element.required("value")? {
            v if v.eq_ignore_ascii_case("true") => Value::Bool(true),
            v if v.eq_ignore_ascii_case("false") => Value::Bool(false),
            other => {
                return Err(element
                    .error(format!("'{}' is not true or false", crate::excerpt::excerpt(other))));
            }
        },
        "string" => Value::Text(element.required("value")?.to_owned()),
        "point" | "vector" => Value::Numbers(vec3(element, None)?.to_array().to_vec()),
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
    // Any other child is one the plugin reads itself (named in `skip`) or its placement;
    // else it would be dropped unseen (a textured radiance, say).
    for child in plugin.children.iter().filter(|c| !PROPERTY_TAGS.contains(&c.tag.as_str())) {
        let name = child.attr("name");
        let read = match child.tag.as_str() {
            "transform" => name == Some("to_world"),
            _ => name.is_some_and(|name| skip.contains(&name)),
        };
        if !read {
            let named = name.map_or(String::new(), |name| format!(" named `{name}`"));
            let tag = &child.tag;
            return Err(
                child.error(format!("{} does not take a <{tag}>{named}", plugin.describe()))
            );
        }
    }
    Ok(Params::new(plugin.describe(), Some(plugin.line), entries))
}
