//! A signed distance grid as the backends and shading see it: in grid units (corner
//! `(i, j, k)` at point `(i, j, k)`, so every voxel is a unit cube), its voxels that may
//! hold the surface as primitives, each with a box around its part of the surface.
//!
//! Shading follows Mitsuba's `sdfgrid`: the geometric normal is the gradient of the hit
//! voxel's trilinear function; the smooth shading normal blends the gradients of the eight
//! voxels around the corner nearest the hit (Hansson-Söderlund, Evans and Akenine-Möller,
//! "Ray Tracing of Signed Distance Function Grids", JCGT 11(3), 2022).

use crate::scene::{SdfGridData, SdfNormals, corner_offset, may_hold_surface};
use glam::{IVec3, Vec3};
use std::sync::Arc;

/// How far (grid units) a voxel's box reaches beyond its surface's crossings: far above
/// the rounding of the crossings and of a box's faces, so no ray that meets the surface
/// misses its box; a ten-thousandth of a voxel costs nothing in culling.
const BOX_SLACK: f32 = 1e-4;

#[derive(Clone, Debug)]
pub struct SdfGrid {
    pub data: Arc<SdfGridData>,
    /// The voxel (its lowest corner) of each primitive.
    pub voxels: Vec<[u32; 3]>,
    /// Per primitive, a box (grid units) around the surface in its voxel: Hansson-Söderlund
    /// and Akenine-Möller's tight bounds (the surface's crossings of the voxel's edges),
    /// which a trilinear surface does not leave.
    pub boxes: Vec<(Vec3, Vec3)>,
}

impl SdfGrid {
    /// The grid's primitives: the voxels whose corners are not all of one strict sign.
    /// `None` if there is none (no surface to draw).
    pub fn new(data: Arc<SdfGridData>) -> Option<SdfGrid> {
        let [vx, vy, vz] = data.voxels();
        let (mut voxels, mut boxes) = (Vec::new(), Vec::new());
        for z in 0..vz {
            for y in 0..vy {
                for x in 0..vx {
                    let f = corners(&data, [x, y, z]);
                    if !may_hold_surface(&f) {
                        continue;
                    }
                    let (lo, hi) = tight_box(&f);
                    let at = Vec3::new(x as f32, y as f32, z as f32);
                    voxels.push([x, y, z]);
                    boxes.push((at + lo - BOX_SLACK, at + hi + BOX_SLACK));
                }
            }
        }
        (!voxels.is_empty()).then_some(SdfGrid { data, voxels, boxes })
    }

    /// The corner values of primitive `prim`'s voxel (zeros for an unknown primitive).
    pub fn prim_corners(&self, prim: u32) -> Option<([u32; 3], [f32; 8])> {
        let voxel = *self.voxels.get(prim as usize)?;
        Some((voxel, corners(&self.data, voxel)))
    }

    /// The extent of the grid in grid units, from the origin.
    pub fn extent(&self) -> Vec3 {
        Vec3::from_array(self.data.voxels().map(|n| n as f32))
    }

    /// The grid's trilinear interpolant at `q` (grid units), clamped into the grid as a
    /// texture lookup with clamping is.
    pub fn value_at(&self, q: Vec3) -> f32 {
        let top = self.extent();
        let q = q.clamp(Vec3::ZERO, top);
        // The lowest corner of the cell, kept one below the top so the cell exists.
        let cell = q.floor().min((top - 1.0).max(Vec3::ZERO));
        let local = q - cell;
        let c = cell.as_ivec3();
        let f = |dx, dy, dz| {
            self.data.value(i64::from(c.x + dx), i64::from(c.y + dy), i64::from(c.z + dz))
        };
        let lerp = |a: f32, b: f32, t: f32| a + (b - a) * t;
        let x00 = lerp(f(0, 0, 0), f(1, 0, 0), local.x);
        let x10 = lerp(f(0, 1, 0), f(1, 1, 0), local.x);
        let x01 = lerp(f(0, 0, 1), f(1, 0, 1), local.x);
        let x11 = lerp(f(0, 1, 1), f(1, 1, 1), local.x);
        lerp(lerp(x00, x10, local.y), lerp(x01, x11, local.y), local.z)
    }

