//! `<Lights>` → `LightDesc`s: AmbientLight (radiance added to every surface's ambient
//! reflectance), PointLight (Intensity, W/sr in the course's 0–255 units), AreaLight (a
//! square of edge `Size` at `Position` facing `Normal`, emitting `Radiance`; it lights the
//! scene but rays cannot hit it), DirectionalLight (`Direction`, and `Radiance`: the
//! irradiance on a surface facing it, no distance attenuation) and SpotLight (a point light
//! with `Direction`, `CoverageAngle` and `FalloffAngle` in degrees, full angles), and
//! SphericalDirectionalLight (an environment: the latitude-longitude image `ImageId`).

use super::textures::TextureMaps;
use super::xml::Xml;
use super::xml::describe;
use crate::excerpt::excerpt;
use crate::params::{Entry, ParamError, Params, Resources, Value};
use crate::scene::desc::{Environment, EnvironmentMap, EnvironmentMapping, LightDesc};
use crate::scene::error::SceneError;
use crate::texels::TextureImage;
use roxmltree::Node;
use std::sync::Arc;

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
                        world_from_map: glam::DMat3::IDENTITY,
                        lookup: Default::default(),
                    })
                }
                "AmbientLight" => course_light(x, node, "ambient", &[(".", "radiance")])?,
                "PointLight" => course_light(x, node, "point", POINT)?,
                "DirectionalLight" => course_light(x, node, "directional", DIRECTIONAL)?,
                "SpotLight" => course_light(x, node, "spot", SPOT)?,
                _ => course_light(x, node, "area", AREA)?,
            });
        }
    }
    Ok(out)
}

/// The course's names of each kind's parameters (the kind's own name second).
const POINT: &[(&str, &str)] = &[("Position", "position"), ("Intensity", "intensity")];
const DIRECTIONAL: &[(&str, &str)] = &[("Direction", "direction"), ("Radiance", "irradiance")];
const SPOT: &[(&str, &str)] = &[
    ("Position", "position"),
    ("Direction", "direction"),
    ("Intensity", "intensity"),
    ("CoverageAngle", "coverage_angle"),
    ("FalloffAngle", "falloff_angle"),
];
const AREA: &[(&str, &str)] =
    &[("Position", "center"), ("Normal", "normal"), ("Size", "size"), ("Radiance", "radiance")];

/// The light of kind `kind` from the child elements of `node` named in `names` (`.`: the
/// element's own text).
fn course_light(
    x: &Xml,
    node: Node,
    kind: &str,
    names: &'static [(&'static str, &'static str)],
) -> Result<LightDesc, SceneError> {
    let children: Vec<&str> =
        names.iter().map(|(course, _)| *course).filter(|c| *c != ".").collect();
    x.check_children(node, &children)?;
    let mut entries = Vec::new();
    for (course, name) in names {
        let element = if *course == "." { Some(node) } else { x.child(node, course)? };
        if let Some(element) = element {
            entries.push(Entry {
                name: (*name).to_owned(),
                value: Value::Numbers(x.floats(element)?),
                field: describe(element),
                line: x.line(element).0,
                indexed: false,
            });
        }
    }
    let params = Params::new(describe(node), x.line(node).0, entries).with_renames(names);
    let read = LightDesc::read(kind, &params, &NoFiles).expect("a kind of light");
    read.map_err(|e| SceneError::from_param(x.file, e))
}

/// Course lights name no files (the environment's image is a texture, looked up by id).
struct NoFiles;

impl Resources for NoFiles {
    fn radiance_image(
        &self,
        p: &Params,
        name: &str,
        _: bool,
    ) -> Result<Arc<TextureImage>, ParamError> {
        Err(p.out_of_range(name, "given", "an image the course names by ImageId"))
    }
}
