//! Emitters outside shapes: point, directional, constant and envmap, read by embray's light
//! kinds from Mitsuba's parameters (the names agree; `to_world` placements are turned into
//! the position or direction they mean).

use super::Builder;
use super::transform::transform;
use super::tree::Element;
use super::values::{ColorUse, PROPERTY_TAGS, params};
use super::values::{boolean, float, property, refuse_unread};
use crate::light::LightDesc;
use crate::params::{Entry, ParamError, Params, Resources, Value};
use crate::scene::error::SceneError;
use crate::scene::texture_image::radiance_param;
use crate::texels::TextureImage;
use crate::transform::{is_orthonormal, nearest_rotation};
use glam::{DMat3, DVec3};
use std::sync::Arc;

impl Builder<'_> {
    pub(super) fn emitter(&mut self, element: &Element) -> Result<(), SceneError> {
        let kind = element.required("type")?;
        // What the emitter is decides first: its children are judged by its kind.
        const KINDS: [&str; 7] =
            ["point", "spot", "projector", "directional", "constant", "envmap", "area"];
        if kind == "area" {
            return Err(element.error("an area emitter belongs inside a <shape>"));
        }
        let unsupported = || {
            element.error(format!(
                "the emitter '{kind}' is not supported yet (point, spot, projector, \
                 directional, constant, envmap and area are)"
            ))
        };
        if !KINDS.contains(&kind) {
            return Err(unsupported());
        }
        // Mitsuba's names only: embray's own (`file`, `falloff_angle`, …) would otherwise
        // reach its light kinds unseen. `sampling_weight` and `mis_compensation` change how
        // Mitsuba samples, not what it renders: checked, and not used.
        // Each kind's parameters: those its embray light takes under the same name and
        // meaning (passed on as they are), those read here, and the one that is a colour.
        let (passed_on, read_here, colour): (&[&str], &[&str], _) = match kind {
            "point" => (&["position", "intensity"], &[], Some("intensity")),
            "directional" => (&["direction", "irradiance"], &[], Some("irradiance")),
            "spot" => {
                (&["intensity"], &["cutoff_angle", "beam_width", "texture"], Some("intensity"))
            }
            "projector" => (&[], &["irradiance", "scale", "fov", "fov_axis", "focal_length"], None),
            "constant" => (&["radiance"], &[], Some("radiance")),
            _ => (&[], &["filename", "scale", "mis_compensation"], None),
        };
        let known: Vec<&str> = passed_on
            .iter()
            .chain(read_here)
            .chain(&["to_world", "sampling_weight"])
            .copied()
            .collect();
        refuse_unread(element, &format!("the {kind} emitter"), &known, &[])?;
        boolean(element, "mis_compensation")?;
        float(element, "sampling_weight")?;
        let mut skip = read_here.to_vec();
        skip.extend(["mis_compensation", "sampling_weight"]);
        // A colour given as a number (or as what is no colour) is read as `color` reads it;
        // a texture there is left for `params` to refuse.
        let colour = colour.and_then(|name| {
            element
                .children
                .iter()
                .find(|c| c.attr("name") == Some(name) && PROPERTY_TAGS.contains(&c.tag.as_str()))
        });
        skip.extend(colour.and_then(|c| c.attr("name")));
        let mut p = params(element, &skip, ColorUse::Emission)?;
        if let Some(child) = colour {
            let rgb = super::values::color(child, ColorUse::Emission)?;
            p.push(Entry {
                name: child.required("name")?.to_owned(),
                value: Value::Numbers(rgb.to_array().to_vec()),
                field: child.describe(),
                line: Some(child.line),
                indexed: false,
            });
        }
        let to_world = match property(element, "transform", "to_world") {
            Some(t) => {
                let m = transform(t)?;
                let textured = element.children.iter().any(|c| c.attr("name") == Some("texture"));
                check_placement(kind, m.matrix3, t, textured)?;
                Some(m)
            }
            None => None,
        };
        let set = |p: &mut Params, name: &str, v: DVec3| {
            p.push(Entry {
                name: name.to_owned(),
                value: Value::Numbers(v.to_array().to_vec()),
                field: format!("{} > to_world", element.describe()),
                line: Some(element.line),
                indexed: false,
            })
        };
        let ours = match kind {
            "point" | "directional" => {
                let (placed, at) = match kind {
                    "point" => ("position", to_world.map(|m| m.translation)),
                    _ => ("direction", to_world.map(|m| m.transform_vector3(DVec3::Z))),
                };
                // Without either, Mitsuba places it by the identity: at the origin, along +z.
                let at = match (at, p.has(placed)) {
                    (None, false) => Some(if kind == "point" { DVec3::ZERO } else { DVec3::Z }),
                    _ => at,
                };
                match (at, p.has(placed)) {
                    (Some(_), true) => {
                        // As Mitsuba: one of them would be dropped unseen.
                        return Err(
                            element.error(format!("give `{placed}` or a to_world, not both"))
                        );
                    }
                    (Some(at), false) => set(&mut p, placed, at),
                    (None, _) => {}
                }
                // Mitsuba's default, as for a spot.
                let power = if kind == "point" { "intensity" } else { "irradiance" };
                if !p.has(power) {
                    set(&mut p, power, DVec3::ONE);
                }
                kind
            }
            "projector" => {
                // Without one, Mitsuba's identity: at the origin, along +z.
                let m = to_world.unwrap_or(glam::DAffine3::IDENTITY);
                let irradiance =
                    element.children.iter().find(|c| c.attr("name") == Some("irradiance"));
                let constant = match irradiance {
                    Some(c) if PROPERTY_TAGS.contains(&c.tag.as_str()) => {
                        let rgb = super::values::color(c, ColorUse::Emission)?;
                        if !rgb.cmpge(DVec3::ZERO).all() {
                            return Err(c.error(format!("irradiance is {rgb}, but must be >= 0")));
                        }
                        rgb
                    }
                    None => DVec3::ONE,
                    Some(_) => {
                        let file = bitmap_file(self, element, "irradiance")?;
                        p.push(derived(element, "image", Value::Text(file)));
                        DVec3::ONE
                    }
                };
                let aspect = match p.has("image") {
                    false => 1.0,
                    true => {
                        let files = Files { files: self.files, scene: &element.file };
                        let image = files
                            .radiance_image(&p, "image", true)
                            .map_err(|e| SceneError::from_param(&element.file, e))?;
                        image.width as f64 / image.height as f64
                    }
                };
                let fov = super::sensor::x_fov(element, aspect)?;
                // Mitsuba's irradiance is π·scale·image on the plane at distance 1.
                let scale = float(element, "scale")?.unwrap_or(1.0);
                if !(scale >= 0.0) {
                    let at = element.children.iter().find(|c| c.attr("name") == Some("scale"));
                    let at = at.unwrap_or(element);
                    return Err(at.error(format!("scale is {scale}, but must be >= 0")));
                }
                let scale = std::f64::consts::PI * scale * constant;
                set(&mut p, "position", m.translation);
                set(&mut p, "direction", m.transform_vector3(DVec3::Z));
                set(&mut p, "up", m.transform_vector3(DVec3::Y));
                p.push(derived(element, "fov", Value::Numbers(vec![fov])));
                p.push(derived(element, "scale", Value::Numbers(scale.to_array().to_vec())));
                "projector"
            }
            "spot" => {
                let m = to_world.unwrap_or(glam::DAffine3::IDENTITY);
                let (cutoff, beam) = spot_angles(element)?;
                set(&mut p, "position", m.translation);
                set(&mut p, "direction", m.transform_vector3(DVec3::Z));
                p.push(derived(element, "coverage_angle", Value::Numbers(vec![2.0 * cutoff])));
                p.push(derived(element, "falloff_angle", Value::Numbers(vec![2.0 * beam])));
                p.push(derived(element, "profile", Value::Text("linear".to_owned())));
                if !p.has("intensity") {
                    set(&mut p, "intensity", DVec3::ONE);
                }
                if element.children.iter().any(|c| c.attr("name") == Some("texture")) {
                    let file = bitmap_file(self, element, "texture")?;
                    p.push(derived(element, "texture", Value::Text(file)));
                    set(&mut p, "up", m.transform_vector3(DVec3::Y));
                }
                "spot"
            }
            "constant" => {
                if !p.has("radiance") {
                    set(&mut p, "radiance", DVec3::ONE);
                }
                "environment"
            }
            "envmap" => {
                let file = property(element, "string", "filename")
                    .ok_or_else(|| element.error("the property `filename` is missing"))?;
                p.push(derived(element, "file", Value::Text(file.required("value")?.to_owned())));
                if let Some(scale) = float(element, "scale")? {
                    p.push(derived(element, "scale", Value::Numbers(vec![scale; 3])));
                }
                let mut rotation = glam::DMat3::IDENTITY;
                if let (Some(m), Some(t)) = (to_world, property(element, "transform", "to_world")) {
                    // Checked before the half turn below, so that a message shows the user's
                    // matrix.
                    let m = m.matrix3;
                    rotation = nearest_rotation(m).ok_or_else(|| {
                        t.error(format!(
                            "an envmap's to_world must be a rotation (no scale, shear or \
                             mirror), not {}",
                            rows(m)
                        ))
                    })?;
                }
                // Mitsuba's map looks along +z at its centre, embray's along −z: half a
                // turn about y between them.
                let half_turn = glam::DMat3::from_diagonal(DVec3::new(-1.0, 1.0, -1.0));
                let world_from_map = rotation * half_turn;
                let rows = world_from_map.transpose().to_cols_array().to_vec();
                p.push(derived(element, "to_world", Value::Numbers(rows)));
                p.push(derived(element, "interpolation", Value::Text("bilinear_poles".to_owned())));
                "environment"
            }
            _ => return Err(unsupported()),
        };
        let files = Files { files: self.files, scene: &element.file };
        let light = LightDesc::read(ours, &p, &files)
            .expect("a kind of light")
            .map_err(|e| SceneError::from_param(&element.file, e))?;
        if light.one_per_scene() && self.lights.iter().any(|l| l.name() == light.name()) {
            let what = match light.name() {
                // As Mitsuba says it: envmap and constant are both the environment.
                "environment" => "environment emitter (envmap or constant)".to_owned(),
                _ => format!("{kind} emitter"),
            };
            return Err(element.error(format!("a scene takes one {what}, as in Mitsuba")));
        }
        self.lights.push(light);
        Ok(())
    }
}