    /// Mitsuba's gradient of voxel `v` at `q`: along each axis, the difference of the
    /// interpolant across the voxel's two faces, at `q`'s other coordinates. For `q` inside
    /// the voxel this is the gradient of its trilinear function.
    pub fn voxel_gradient(&self, q: Vec3, v: IVec3) -> Vec3 {
        let v = v.as_vec3();
        let across = |axis: usize| {
            let (mut near, mut far) = (q, q);
            near[axis] = v[axis];
            far[axis] = v[axis] + 1.0;
            self.value_at(far) - self.value_at(near)
        };
        Vec3::new(across(0), across(1), across(2))
    }

    /// The outward geometric normal (not unit) of primitive `prim` at `q`.
    pub fn geometric_normal(&self, prim: u32, q: Vec3) -> Vec3 {
        let voxel = self.voxels.get(prim as usize).copied().unwrap_or_default();
        let v = IVec3::from_array(voxel.map(|c| c as i32));
        let inside = q.clamp(v.as_vec3(), v.as_vec3() + 1.0);
        self.voxel_gradient(inside, v)
    }

    /// The shading normal (not unit; zero if none) at `q`, on primitive `prim`.
    pub fn shading_normal(&self, prim: u32, q: Vec3) -> Vec3 {
        match self.data.normals {
            SdfNormals::Analytic => self.geometric_normal(prim, q),
            SdfNormals::Smooth => self.smooth_normal(q),
        }
    }

    /// Hansson-Söderlund et al.'s smooth normal: the unit gradients of the eight voxels
    /// around the grid corner nearest `q`, weighted trilinearly by where `q` lies between
    /// those voxels' centres. Voxels below the grid are left out (their axis's weight goes
    /// to the other side), as in Mitsuba; so, as in Mitsuba, voxels beyond the top faces
    /// are not: their gradient across that face is zero (the clamped lookups' difference).
    /// A surface so near the grid's top face is rare, and Mitsuba draws it so.
    pub fn smooth_normal(&self, q: Vec3) -> Vec3 {
        // Into the grid first (as `value_at` clamps), so the corner indices below stay
        // small: a huge `q` would overflow i32 in `base + k`.
        let q = q.clamp(Vec3::ZERO, self.extent());
        let nearest = q.round().as_ivec3();
        let base = nearest - IVec3::ONE;
        // A voxel's gradient along an axis depends on its coordinate on that axis alone
        // (`voxel_gradient`: the interpolant on its two faces, at `q`'s other coordinates),
        // so three planes an axis serve all eight voxels: 9 lookups instead of 48.
        let planes: [[f32; 3]; 3] = std::array::from_fn(|axis| {
            std::array::from_fn(|k| {
                let mut at = q;
                at[axis] = (base[axis] + k as i32) as f32;
                self.value_at(at)
            })
        });
        let mut normals = [Vec3::ZERO; 8];
        let mut inside = [false; 8];
        for (c, (normal, inside)) in normals.iter_mut().zip(&mut inside).enumerate() {
            let o = corner_offset(c).map(|o| o as usize);
            let v = base + IVec3::from_array(o.map(|o| o as i32));
            *inside = v.cmpge(IVec3::ZERO).all();
            if *inside {
                let across = |axis: usize| planes[axis][o[axis] + 1] - planes[axis][o[axis]];
                *normal = Vec3::new(across(0), across(1), across(2)).normalize_or_zero();
            }
        }
        let mut w = q - nearest.as_vec3() + 0.5;
        for axis in 0..3 {
            let side = |high: usize| (0..8).filter(|c| (c >> axis & 1) == high).all(|c| !inside[c]);
            if side(0) {
                w[axis] = 1.0;
            }
            if side(1) {
                w[axis] = 0.0;
            }
        }
        (0..8)
            .map(|c| {
                let [ox, oy, oz] = corner_offset(c);
                let pick = |o: u32, t: f32| if o == 1 { t } else { 1.0 - t };
                normals[c] * pick(ox, w.x) * pick(oy, w.y) * pick(oz, w.z)
            })
            .sum()
    }
}

