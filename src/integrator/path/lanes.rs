//! Plain Lambertian bounces of many paths in structure-of-arrays form: queued lane by lane
//! (one column per scalar of a `LambertLane`), computed by one loop over all of them that
//! the compiler vectorises — built for the widest vector unit the CPU has, chosen at run
//! time (`pulp`: AVX-512, else AVX2, else the build's baseline), so one portable binary
//! uses all of it — and read back lane by lane.

use super::lambert::{FrameSpaces, LambertLane, LambertOutcome, lambert_bounce};
use glam::Vec3;

/// Flattens a lane record into `f32` columns and back: `Vec3` fields first, then scalars.
macro_rules! lane_columns {
    ($record:ident { $($vector:ident),* ; $($scalar:ident),* }) => {
        impl $record {
            /// Its number of `f32` columns.
            pub const COLUMNS: usize = 3 * [$(stringify!($vector)),*].len()
                + [$(stringify!($scalar)),*].len();

            #[inline(always)]
            fn to_columns(self) -> [f32; Self::COLUMNS] {
                let mut out = [0.0; Self::COLUMNS];
                let mut k = 0;
                $(
                    out[k..k + 3].copy_from_slice(&self.$vector.to_array());
                    k += 3;
                )*
                $(
                    out[k] = self.$scalar;
                    k += 1;
                )*
                debug_assert_eq!(k, Self::COLUMNS);
                out
            }

            #[inline(always)]
            fn from_columns(columns: [f32; Self::COLUMNS]) -> Self {
                let mut record = Self::default();
                let mut k = 0;
                $(
                    record.$vector = Vec3::new(columns[k], columns[k + 1], columns[k + 2]);
                    k += 3;
                )*
                $(
                    record.$scalar = columns[k];
                    k += 1;
                )*
                debug_assert_eq!(k, Self::COLUMNS);
                record
            }
        }
    };
}

lane_columns!(LambertLane {
    dir, point, error, normal, shading_normal, diffuse, throughput, light_point, light_error,
    light_normal, emission;
    eta_scale, has_light, light_pdf, light_visible, light_two_sided, u0, u1, u_survive, roulette
});

lane_columns!(LambertOutcome {
    shadow_origin, shadow_dir, contribution, next_origin, next_dir, throughput;
    shadow, next, pdf
});

const IN: usize = LambertLane::COLUMNS;
const OUT: usize = LambertOutcome::COLUMNS;

/// Lanes computed together: AVX-512's width (two AVX2 registers, four SSE ones).
const CHUNK: usize = 16;

/// The queue: columns of inputs and outputs, and the path each lane belongs to.
pub(crate) struct LambertLanes {
    inputs: [Vec<f32>; IN],
    outputs: [Vec<f32>; OUT],
    paths: Vec<u32>,
}

impl Default for LambertLanes {
    fn default() -> Self {
        LambertLanes {
            inputs: std::array::from_fn(|_| Vec::new()),
            outputs: std::array::from_fn(|_| Vec::new()),
            paths: Vec::new(),
        }
    }
}

impl LambertLanes {
    /// Empties the queue.
    pub fn clear(&mut self) {
        self.paths.clear();
    }

    /// Queues the bounce `lane` of path `path`.
    pub fn push(&mut self, path: u32, lane: &LambertLane) {
        let i = self.paths.len();
        self.paths.push(path);
        for (column, value) in self.inputs.iter_mut().zip(lane.to_columns()) {
            if column.len() <= i {
                column.resize(i + 1, 0.0);
            }
            column[i] = value;
        }
    }

    /// Computes every queued bounce.
    pub fn run(&mut self, spaces: &FrameSpaces) {
        let n = self.paths.len();
        for column in &mut self.outputs {
            if column.len() < n {
                column.resize(n, 0.0);
            }
        }
        let kernel = Kernel { spaces, inputs: &self.inputs, outputs: &mut self.outputs, n };
        pulp::Arch::new().dispatch(kernel);
    }

    /// The queued bounces' paths and outcomes, in the order they were queued (after `run`).
    pub fn outcomes(&self) -> impl Iterator<Item = (u32, LambertOutcome)> + '_ {
        self.paths.iter().enumerate().map(|(i, &path)| {
            (path, LambertOutcome::from_columns(std::array::from_fn(|k| self.outputs[k][i])))
        })
    }
}

/// The loop over the lanes, compiled once per instruction set `pulp` dispatches to.
struct Kernel<'a> {
    spaces: &'a FrameSpaces,
    inputs: &'a [Vec<f32>; IN],
    outputs: &'a mut [Vec<f32>; OUT],
    n: usize,
}

impl pulp::WithSimd for Kernel<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        // Chunks of lanes copied to and from local arrays: the compiler then knows that no
        // column aliases another (the columns themselves could, for all it can prove, and
        // checking 63 of them against each other at run time is more than it will do).
        let n = self.n;
        for start in (0..n).step_by(CHUNK) {
            let len = (n - start).min(CHUNK);
            let mut inputs = [[0.0f32; CHUNK]; IN];
            for (chunk, column) in inputs.iter_mut().zip(self.inputs) {
                chunk[..len].copy_from_slice(&column[start..start + len]);
            }
            let mut outputs = [[0.0f32; CHUNK]; OUT];
            for j in 0..CHUNK {
                let lane = LambertLane::from_columns(std::array::from_fn(|k| inputs[k][j]));
                let outcome = lambert_bounce(&lane, self.spaces).to_columns();
                for (chunk, value) in outputs.iter_mut().zip(outcome) {
                    chunk[j] = value;
                }
            }
            for (column, chunk) in self.outputs.iter_mut().zip(&outputs) {
                column[start..start + len].copy_from_slice(&chunk[..len]);
            }
        }
    }
}

#[cfg(test)]
#[path = "lanes_tests.rs"]
mod tests;
