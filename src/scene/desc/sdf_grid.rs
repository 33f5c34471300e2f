//! A signed distance function sampled on a grid (Mitsuba's `sdfgrid`): values at the
//! corners of `resolution - 1` voxels per axis, spanning [0, 1]³ in object space.

/// How the shading normal is found at a hit on a grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SdfNormals {
    /// The gradient of the hit voxel's trilinear function (the geometric normal).
    Analytic,
    /// Hansson-Söderlund et al. 2022: the gradients of the eight voxels around the nearest
    /// grid corner, blended, so that shading is continuous across voxel faces.
    Smooth,
}

/// The grid's values, x fastest then y then z (as a Mitsuba `.vol` stores them).
#[derive(Clone, Debug, PartialEq)]
pub struct SdfGridData {
    /// Samples per axis (each at least 2).
    pub resolution: [u32; 3],
    pub values: Vec<f32>,
    pub normals: SdfNormals,
}

impl SdfGridData {
    /// The value at grid corner (`x`, `y`, `z`), each clamped into the grid (as a texture
    /// lookup with clamping would).
    pub fn value(&self, x: i64, y: i64, z: i64) -> f32 {
        let [nx, ny, nz] = self.resolution.map(i64::from);
        // `max` then `min`, not `clamp` (which panics if a side were 0): Embree's
        // callbacks read corners through this.
        let (x, y, z) = (x.max(0).min(nx - 1), y.max(0).min(ny - 1), z.max(0).min(nz - 1));
        // In range: the reader checked values.len() == nx·ny·nz.
        self.values.get((x + nx * (y + ny * z)) as usize).copied().unwrap_or(0.0)
    }

    /// Voxels per axis.
    pub fn voxels(&self) -> [u32; 3] {
        self.resolution.map(|n| n.saturating_sub(1))
    }
}
