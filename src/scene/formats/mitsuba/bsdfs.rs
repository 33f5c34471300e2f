//! `<bsdf>` → `MaterialDesc`: diffuse, twosided, conductor, roughconductor (GGX) and
//! dielectric, with Mitsuba's parameter names and defaults. Other BSDFs are refused with
//! their type, file and line: none is silently replaced.

use super::ior::{conductor_ior, dielectric_ior};
use super::tree::{Element, FileResolver};
use super::values::{ColorUse, color};
use super::values::{boolean, float, property};
use crate::scene::desc::{
    Interpolation, MaterialDesc, Pattern, Specular, TextureDesc, TextureMode,
};
use crate::scene::error::{Line, SceneError};
use crate::scene::texture_image::{ImageRef, load};
use glam::{DAffine3, DVec3, Vec3};

/// The BSDFs this reader knows, for messages.
pub(super) const SUPPORTED: &str = "diffuse, twosided, conductor, roughconductor, dielectric";

pub(super) fn bsdf(
    element: &Element,
    ids: &super::Ids,
    files: &FileResolver,
) -> Result<MaterialDesc, SceneError> {
    let kind = element.required("type")?;
    let name = element.attr("id").unwrap_or(kind).to_owned();
    let none = MaterialDesc { name, albedo: Vec3::ZERO, ..Default::default() };
    match kind {
        "twosided" => {
            let inner: Vec<&Element> =
                element.children.iter().filter(|c| c.tag == "bsdf" || c.tag == "ref").collect();
            match inner[..] {
                [one] => {
                    let inner = ids.bsdf(one)?;
                    Ok(MaterialDesc { name: none.name, ..bsdf(inner, ids, files)? })
                }
                _ => Err(element.error("twosided takes one nested <bsdf> (two are not supported)")),
            }
        }
        "diffuse" => {
            let mut material = MaterialDesc { albedo: Vec3::splat(0.5), ..none };
            check_properties(element, &["reflectance"])?;
            if let Some(texture) = reflectance_texture(element, "reflectance", ids, files)? {
                material.texture = Some(texture);
            } else if let Some(rgb) = reflectance(element, "reflectance")? {
                material.albedo = rgb;
            }
            Ok(material)
        }
        "conductor" | "roughconductor" => {
            let mut known = vec!["material", "eta", "k", "specular_reflectance"];
            if kind == "roughconductor" {
                known.extend(["alpha", "alpha_u", "alpha_v", "distribution", "sample_visible"]);
            }
            check_properties(element, &known)?;
            let reflectance = reflectance(element, "specular_reflectance")?.unwrap_or(Vec3::ONE);
            let roughness = if kind == "roughconductor" { roughness(element)? } else { 0.0 };
            let named = property(element, "string", "material");
            let has_eta = element.children.iter().any(|c| c.attr("name") == Some("eta"));
            let named_none =
                named.map_or(Ok(true), |m| m.required("value").map(|v| v == "none"))?;
            if !has_eta && named_none {
                // Mitsuba's default material "none": a perfect mirror.
                let specular = Specular::Mirror { reflectance };
                return Ok(MaterialDesc { specular, roughness, ..none });
            }
            let (eta, k) = match element.children.iter().find(|c| c.attr("name") == Some("eta")) {
                Some(eta) => {
                    let k = element.children.iter().find(|c| c.attr("name") == Some("k"));
                    let k = k.map_or(Ok(DVec3::ZERO), |k| color(k, ColorUse::Unbounded))?;
                    (color(eta, ColorUse::Unbounded)?, k)
                }
                None => {
                    let name = property(element, "string", "material");
                    let value = name.map_or(Ok("none"), |m| m.required("value"))?;
                    conductor_ior(value).ok_or_else(|| {
                        let known: Vec<&str> = super::metals::names().collect();
                        name.unwrap_or(element).error(format!(
                            "the conductor material '{value}' is not known (known: {}; or give \
                             eta and k)",
                            known.join(", ")
                        ))
                    })?
                }
            };
            let specular = Specular::Conductor { eta: eta.as_vec3(), k: k.as_vec3(), reflectance };
            Ok(MaterialDesc { specular, roughness, ..none })
        }
        "dielectric" => {
            let known = ["int_ior", "ext_ior", "specular_reflectance", "specular_transmittance"];
            check_properties(element, &known)?;
            let ior = |name: &str, default: f64| -> Result<f64, SceneError> {
                match element.children.iter().find(|c| c.attr("name") == Some(name)) {
                    None => Ok(default),
                    Some(p) if p.tag == "float" => super::values::number_attr(p, "value"),
                    Some(p) => {
                        let value = p.required("value")?;
                        dielectric_ior(value).ok_or_else(|| {
                            p.error(format!("'{value}' is not a known index of refraction"))
                        })
                    }
                }
            };
            let (inside, outside) = (ior("int_ior", 1.5046)?, ior("ext_ior", 1.000277)?);
            if !(inside > 0.0 && outside > 0.0) {
                return Err(element.error("int_ior and ext_ior must be > 0"));
            }
            for name in ["specular_reflectance", "specular_transmittance"] {
                if reflectance(element, name)?.is_some_and(|r| r != Vec3::ONE) {
                    return Err(element.error(format!("{name} other than 1 is not supported")));
                }
            }
            let ior = (inside / outside) as f32;
            Ok(MaterialDesc {
                specular: Specular::Dielectric { ior, absorption: Vec3::ZERO },
                ..none
            })
        }
        other => Err(element
            .error(format!("the BSDF '{other}' is not supported yet (supported: {SUPPORTED})"))),
    }
}

