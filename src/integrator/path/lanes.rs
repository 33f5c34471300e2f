//! Plain Lambertian bounces of many paths in structure-of-arrays form: queued lane by lane
//! into blocks of 16 lanes (one 16-wide column per scalar of a `LambertLane`), computed by
//! one loop over all of them that the compiler vectorises — built for the widest vector
//! unit the CPU has, chosen at run time (`pulp`: AVX-512, else AVX2, else the build's
//! baseline), so one portable binary uses all of it — and read back lane by lane.

use super::lambert::{FrameSpaces, LambertLane, LambertOutcome, LaneSink, lambert_bounce};
use super::lane_light::{with_hit_point, with_lone_light};
use crate::light::{AreaSampler, LoneEmitter};
use glam::Vec3;

/// Flattens a lane record into `f32` columns and back: `Vec3` fields first, then scalars,
/// each field at its place in the enum `$place` (listed in the same order).
macro_rules! lane_columns {
    ($record:ident, $place:ident { $($vector:ident),* ; $($scalar:ident),* }) => {
        /// Each field's place in the order `lane_columns` lays them out.
        #[allow(non_camel_case_types, dead_code)]
        #[derive(Clone, Copy)]
        enum $place {
            $($vector,)*
            $($scalar,)*
        }

        impl $place {
            const VECTORS: usize = [$(stringify!($vector)),*].len();
            const FIELDS: usize = Self::VECTORS + [$(stringify!($scalar)),*].len();

            /// Its bit in a set of fields (`write_at`'s `unwritten`).
            #[allow(dead_code)]
            const fn bit(self) -> u64 {
                1 << self as u64
            }

            /// Its (first) column: the vectors' come first, three each, then the scalars'.
            const fn column(self) -> usize {
                let place = self as usize;
                if place < Self::VECTORS { 3 * place } else { place + 2 * Self::VECTORS }
            }
        }

        // Every field has a bit.
        const _: () = assert!($place::FIELDS <= 64);

        impl $record {
            /// Its number of `f32` columns.
            pub const COLUMNS: usize = $place::FIELDS + 2 * $place::VECTORS;

            /// Writes it into position `j` of the columns of a block, straight from its
            /// fields (no array in between), but for the fields of `unwritten` (bits of
            /// `$place`), whose columns keep what they held. Where `unwritten` is a
            /// constant once inlined no test is left; `lambert_lane`'s is one of two, and
            /// costs a few tests and branches a lane, fewer than the columns it spares.
            #[inline(always)]
            fn write_at(&self, block: &mut Block<{ Self::COLUMNS }>, j: usize, unwritten: u64) {
                let j = j % CHUNK;
                $(
                    if unwritten & $place::$vector.bit() == 0 {
                        let k = $place::$vector.column();
                        block[k][j] = self.$vector.x;
                        block[k + 1][j] = self.$vector.y;
                        block[k + 2][j] = self.$vector.z;
                    }
                )*
                $(
                    if unwritten & $place::$scalar.bit() == 0 {
                        block[$place::$scalar.column()][j] = self.$scalar;
                    }
                )*
            }

            /// The record at position `j` of the columns of a block. (The outcomes are read
            /// field by field, `lane_fields`: only tests read them whole.)
            #[cfg_attr(not(test), allow(dead_code))]
            #[inline(always)]
            fn read_at(block: &Block<{ Self::COLUMNS }>, j: usize) -> Self {
                let j = j % CHUNK;
                let mut record = Self::default();
                $(
                    let k = $place::$vector.column();
                    record.$vector = Vec3::new(block[k][j], block[k + 1][j], block[k + 2][j]);
                )*
                $(
                    record.$scalar = block[$place::$scalar.column()][j];
                )*
                record
            }
        }
    };
}