/// Refuses a `to_world` whose placement embray's light of `kind` would not render as
/// Mitsuba does: a directional or projector one that scales (Mitsuba's irradiance scales
/// with the unnormalised axis), a spot one that stretches or shears (Mitsuba's cone would
/// stretch; a uniform scale changes nothing there), a mirror where an image is projected.
fn check_placement(kind: &str, m: DMat3, at: &Element, textured: bool) -> Result<(), SceneError> {
    let scale = m.determinant().abs().cbrt();
    let problem = match kind {
        "directional" | "projector" if !is_orthonormal(m) => Some(format!(
            "a {kind} emitter's to_world must not scale (or shear): Mitsuba uses its axis \
             unnormalised, so its irradiance would change with the scale"
        )),
        "spot" if !(scale > 0.0 && is_orthonormal(m / scale)) => Some(
            "a spot emitter's to_world may scale uniformly, but not non-uniformly or with \
             shear: Mitsuba would stretch its cone"
                .to_owned(),
        ),
        "spot" | "projector" if (textured || kind == "projector") && m.determinant() < 0.0 => {
            Some(format!(
                "a {kind} emitter's to_world mirrors: Mitsuba would project its image mirrored"
            ))
        }
        _ => None,
    };
    match problem {
        Some(problem) => Err(at.error(format!("{problem}; its matrix, row by row: {}", rows(m)))),
        None => Ok(()),
    }
}

