//! The attributes each element of a Mitsuba file takes, as Mitsuba's parser checks them
//! (`check_attributes`): an attribute it would not read is refused, never dropped.

/// The attributes `tag` takes, or `None` for a tag the reader refuses on its own.
fn takes(tag: &str) -> Option<&'static [&'static str]> {
    Some(match tag {
        "scene" => &["version", "type", "id", "name"],
        "bsdf" | "shape" | "emitter" | "sensor" | "film" | "sampler" | "rfilter" | "texture"
        | "integrator" | "medium" | "phase" | "volume" => &["type", "id", "name"],
        "float" | "integer" | "boolean" | "string" | "rgb" | "color" => &["name", "value"],
        // A `<spectrum type=…>` is a plugin to Mitsuba: its type is judged where it is read.
        "spectrum" => &["name", "value", "filename", "type", "id"],
        "point" | "vector" => &["name", "value", "x", "y", "z"],
        "transform" => &["name"],
        "translate" | "scale" => &["value", "x", "y", "z"],
        "rotate" => &["value", "x", "y", "z", "angle"],
        "lookat" => &["origin", "target", "up"],
        "matrix" => &["value"],
        "ref" => &["id", "name"],
        "default" => &["name", "value"],
        "path" => &["value"],
        "include" => &["filename", "name"],
        "alias" => &["id", "as"],
        _ => return None,
    })
}

/// Why an element `<tag>` with the attributes `names` is refused, if one is not its.
pub(super) fn unread<'a>(tag: &str, mut names: impl Iterator<Item = &'a str>) -> Option<String> {
    let known = takes(tag)?;
    let name = names.find(|name| !known.contains(name))?;
    Some(format!(
        "<{tag}> does not take the attribute `{}` (it takes: {})",
        crate::excerpt::excerpt(name),
        known.join(", ")
    ))
}
