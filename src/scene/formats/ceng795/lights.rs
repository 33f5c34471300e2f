//! `<Lights>` → `LightDesc`s: AmbientLight (radiance added to every surface's ambient
//! reflectance), PointLight (Intensity, W/sr in the course's 0–255 units), AreaLight (a
//! square of edge `Size` at `Position` facing `Normal`, emitting `Radiance`; it lights the
//! scene but rays cannot hit it), DirectionalLight (`Direction`, and `Radiance`: the
//! irradiance on a surface facing it, no distance attenuation) and SpotLight (a point light
//! with `Direction`, `CoverageAngle` and `FalloffAngle` in degrees, full angles), and
//! SphericalDirectionalLight (an environment: the latitude-longitude image `ImageId`).

use super::textures::TextureMaps;
use super::xml::Xml;
use crate::excerpt::excerpt;
use crate::scene::desc::{EnvironmentMap, EnvironmentMapping, LightDesc, Spot, Point, Environment, Directional, Area, Ambient};
use crate::scene::error::SceneError;
use roxmltree::Node;

pub(super) fn lights<'a, 'i: 'a>(
    x: &Xml,
    lists: impl Iterator<Item = Node<'a, 'i>>,
    textures: &TextureMaps,
) -> Result<Vec<LightDesc>, SceneError> {
    let mut out = Vec::new();
    for list in lists {
        x.check_children(
            list,
            &[
                "AmbientLight",
                "PointLight",
                "AreaLight",
                "DirectionalLight",
                "SpotLight",
                "SphericalDirectionalLight",
            ],
        )?;
        for node in list.children().filter(Node::is_element) {
            out.push(match node.tag_name().name() {
                "SphericalDirectionalLight" => {
                    x.check_children(node, &["ImageId"])?;
                    if out.iter().any(|l| matches!(l, LightDesc::Environment(_))) {
                        return Err(x.error(node, "a scene takes one SphericalDirectionalLight"));
                    }
                    let mapping = match node.attribute("type").map(str::trim) {
                        None | Some("latlong") => EnvironmentMapping::LatLong,
                        Some("probe") => EnvironmentMapping::Probe,
                        Some(kind) => {
                            let message = format!(
                                "environment map type {} is not supported (expected latlong or \
                                 probe)",
                                excerpt(kind)
                            );
                            return Err(x.error(node, message));
                        }
                    };
                    let image = textures.radiance_map(x, x.required(node, "ImageId")?)?;
                    LightDesc::Environment(Environment {
                        map: EnvironmentMap::Image(image),
                        scale: glam::Vec3::ONE,
                        mapping,
                    })
                }
                "AmbientLight" => LightDesc::Ambient(Ambient { radiance: x.color(node)? }),
                "PointLight" => {
                    x.check_children(node, &["Position", "Intensity"])?;
                    LightDesc::Point(Point {
                        position: x.vec3(x.required(node, "Position")?)?,
                        intensity: x.color(x.required(node, "Intensity")?)?,
                    })
                }
                "DirectionalLight" => {
                    x.check_children(node, &["Direction", "Radiance"])?;
                    LightDesc::Directional(Directional {
                        direction: direction(x, x.required(node, "Direction")?)?,
                        irradiance: x.color(x.required(node, "Radiance")?)?,
                    })
                }
                "SpotLight" => {
                    let children =
                        ["Position", "Direction", "Intensity", "CoverageAngle", "FalloffAngle"];
                    x.check_children(node, &children)?;
                    let coverage_node = x.required(node, "CoverageAngle")?;
                    let coverage = x.scalar(coverage_node)?;
                    if !(coverage > 0.0 && coverage <= 360.0) {
                        return Err(x.out_of_range(coverage_node, coverage, "degrees in (0, 360]"));
                    }
                    let falloff_node = x.required(node, "FalloffAngle")?;
                    let falloff = x.scalar(falloff_node)?;
                    if !(falloff >= 0.0 && falloff <= coverage) {
                        let requirement = "degrees in [0, CoverageAngle]";
                        return Err(x.out_of_range(falloff_node, falloff, requirement));
                    }
                    LightDesc::Spot(Spot {
                        position: x.vec3(x.required(node, "Position")?)?,
                        direction: direction(x, x.required(node, "Direction")?)?,
                        intensity: x.color(x.required(node, "Intensity")?)?,
                        coverage_degrees: coverage,
                        falloff_degrees: falloff,
                    })
                }
                _ => {
                    x.check_children(node, &["Position", "Normal", "Size", "Radiance"])?;
                    let normal = direction(x, x.required(node, "Normal")?)?;
                    let size_node = x.required(node, "Size")?;
                    let size = x.scalar(size_node)?;
                    if !(size > 0.0) {
                        return Err(x.out_of_range(size_node, size, "> 0"));
                    }
                    LightDesc::Area(Area {
                        center: x.vec3(x.required(node, "Position")?)?,
                        normal,
                        size,
                        radiance: x.color(x.required(node, "Radiance")?)?,
                    })
                }
            });
        }
    }
    Ok(out)
}

/// A unit direction from a `Direction` element (refused when zero).
fn direction(x: &Xml, node: Node) -> Result<glam::DVec3, SceneError> {
    x.vec3(node)?.try_normalize().ok_or_else(|| x.out_of_range(node, "0 0 0", "a non-zero vector"))
}