/// The values at the eight corners of voxel `v` (`SdfGridData::corners`).
pub fn corners(data: &SdfGridData, v: [u32; 3]) -> [f32; 8] {
    data.corners(v)
}

/// The box (voxel-local, within [0, 1]³) around the surface of a voxel with corner values
/// `f`: its corners where the value is zero and the crossings of its edges.
fn tight_box(f: &[f32; 8]) -> (Vec3, Vec3) {
    let (mut lo, mut hi) = (Vec3::ONE, Vec3::ZERO);
    for (c, &value) in f.iter().enumerate() {
        if value == 0.0 {
            let at = Vec3::from_array(corner_offset(c).map(|o| o as f32));
            (lo, hi) = (lo.min(at), hi.max(at));
        }
        for axis in 0..3 {
            let d = c | 1 << axis;
            if d == c || !(value * f[d] <= 0.0) || value == f[d] {
                continue;
            }
            let mut at = Vec3::from_array(corner_offset(c).map(|o| o as f32));
            at[axis] = value / (value - f[d]);
            (lo, hi) = (lo.min(at), hi.max(at));
        }
    }
    // A voxel whose corners are all zero (or NaN) keeps its whole box.
    if lo.cmpgt(hi).any() { (Vec3::ZERO, Vec3::ONE) } else { (lo, hi) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::splitmix::SplitMix64;

    /// A grid of `n`³ samples of `f` at the grid's corners (grid units).
    fn sampled(n: u32, normals: SdfNormals, f: impl Fn(Vec3) -> f32) -> SdfGrid {
        let mut values = Vec::new();
        for z in 0..n {
            for y in 0..n {
                for x in 0..n {
                    values.push(f(Vec3::new(x as f32, y as f32, z as f32)));
                }
            }
        }
        let data = SdfGridData { resolution: [n; 3], values, normals };
        SdfGrid::new(Arc::new(data)).unwrap()
    }

    /// `has_surface` agrees with `new`; a far or NaN point gets a finite smooth normal.
    #[test]
    fn has_surface_agrees_with_the_primitives_and_far_points_are_safe() {
        let flat = |v: f32| SdfGridData {
            resolution: [3, 2, 2],
            values: vec![v; 12],
            normals: SdfNormals::Smooth,
        };
        for data in [flat(1.0), flat(-1.0), flat(0.0)] {
            let built = SdfGrid::new(Arc::new(data.clone())).is_some();
            assert_eq!(data.has_surface(), built);
        }
        let mut one = flat(1.0);
        one.values[11] = -1.0;
        assert!(one.has_surface());
        let grid = sampled(6, SdfNormals::Smooth, |q| q.length() - 2.5);
        assert_eq!(grid.data.surface_voxels(), grid.voxels.len() as u64);
        assert!(grid.voxels.len() < 5 * 5 * 5, "{} of 125 voxels", grid.voxels.len());
        let grid = sampled(4, SdfNormals::Smooth, |q| q.x - 1.5);
        for q in [Vec3::splat(3e9), Vec3::splat(-3e9), Vec3::splat(f32::MAX), Vec3::NAN] {
            assert!(grid.smooth_normal(q).is_finite(), "{q}");
        }
    }

    /// On a linear field every voxel has the field's gradient, so both normals are it.
    #[test]
    fn a_plane_has_its_normal_everywhere() {
        let a = Vec3::new(0.3, -0.5, 0.8);
        let grid = sampled(6, SdfNormals::Smooth, |q| a.dot(q) - 1.2);
        let mut rng = SplitMix64(3);
        for _ in 0..200 {
            // Nearest corners below the top faces: voxels beyond them are kept (see
            // `smooth_normal`), with no gradient across the face.
            let q = rng.vec3(0.0, 4.49);
            let prim = rng.next_u64() as u32 % grid.voxels.len() as u32;
            let v = Vec3::from_array(grid.voxels[prim as usize].map(|c| c as f32));
            let q_in = v + (q - q.floor());
            for n in [grid.geometric_normal(prim, q_in), grid.smooth_normal(q)] {
                assert!((n.normalize() - a.normalize()).length() < 1e-4, "{n} at {q}");
            }
        }
    }

    /// The smooth normal's shared planes give each voxel's `voxel_gradient`, bit for bit.
    #[test]
    fn shared_planes_are_each_voxels_gradient() {
        let centre = Vec3::new(3.3, 4.1, 3.7);
        let grid = sampled(8, SdfNormals::Smooth, |q| (q - centre).length() - 2.2);
        let mut rng = SplitMix64(8);
        for _ in 0..300 {
            let q = rng.vec3(0.0, 7.0);
            let nearest = q.round().as_ivec3();
            let w = q - nearest.as_vec3() + 0.5;
            let mut expected = Vec3::ZERO;
            for c in 0..8 {
                let o = IVec3::from_array(corner_offset(c).map(|o| o as i32));
                let v = nearest - IVec3::ONE + o;
                let n = if v.cmpge(IVec3::ZERO).all() {
                    grid.voxel_gradient(q, v).normalize_or_zero()
                } else {
                    Vec3::ZERO
                };
                let weight = |axis: usize| if o[axis] == 1 { w[axis] } else { 1.0 - w[axis] };
                expected += n * weight(0) * weight(1) * weight(2);
            }
            // Only inside the grid's lower faces are the weights those above.
            if nearest.cmpge(IVec3::ONE).all() {
                assert_eq!(grid.smooth_normal(q), expected, "at {q}");
            }
        }
    }

    /// The smooth normal is continuous across voxel faces (the analytic one need not be).
    #[test]
    fn the_smooth_normal_is_continuous_across_voxels() {
        let centre = Vec3::splat(4.0);
        let grid = sampled(9, SdfNormals::Smooth, |q| (q - centre).length() - 2.7);
        let mut rng = SplitMix64(9);
        for _ in 0..200 {
            let mut q = rng.vec3(1.0, 7.0);
            let axis = (rng.next_u64() % 3) as usize;
            q[axis] = q[axis].round();
            let (mut below, mut above) = (q, q);
            below[axis] -= 1e-4;
            above[axis] += 1e-4;
            let (a, b) =
                (grid.smooth_normal(below).normalize(), grid.smooth_normal(above).normalize());
            assert!((a - b).length() < 2e-3, "{a} and {b} across {q}");
        }
    }

    /// Each primitive's box holds its voxel's surface: points on it, found exactly on
    /// random lines along each axis (the function is linear along them).
    #[test]
    fn boxes_hold_the_surface_of_their_voxels() {
        let centre = Vec3::new(3.2, 2.9, 3.5);
        let grid = sampled(7, SdfNormals::Analytic, |q| (q - centre).length() - 1.9);
        let mut rng = SplitMix64(4);
        let mut checked = 0;
        for (prim, &(lo, hi)) in grid.boxes.iter().enumerate() {
            let v = Vec3::from_array(grid.voxels[prim].map(|c| c as f32));
            for _ in 0..300 {
                let axis = (rng.next_u64() % 3) as usize;
                let mut near = v + rng.vec3(0.0, 1.0);
                near[axis] = v[axis];
                let mut far = near;
                far[axis] += 1.0;
                let (a, b) = (grid.value_at(near), grid.value_at(far));
                if a * b > 0.0 || a == b {
                    continue;
                }
                checked += 1;
                let q = near.lerp(far, a / (a - b));
                let inside = q.cmpge(lo - 1e-4).all() && q.cmple(hi + 1e-4).all();
                assert!(inside, "{q} outside {lo}..{hi}");
            }
        }
        assert!(checked > 1000, "{checked} points on the surface");
    }
}
