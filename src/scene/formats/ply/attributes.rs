//! A PLY element's other properties grouped into mesh attributes as Mitsuba groups them:
//! `r g b` (or `red green blue`) is `{element}_color`, and consecutive properties
//! `{prefix}_{postfix}` whose postfixes run `x y z`, `r g b`, `0 1 2` or `1 2 3` (one or
//! three of them) are `{element}_{prefix}` (`{element}_{prefix}_color` for `r g b`).
//! Properties that fit no group are ignored, as Mitsuba ignores them.

use super::header::{Element, Kind};

/// An attribute and the element's properties it reads, in channel order.
pub(super) struct AttributeLayout {
    pub name: String,
    pub properties: Vec<usize>,
}

const POSTFIX_RUNS: [&str; 4] = ["xyzw", "rgba", "0123", "1234"];

/// The attributes of `element` (`kind` is `vertex` or `face`), skipping the properties
/// named in `reserved` (positions, normals, texture coordinates, the index list).
pub(super) fn attribute_layouts(
    element: &Element,
    kind: &str,
    reserved: &[&str],
) -> Vec<AttributeLayout> {
    let scalar = |name: &str| {
        element.find(name).filter(|&i| matches!(element.properties[i].kind, Kind::Scalar(_)))
    };
    let mut layouts = Vec::new();
    let colour = [["r", "g", "b"], ["red", "green", "blue"]]
        .into_iter()
        .find_map(|names| names.iter().map(|n| scalar(n)).collect::<Option<Vec<_>>>());
    if let Some(properties) = colour {
        layouts.push(AttributeLayout { name: format!("{kind}_color"), properties });
    }
    let skipped = |name: &str| {
        reserved.contains(&name)
            || ["r", "g", "b", "a", "red", "green", "blue", "alpha"].contains(&name)
    };
    // The run being read: its prefix, which postfix column, and its properties.
    let mut run: Option<(String, usize, Vec<usize>)> = None;
    // A set: a header may declare any number of properties (a linear scan was n²).
    let mut seen_prefixes: std::collections::HashSet<String> = Default::default();
    let flush = |run: &mut Option<(String, usize, Vec<usize>)>,
                 layouts: &mut Vec<AttributeLayout>,
                 seen: &mut std::collections::HashSet<String>| {
        if let Some((prefix, column, properties)) = run.take() {
            if matches!(properties.len(), 1 | 3) {
                let suffix = if column == 1 { "_color" } else { "" };
                layouts
                    .push(AttributeLayout { name: format!("{kind}_{prefix}{suffix}"), properties });
            }
            seen.insert(prefix);
        }
    };
    for (index, property) in element.properties.iter().enumerate() {
        let name = property.name.as_str();
        if skipped(name) || !matches!(property.kind, Kind::Scalar(_)) {
            flush(&mut run, &mut layouts, &mut seen_prefixes);
            continue;
        }
        let Some((prefix, postfix)) = name.rsplit_once('_') else {
            flush(&mut run, &mut layouts, &mut seen_prefixes);
            continue;
        };
        let mut postfix_chars = postfix.chars();
        let (Some(postfix), None) = (postfix_chars.next(), postfix_chars.next()) else {
            flush(&mut run, &mut layouts, &mut seen_prefixes);
            continue;
        };
        let continues = run.as_ref().is_some_and(|(p, column, properties)| {
            p == prefix && POSTFIX_RUNS[*column].chars().nth(properties.len()) == Some(postfix)
        });
        if continues {
            run.as_mut().unwrap().2.push(index);
            continue;
        }
        flush(&mut run, &mut layouts, &mut seen_prefixes);
        if seen_prefixes.contains(prefix) {
            continue;
        }
        if let Some(column) = POSTFIX_RUNS.iter().position(|r| r.starts_with(postfix)) {
            run = Some((prefix.to_owned(), column, vec![index]));
        }
    }
    flush(&mut run, &mut layouts, &mut seen_prefixes);
    layouts
}
