//! `<VertexData>` and `<TexCoordData>`: the scene's shared vertex and texture-coordinate
//! lists, read as tuples of numbers with the line of any bad one.

use super::xml::Xml;
use crate::scene::error::SceneError;
use glam::{DVec3, Vec2};
use roxmltree::Node;

/// The numbers of every list element in `lists`, in order, in tuples of `N` (`what` names
/// the data and `tuple` one tuple, for messages).
fn number_tuples<'a, 'i: 'a, const N: usize>(
    x: &Xml,
    lists: impl Iterator<Item = Node<'a, 'i>>,
    what: &str,
    tuple: &str,
) -> Result<Vec<[f64; N]>, SceneError> {
    let mut out = Vec::new();
    for node in lists {
        if node.attribute("binaryFile").is_some() {
            return Err(
                x.error(node, format!("{what} from a binary file (binaryFile) cannot be read"))
            );
        }
        let values = x.floats(node)?;
        if values.len() % N != 0 {
            let message = format!("{} numbers is not a whole number of {tuple}", values.len());
            return Err(x.error(node, message));
        }
        out.extend(values.chunks_exact(N).map(|v| std::array::from_fn(|i| v[i])));
    }
    Ok(out)
}

/// The scene's vertex list (its `<VertexData>`).
pub(super) fn vertex_data<'a, 'i: 'a>(
    x: &Xml,
    lists: impl Iterator<Item = Node<'a, 'i>>,
) -> Result<Vec<DVec3>, SceneError> {
    let tuples = number_tuples::<3>(x, lists, "vertex data", "x y z vertices")?;
    Ok(tuples.into_iter().map(DVec3::from_array).collect())
}

/// The scene's texture coordinates (u v per vertex).
pub(super) fn texcoord_data<'a, 'i: 'a>(
    x: &Xml,
    lists: impl Iterator<Item = Node<'a, 'i>>,
) -> Result<Vec<Vec2>, SceneError> {
    let tuples = number_tuples::<2>(x, lists, "texture coordinates", "u v pairs")?;
    Ok(tuples.into_iter().map(|[u, v]| Vec2::new(u as f32, v as f32)).collect())
}
