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

    /// The values at the eight corners of voxel `v` (corner order as [`corner_offset`]).
    pub fn corners(&self, v: [u32; 3]) -> [f32; 8] {
        std::array::from_fn(|c| {
            let [ox, oy, oz] = corner_offset(c);
            self.value(i64::from(v[0] + ox), i64::from(v[1] + oy), i64::from(v[2] + oz))
        })
    }

    /// Whether `SdfGrid::new` would find a primitive, without allocating: the reader's
    /// check, made before the memory budget has counted what the grid will hold.
    pub fn has_surface(&self) -> bool {
        let [vx, vy, vz] = self.voxels();
        (0..vz)
            .any(|z| (0..vy).any(|y| (0..vx).any(|x| may_hold_surface(&self.corners([x, y, z])))))
    }

    /// How many primitives `SdfGrid::new` will make, without allocating: what the memory
    /// estimate counts (a closed surface holds a few voxels in a hundred, not all of them).
    pub fn surface_voxels(&self) -> u64 {
        let [vx, vy, vz] = self.voxels();
        let holds = |x, y, z| may_hold_surface(&self.corners([x, y, z]));
        let in_row = |y, z| (0..vx).filter(|&x| holds(x, y, z)).count() as u64;
        (0..vz).map(|z| (0..vy).map(|y| in_row(y, z)).sum::<u64>()).sum()
    }
}

/// Corner `c` of a voxel is at offset (c & 1, c >> 1 & 1, c >> 2 & 1).
pub fn corner_offset(c: usize) -> [u32; 3] {
    [(c & 1) as u32, (c >> 1 & 1) as u32, (c >> 2 & 1) as u32]
}

/// Whether a voxel with corner values `f` may hold the surface: its corners are not all
/// of one strict sign. The one criterion for a primitive.
pub fn may_hold_surface(f: &[f32; 8]) -> bool {
    !(f.iter().all(|&v| v > 0.0) || f.iter().all(|&v| v < 0.0))
}