/// Refuses a parameter (a property, a texture or a reference by `name`) the BSDF does not
/// read, so that nothing in the file is silently ignored.
fn check_properties(element: &Element, known: &[&str]) -> Result<(), SceneError> {
    for child in &element.children {
        if let Some(name) = child.attr("name") {
            if !known.contains(&name) {
                return Err(child.error(format!(
                    "{} does not take `{name}` (it takes: {})",
                    element.describe(),
                    known.join(", ")
                )));
            }
        } else if child.tag != "bsdf" || element.attr("type") != Some("twosided") {
            return Err(child.error(format!(
                "{} does not take a <{}>",
                element.describe(),
                child.tag
            )));
        }
    }
    Ok(())
}

/// GGX roughness `alpha` (default 0.1); Beckmann and anisotropic roughness are refused.
fn roughness(element: &Element) -> Result<f32, SceneError> {
    // Mitsuba's default distribution is Beckmann, not GGX.
    let name = match property(element, "string", "distribution") {
        Some(d) => d.required("value")?,
        None => "beckmann",
    };
    if name != "ggx" {
        let at = property(element, "string", "distribution").unwrap_or(element);
        return Err(at.error(format!(
            "the {name} distribution (Mitsuba's default when none is given) is not supported \
             yet: give <string name=\"distribution\" value=\"ggx\"/>"
        )));
    }
    if float(element, "alpha_u")?.is_some() || float(element, "alpha_v")?.is_some() {
        return Err(element.error("anisotropic roughness (alpha_u, alpha_v) is not supported"));
    }
    let alpha = float(element, "alpha")?.unwrap_or(0.1);
    if !(0.0..=1.0).contains(&alpha) {
        return Err(element.error(format!("alpha is {alpha}, but must be in [0, 1]")));
    }
    Ok(alpha as f32)
}

/// An `<rgb>`/`<spectrum>` reflectance named `name`, each component in [0, 1].
fn reflectance(element: &Element, name: &str) -> Result<Option<Vec3>, SceneError> {
    let found = element
        .children
        .iter()
        .find(|c| c.attr("name") == Some(name) && matches!(c.tag.as_str(), "rgb" | "spectrum"));
    let Some(found) = found else { return Ok(None) };
    let rgb = color(found, ColorUse::Reflectance)?;
    if !rgb.cmpge(DVec3::ZERO).all() || !rgb.cmple(DVec3::ONE).all() {
        return Err(found.error(format!("a reflectance must be in [0, 1], not {rgb}")));
    }
    Ok(Some(rgb.as_vec3()))
}

/// A `<texture name="…">` (bitmap or checkerboard) for the reflectance `name`.
fn reflectance_texture(
    element: &Element,
    name: &str,
    ids: &super::Ids,
    files: &FileResolver,
) -> Result<Option<TextureDesc>, SceneError> {
    let Some(texture) = element
        .children
        .iter()
        .find(|c| matches!(c.tag.as_str(), "texture" | "ref") && c.attr("name") == Some(name))
    else {
        return Ok(None);
    };
    let texture = ids.resolve(texture)?;
    if texture.tag != "texture" {
        return Err(texture.error(format!("`{name}` must be a colour or a <texture>")));
    }
    let pattern = match texture.required("type")? {
        "bitmap" => {
            let file = property(texture, "string", "filename")
                .ok_or_else(|| texture.error("a bitmap needs a filename"))?;
            let raw = boolean(texture, "raw")?.unwrap_or(false);
            let at = ImageRef {
                image: files.resolve(file.required("value")?),
                scene: &file.file,
                item: file.describe(),
                line: Line(Some(file.line)),
            };
            let image = load(&at, !raw)?;
            let normalizer = if image.srgb_decoded || image.hdr { 1.0 } else { 255.0 };
            let interpolation = match property(texture, "string", "filter_type") {
                Some(f) if f.required("value")? == "nearest" => Interpolation::Nearest,
                _ => Interpolation::Bilinear,
            };
            Pattern::Image { image, interpolation, normalizer }
        }
        "checkerboard" => {
            let color_of = |name: &str, default: f64| -> Result<Vec3, SceneError> {
                Ok(reflectance(texture, name)?.unwrap_or(Vec3::splat(default as f32)))
            };
            Pattern::Checker2d {
                scale: 2.0,
                even: color_of("color0", 0.4)?,
                odd: color_of("color1", 0.2)?,
            }
        }
        other => {
            return Err(texture.error(format!(
                "the texture '{other}' is not supported yet (bitmap and checkerboard are)"
            )));
        }
    };
    let pattern = match (property(texture, "transform", "to_uv"), pattern) {
        (None, pattern) => pattern,
        // A uniform scale of the texture coordinates: more checks.
        (Some(to_uv), Pattern::Checker2d { scale, even, odd }) => {
            let m = super::transform::transform(to_uv)?;
            let factor = m.matrix3.x_axis.x;
            let uniform = m.matrix3 == glam::DMat3::from_diagonal(DVec3::new(factor, factor, 1.0))
                || m.matrix3 == glam::DMat3::from_diagonal(DVec3::splat(factor));
            if !uniform || m.translation != DVec3::ZERO || !(factor > 0.0) {
                return Err(to_uv.error("to_uv other than a uniform scale is not supported yet"));
            }
            Pattern::Checker2d { scale: scale * factor as f32, even, odd }
        }
        (Some(to_uv), _) => return Err(to_uv.error("to_uv on a bitmap is not supported yet")),
    };
    Ok(Some(TextureDesc {
        pattern,
        mode: TextureMode::Replace,
        texture_from_object: DAffine3::IDENTITY,
    }))
}