/// Lays a lane record out in columns (`lane_columns`) and reads its fields one at a time,
/// from the record or straight from its position in the columns of a block (`$view`): what
/// reads it need not copy all of it first (a read-back of all of an outcome's columns, 22
/// then, spilled half of them to the stack before they were used).
macro_rules! lane_fields {
    ($record:ident, $fields:ident, $view:ident, $place:ident {
        $($vector:ident),* ; $($scalar:ident),*
    }) => {
        // One list of the fields for both, so that the view reads the layout it was written in.
        lane_columns!($record, $place { $($vector),* ; $($scalar),* });

        /// The fields of a record, read one at a time.
        pub(crate) trait $fields {
            $(fn $vector(&self) -> Vec3;)*
            $(fn $scalar(&self) -> f32;)*
        }

        impl $fields for $record {
            $(#[inline(always)] fn $vector(&self) -> Vec3 { self.$vector })*
            $(#[inline(always)] fn $scalar(&self) -> f32 { self.$scalar })*
        }

        /// A record at position `j` of the columns of a block.
        pub(crate) struct $view<'a> {
            block: &'a Block<{ $record::COLUMNS }>,
            j: usize,
        }

        impl $view<'_> {
            /// The whole record.
            #[cfg(test)]
            pub fn record(&self) -> $record {
                $record::read_at(self.block, self.j)
            }
        }

        impl $fields for $view<'_> {
            $(
                #[inline(always)]
                fn $vector(&self) -> Vec3 {
                    let (k, j) = ($place::$vector.column(), self.j % CHUNK);
                    Vec3::new(self.block[k][j], self.block[k + 1][j], self.block[k + 2][j])
                }
            )*
            $(
                #[inline(always)]
                fn $scalar(&self) -> f32 {
                    self.block[$place::$scalar.column()][self.j % CHUNK]
                }
            )*
        }
    };
}

lane_columns!(LambertLane, LanePlace {
    dir, point, error, normal, hit_v0, hit_v1, hit_v2, hit_origin, shading_normal, diffuse,
    throughput, light_point, light_error, light_normal, emission;
    eta_scale, has_light, light_kind, light_pdf, light_visible, light_two_sided, u0, u1,
    u_survive, roulette, on_triangle, hit_b1, hit_b2, hit_t, hit_tilt, hit_edge_tilt
});

lane_fields!(LambertOutcome, OutcomeFields, OutcomeAt, OutcomePlace {
    shadow_origin, shadow_dir, contribution, next_origin, next_dir, throughput, point;
    shadow, next, pdf, shadow_tmax, near
});

/// The fields a lane whose point is left to the lanes (`on_triangle` not 0) need not write:
/// `with_hit_point` sets them before anything reads them.
pub(crate) const POINT_UNWRITTEN: u64 = LanePlace::point.bit() | LanePlace::error.bit();

/// The fields a `LONE` lane need not write: `with_lone_light` sets them where it samples
/// the light by area; where it does not, the lane has no light (`has_light`, which it
/// always sets, is 0) and nothing reads them, and a `NEAR` lane gets all its light fields
/// one lane at a time (`PathTracer::lambert_outcome`). A column left unwritten keeps an
/// earlier bounce's value, which reaches no result that is read.
pub(crate) const LONE_UNWRITTEN: u64 = LanePlace::has_light.bit()
    | LanePlace::light_error.bit()
    | LanePlace::emission.bit()
    | LanePlace::light_pdf.bit()
    | LanePlace::light_visible.bit()
    | LanePlace::light_two_sided.bit();

const IN: usize = LambertLane::COLUMNS;
const OUT: usize = LambertOutcome::COLUMNS;

/// Lanes computed together: AVX-512's width (two AVX2 registers, four SSE ones).
const CHUNK: usize = 16;

/// `CHUNK` lanes' worth of each column of `N`.
type Block<const N: usize> = [[f32; CHUNK]; N];

/// The queue: each bounce written by its path straight into the next column position of
/// the blocks of `CHUNK` lanes (each column of a block contiguous), and the path each
/// belongs to.
#[derive(Default)]
pub(crate) struct LambertLanes {
    paths: Vec<u32>,
    inputs: Vec<Block<IN>>,
    outputs: Vec<Block<OUT>>,
}

/// The column position the next queued bounce is written to.
pub(crate) struct LaneSlot<'a> {
    block: &'a mut Block<IN>,
    j: usize,
}

impl LaneSink for LaneSlot<'_> {
    #[inline(always)]
    fn put(&mut self, lane: LambertLane, unwritten: u64) {
        lane.write_at(self.block, self.j, unwritten);
    }
}

impl LambertLanes {
    /// Empties the queue.
    pub fn clear(&mut self) {
        self.paths.clear();
    }