/// A 3×3 matrix row by row, to 6 decimals.
fn rows(m: DMat3) -> String {
    let digits = m.transpose().to_cols_array().map(|x| (x * 1e6).round() / 1e6 + 0.0);
    digits.map(|x| x.to_string()).join(", ")
}

/// A spot emitter's `cutoff_angle` and `beam_width` in degrees. A beam wider than the
/// cutoff is the cutoff (Mitsuba's falloff is then full up to the cutoff); past a cutoff of
/// 180 Mitsuba's cone test wraps around, and an image is projected only within 90.
fn spot_angles(element: &Element) -> Result<(f64, f64), SceneError> {
    let cutoff = float(element, "cutoff_angle")?.unwrap_or(20.0);
    let beam = float(element, "beam_width")?.unwrap_or(0.75 * cutoff);
    let textured = element.children.iter().any(|c| c.attr("name") == Some("texture"));
    let cutoff_ok = cutoff > 0.0 && if textured { cutoff < 90.0 } else { cutoff <= 180.0 };
    if !(cutoff_ok && beam >= 0.0) {
        let texture = if textured { " (with a texture)" } else { "" };
        let bound = if textured { "< 90" } else { "<= 180" };
        return Err(element.error(format!(
            "cutoff_angle {cutoff} and beam_width {beam} must satisfy 0 < cutoff_angle \
             {bound}{texture} and beam_width >= 0"
        )));
    }
    Ok((cutoff, beam.min(cutoff)))
}

/// A parameter the reader derives from the element's own (a placement, a renamed angle).
fn derived(element: &Element, name: &str, value: Value) -> Entry {
    Entry {
        name: name.to_owned(),
        value,
        field: format!("{} > {name}", element.describe()),
        line: Some(element.line),
        indexed: false,
    }
}

/// The file of the bitmap texture `name` of an emitter (nothing else about the bitmap is
/// supported there).
fn bitmap_file(builder: &Builder, element: &Element, name: &str) -> Result<String, SceneError> {
    let texture = element
        .children
        .iter()
        .find(|c| c.attr("name") == Some(name))
        .ok_or_else(|| element.error(format!("the texture `{name}` is missing")))?;
    let texture = builder.ids.resolve(texture)?;
    if texture.tag != "texture" || texture.attr("type") != Some("bitmap") {
        return Err(texture.error(format!("`{name}` must be a bitmap texture")));
    }
    for child in &texture.children {
        if child.attr("name") != Some("filename") {
            return Err(child.error("only a bitmap's filename is supported here"));
        }
    }
    let file = property(texture, "string", "filename")
        .ok_or_else(|| texture.error("the property `filename` is missing"))?;
    Ok(file.required("value")?.to_owned())
}

/// Files named by an emitter, found where the scene finds its files.
struct Files<'a> {
    files: &'a super::tree::FileResolver,
    scene: &'a std::path::Path,
}

impl Resources for Files<'_> {
    fn radiance_image(
        &self,
        p: &Params,
        name: &str,
        srgb: bool,
    ) -> Result<Arc<TextureImage>, ParamError> {
        radiance_param(p, name, self.scene, |file| self.files.resolve(file), srgb)
    }
}
