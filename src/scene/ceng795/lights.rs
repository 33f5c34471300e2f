//! `<Lights>` → `LightDesc`s: AmbientLight (radiance added to every surface's ambient
//! reflectance), PointLight (Intensity, W/sr in the course's 0–255 units) and AreaLight (a
//! square of edge `Size` at `Position` facing `Normal`, emitting `Radiance`; it lights the
//! scene but rays cannot hit it).

use super::xml::Xml;
use crate::scene::desc::LightDesc;
use crate::scene::error::SceneError;
use roxmltree::Node;

pub(super) fn lights<'a, 'i: 'a>(
    x: &Xml,
    lists: impl Iterator<Item = Node<'a, 'i>>,
) -> Result<Vec<LightDesc>, SceneError> {
    let mut out = Vec::new();
    for list in lists {
        x.check_children(list, &["AmbientLight", "PointLight", "AreaLight"])?;
        for node in list.children().filter(Node::is_element) {
            out.push(match node.tag_name().name() {
                "AmbientLight" => LightDesc::Ambient { radiance: x.color(node)? },
                "PointLight" => {
                    x.check_children(node, &["Position", "Intensity"])?;
                    LightDesc::Point {
                        position: x.vec3(x.required(node, "Position")?)?,
                        intensity: x.color(x.required(node, "Intensity")?)?,
                    }
                }
                _ => {
                    x.check_children(node, &["Position", "Normal", "Size", "Radiance"])?;
                    let normal_node = x.required(node, "Normal")?;
                    let Some(normal) = x.vec3(normal_node)?.try_normalize() else {
                        return Err(x.out_of_range(normal_node, "0 0 0", "a non-zero vector"));
                    };
                    let size_node = x.required(node, "Size")?;
                    let size = x.scalar(size_node)?;
                    if !(size > 0.0) {
                        return Err(x.out_of_range(size_node, size, "> 0"));
                    }
                    LightDesc::Area {
                        center: x.vec3(x.required(node, "Position")?)?,
                        normal,
                        size,
                        radiance: x.color(x.required(node, "Radiance")?)?,
                    }
                }
            });
        }
    }
    Ok(out)
}
