//! A queue of rays in blocks of eight, each field a column of the block: the layout of a
//! packet of eight rays, so that a backend fills its packets (Embree's `RTCRay8`) a column
//! at a time rather than ray by ray. The batched path tracer queues a bounce's closest-hit
//! rays and its shadow rays so.

use crate::ray::Ray;
use glam::Vec3;

/// Rays per block.
pub const BLOCK: usize = 8;

/// Eight rays, field by field.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RayBlock {
    pub origin: [[f32; BLOCK]; 3],
    pub dir: [[f32; BLOCK]; 3],
    pub tmin: [f32; BLOCK],
    pub tmax: [f32; BLOCK],
    pub time: [f32; BLOCK],
}

impl RayBlock {
    /// Ray `j` of the block.
    #[inline]
    pub fn ray(&self, j: usize) -> Ray {
        let [ox, oy, oz] = &self.origin;
        let [dx, dy, dz] = &self.dir;
        Ray {
            origin: Vec3::new(ox[j], oy[j], oz[j]),
            dir: Vec3::new(dx[j], dy[j], dz[j]),
            tmin: self.tmin[j],
            tmax: self.tmax[j],
            time: self.time[j],
        }
    }

    /// Whether each ray passes [`Ray::is_valid`] (branch-free, so that it vectorises over
    /// the block's columns).
    #[inline]
    pub fn valid(&self) -> [bool; BLOCK] {
        std::array::from_fn(|j| self.ray(j).is_valid())
    }
}

/// Rays queued in blocks (see the module's comment). The spare lanes of the last block
/// hold whatever they held (rays queued earlier, or zeros): only `len` rays are queued.
#[derive(Clone, Debug, Default)]
pub struct RayColumns {
    blocks: Vec<RayBlock>,
    len: usize,
}

impl RayColumns {
    /// How many rays are queued.
    #[inline]
    pub fn len(&self) -> usize {
        self.len
    }

    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Empties the queue (its blocks are kept for reuse).
    pub fn clear(&mut self) {
        self.len = 0;
    }

    /// Queues `ray`.
    #[inline]
    pub fn push(&mut self, ray: &Ray) {
        let (b, j) = (self.len / BLOCK, self.len % BLOCK);
        if b == self.blocks.len() {
            self.blocks.push(RayBlock::default());
        }
        let block = &mut self.blocks[b];
        for axis in 0..3 {
            block.origin[axis][j] = ray.origin[axis];
            block.dir[axis][j] = ray.dir[axis];
        }
        block.tmin[j] = ray.tmin;
        block.tmax[j] = ray.tmax;
        block.time[j] = ray.time;
        self.len += 1;
    }

    /// The blocks holding the queued rays, the last possibly part full.
    #[inline]
    pub fn blocks(&self) -> &[RayBlock] {
        &self.blocks[..self.len.div_ceil(BLOCK)]
    }

    /// Ray `i` of the queue.
    ///
    /// # Panics
    /// If `i` is not below `len`.
    #[inline]
    pub fn ray(&self, i: usize) -> Ray {
        assert!(i < self.len, "ray {i} of {}", self.len);
        self.blocks[i / BLOCK].ray(i % BLOCK)
    }

    /// The queued rays, in order.
    pub fn iter(&self) -> impl Iterator<Item = Ray> + '_ {
        (0..self.len).map(|i| self.ray(i))
    }
}

/// A batch of rays, by index: a slice of them, or a queue of columns.
pub trait RayBatch {
    fn count(&self) -> usize;
    /// Ray `i` (below `count`).
    fn ray_at(&self, i: usize) -> Ray;
}

impl RayBatch for [Ray] {
    fn count(&self) -> usize {
        self.len()
    }

    fn ray_at(&self, i: usize) -> Ray {
        self[i]
    }
}

impl RayBatch for RayColumns {
    fn count(&self) -> usize {
        self.len
    }

    fn ray_at(&self, i: usize) -> Ray {
        self.ray(i)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(k: usize) -> Ray {
        let k = k as f32;
        Ray {
            origin: Vec3::new(k, -k, 2.0 * k),
            dir: Vec3::new(1.0, k, -0.5),
            tmin: 0.25 * k,
            tmax: 10.0 + k,
            time: 0.01 * k,
        }
    }

    /// Rays come back as they were queued, over several blocks and after a clear.
    #[test]
    fn rays_come_back_in_order() {
        let mut columns = RayColumns::default();
        for round in 0..2 {
            columns.clear();
            assert!(columns.is_empty());
            let n = 19 - 5 * round;
            for k in 0..n {
                columns.push(&ray(k + round));
            }
            assert_eq!(columns.len(), n);
            assert_eq!(columns.blocks().len(), n.div_ceil(BLOCK));
            let back: Vec<Ray> = columns.iter().collect();
            let expected: Vec<Ray> = (0..n).map(|k| ray(k + round)).collect();
            assert_eq!(back, expected, "round {round}");
        }
    }
}
