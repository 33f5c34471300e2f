//! `<integrator>` (path, direct, ptracer, volpath, moment, aov): the render settings it asks
//! for, each integrator's own parameters read and any other refused.

use super::tree::Element;
use super::values::{boolean, integer, refuse_unread};
use crate::limits::MAX_DEPTH;
use crate::scene::desc::{IntegratorKind, RenderSettings};
use crate::scene::error::SceneError;

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
    refuse_unread(element, &format!("the {kind} integrator"), known, &["integrator"])?;
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
            if kind == "ptracer" {
                // Its splats lose the part of an edge pixel's filter beyond the image.
                settings.filter_edges = crate::sampling::filter::FilterEdges::Cut;
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
                0 => {
                    // Mitsuba traces no ray: black. embray's depth 0 still shows what the
                    // camera sees emitting, which hiding the emitters takes away.
                    settings.hide_emitters = true;
                    warnings.push(format!(
                        "{}: line {}: max_depth = 0: no light reaches the camera, the image is \
                         black (as Mitsuba renders it; embray's max depth 0 with hidden emitters)",
                        element.file.display(),
                        element.line
                    ));
                    0
                }
                depth if (1..=i64::from(MAX_DEPTH)).contains(&depth) => depth as u32 - 1,
                depth => {
                    return Err(element.error(format!(
                        "max_depth is {depth}, but must be -1 (no limit) or 0 to {MAX_DEPTH}"
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
        // 0 leaves one technique out: Mitsuba's image then lacks what only the other sees
        // (point lights without emitter samples, mirrors without BSDF samples), which
        // embray's estimator, both techniques MIS-weighted, does not render.
        if !(1..=max).contains(&count) {
            let why = match count {
                0 => " (embray samples both emitters and the BSDF at every hit)",
                _ => "",
            };
            return Err(element.error(format!("{name} is {count}, but must be 1 to {max}{why}")));
        }
        let (taken, as_taken) = match name {
            "emitter_samples" => (count, "one emitter sample"),
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