    /// Where to write the next bounce; it is queued only by `commit`.
    #[inline]
    pub fn next_lane(&mut self) -> LaneSlot<'_> {
        let (block, j) = (self.paths.len() / CHUNK, self.paths.len() % CHUNK);
        if block == self.inputs.len() {
            // A block's spare lanes are computed too, and ignored: what they hold (zeros,
            // or an earlier bounce's lanes) is as good as anything.
            self.inputs.push([[0.0; CHUNK]; IN]);
            self.outputs.push([[0.0; CHUNK]; OUT]);
        }
        LaneSlot { block: &mut self.inputs[block], j }
    }

    /// Queues the bounce written into `next_lane`, of path `path`.
    #[inline]
    pub fn commit(&mut self, path: u32) {
        self.paths.push(path);
    }

    /// Queues the bounce `lane` of path `path`.
    #[cfg(test)]
    pub fn push(&mut self, path: u32, lane: &LambertLane) {
        self.next_lane().put(*lane, 0);
        self.commit(path);
    }

    /// Computes every queued bounce, its point computed first where it was left to the
    /// lanes (only ever on a plain surface: none without `plain_surfaces`), and its light
    /// sampled on `emitter` where that was (`lane_light`).
    pub fn run(
        &mut self,
        spaces: &FrameSpaces,
        emitter: Option<&LoneEmitter>,
        plain_surfaces: bool,
    ) {
        let blocks = self.paths.len().div_ceil(CHUNK);
        let (inputs, outputs) = (&self.inputs[..blocks], &mut self.outputs[..blocks]);
        let kernel = Kernel { spaces, emitter, plain_surfaces, inputs, outputs };
        pulp::Arch::new().dispatch(kernel);
    }

    /// The queued bounces' positions in the queue, paths and outcomes, in the order they
    /// were queued (after `run`): each outcome read where it lies, field by field.
    pub fn outcomes(&self) -> impl Iterator<Item = (usize, u32, OutcomeAt<'_>)> + '_ {
        self.paths.iter().enumerate().map(|(i, &path)| {
            (i, path, OutcomeAt { block: &self.outputs[i / CHUNK], j: i % CHUNK })
        })
    }

    /// The bounce queued at position `i`, as it was queued, but for the columns its lane
    /// left unwritten (`POINT_UNWRITTEN`, `LONE_UNWRITTEN`): `lambert_outcome` sets those
    /// again.
    pub fn queued(&self, i: usize) -> LambertLane {
        LambertLane::read_at(&self.inputs[i / CHUNK], i % CHUNK)
    }
}

/// The loop over the blocks, compiled once per instruction set `pulp` dispatches to.
struct Kernel<'a> {
    spaces: &'a FrameSpaces,
    emitter: Option<&'a LoneEmitter>,
    plain_surfaces: bool,
    inputs: &'a [Block<IN>],
    outputs: &'a mut [Block<OUT>],
}

impl pulp::WithSimd for Kernel<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let blocks = self.inputs.iter().zip(self.outputs.iter_mut());
        match (self.emitter, self.plain_surfaces) {
            (Some(emitter), _) => {
                for (inputs, outputs) in blocks {
                    run_block(self.spaces, emitter.sampler, inputs, outputs);
                }
            }
            (None, true) => {
                for (inputs, outputs) in blocks {
                    run_block(self.spaces, HitPoints, inputs, outputs);
                }
            }
            (None, false) => {
                for (inputs, outputs) in blocks {
                    run_block(self.spaces, Unchanged, inputs, outputs);
                }
            }
        }
    }
}

/// What a lane needs before its bounce is computed.
trait Prepare: Copy {
    fn prepare(&self, lane: LambertLane) -> LambertLane;
}

/// Nothing: every point and light point is known already.
#[derive(Clone, Copy)]
struct Unchanged;

impl Prepare for Unchanged {
    #[inline(always)]
    fn prepare(&self, lane: LambertLane) -> LambertLane {
        lane
    }
}

/// The points left to the lanes (where the scene's light is not a lone emitter).
#[derive(Clone, Copy)]
struct HitPoints;

impl Prepare for HitPoints {
    #[inline(always)]
    fn prepare(&self, lane: LambertLane) -> LambertLane {
        with_hit_point(&lane)
    }
}

/// The points and light samples left to the lanes where the scene's light is the lone
/// emitter.
impl Prepare for AreaSampler {
    #[inline(always)]
    fn prepare(&self, lane: LambertLane) -> LambertLane {
        with_lone_light(&with_hit_point(&lane), self)
    }
}

/// One block's lanes, each made ready by `prepare` first. Its own function so that its
/// arguments tell the compiler that the outputs alias no input (it vectorises the loop
/// only then).
#[inline(always)]
fn run_block(
    spaces: &FrameSpaces,
    prepare: impl Prepare,
    inputs: &Block<IN>,
    outputs: &mut Block<OUT>,
) {
    for j in 0..CHUNK {
        let lane = prepare.prepare(LambertLane::read_at(inputs, j));
        lambert_bounce(&lane, spaces).write_at(outputs, j, 0);
    }
}

#[cfg(test)]
#[path = "lanes_tests.rs"]
mod tests;
