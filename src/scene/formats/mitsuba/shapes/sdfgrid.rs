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

/// Grids whose header declares more values than this are refused by `vol::parse` before
/// any is read or the file's length compared (a short file whose header claims more is
/// refused with this limit, not a length mismatch). A file that
/// held this many (4 GiB) would be refused first by the input cap (2 GiB, about 2²⁹
/// values); whether a grid the cap lets through fits the machine is the memory budget's
/// call (`crate::scene::budget`), made before the grid's voxels are built.
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
        let grid = vol::parse(&bytes, MAX_VALUES).map_err(problem)?;
        if grid.channels != 1 {
            return Err(problem(format!("{} channels, but an SDF grid has 1", grid.channels)));
        }
        if grid.size.iter().any(|&n| n < 2) {
            let [x, y, z] = grid.size;
            return Err(problem(format!(
                "a grid of {x}×{y}×{z} values: each side needs at least 2 (one voxel)"
            )));
        }
        if let Some(i) = grid.values.iter().position(|v| !v.is_finite()) {
            return Err(problem(format!("value {i} is {}, not a finite number", grid.values[i])));
        }
        let data = SdfGridData { resolution: grid.size, values: grid.values, normals };
        // Without building the voxels: the budget has not yet counted their memory.
        if !data.has_surface() {
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
        Ok(ShapeDesc::SdfGrid(Arc::new(data)))
    }
}
