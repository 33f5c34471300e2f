//! Mitsuba's `sdfgrid` shape: a signed distance grid read from a one-channel `.vol` file,
//! over [0, 1]³ in object space, with `analytic` or `smooth` (the default) shading normals.
//! As in Mitsuba it cannot emit light (it has no area to sample) and has no texture
//! coordinates (a texture sees uv = (0, 0)).

use super::super::Builder;
use super::super::tree::Element;
use super::super::values::string;
use crate::scene::desc::{SdfGridData, SdfNormals, ShapeDesc};
use crate::scene::error::SceneError;
use crate::scene::formats::vol;
use glam::DAffine3;
use std::sync::Arc;

/// Grids larger than this many values are refused before any is read: 2³⁰ values are
/// 4 GiB of file, far beyond a grid one would ray trace voxel by voxel.
const MAX_VALUES: u64 = 1 << 30;

impl Builder<'_> {
    /// The grid of an `sdfgrid` element. `world_from_object` is its `to_world`.
    pub(in super::super) fn sdf_grid(
        &mut self,
        element: &Element,
        world_from_object: &DAffine3,
    ) -> Result<ShapeDesc, SceneError> {
        if let Some(emitter) = element.children.iter().find(|c| c.tag == "emitter") {
            return Err(emitter.error(
                "an sdfgrid cannot be an area emitter (as in Mitsuba: it has no area to sample)",
            ));
        }
        let normals = match string(element, "normals")? {
            None => SdfNormals::Smooth,
            Some(n) => match n.required("value")? {
                "smooth" => SdfNormals::Smooth,
                "analytic" => SdfNormals::Analytic,
                other => {
                    return Err(n.error(format!(
                        "normals is '{other}', but must be 'analytic' or 'smooth'"
                    )));
                }
            },
        };
        let file = string(element, "filename")?.ok_or_else(|| {
            element.error("an sdfgrid needs a `filename` (a .vol file; a `grid` tensor cannot be written in XML)")
        })?;
        let path = self.files.resolve(file.required("value")?);
        let bytes = crate::input_file::read_bytes(&path)
            .map_err(|e| file.error(format!("cannot read '{}': {e}", path.display())))?;
        let problem = |what: String| file.error(format!("'{}': {what}", path.display()));
        let grid = vol::parse(&bytes).map_err(problem)?;
        if grid.channels != 1 {
            return Err(problem(format!("{} channels, but an SDF grid has 1", grid.channels)));
        }
        let count = grid.size.iter().map(|&n| u64::from(n)).product::<u64>();
        if grid.size.iter().any(|&n| n < 2) || count > MAX_VALUES {
            let [x, y, z] = grid.size;
            return Err(problem(format!(
                "a grid of {x}×{y}×{z} values: each side needs at least 2 (one voxel) and the \
                 grid at most {MAX_VALUES} values"
            )));
        }
        if let Some(i) = grid.values.iter().position(|v| !v.is_finite()) {
            return Err(problem(format!("value {i} is {}, not a finite number", grid.values[i])));
        }
        let data = Arc::new(SdfGridData { resolution: grid.size, values: grid.values, normals });
        if crate::sdf_grid::SdfGrid::new(Arc::clone(&data)).is_none() {
            return Err(problem(
                "no voxel of the grid holds the surface (every value has the same sign)".into(),
            ));
        }
        let linear = world_from_object.matrix3;
        let scale = glam::DMat3::from_diagonal(glam::DVec3::new(
            linear.x_axis.length(),
            linear.y_axis.length(),
            linear.z_axis.length(),
        ));
        let rotated = (linear - scale).to_cols_array().iter().any(|d| d.abs() > 1e-6);
        if rotated {
            self.warnings.push(format!(
                "{} (line {}): its to_world rotates the grid; Mitsuba warns that it should not \
                 (its voxel boxes would not bound the surface: use an instance) — embray \
                 renders the rotated grid",
                element.describe(),
                element.line
            ));
        }
        Ok(ShapeDesc::SdfGrid(data))
    }
}
