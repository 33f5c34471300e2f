//! `EmbreeAccel`: the `Accel` implementation over a committed Embree scene.

use super::batch::BatchKind;
use super::device::Device;
use super::ffi;
use super::geometry_handle::GeometryHandle;
use super::scene::{CommittedScene, Scene};
use super::sdf_grid::sdf_grid_geometry;
use super::sphere::sphere_geometry;
use super::user_triangles::user_triangle_geometry;
use crate::accel::{
    Accel, AccelError, AccelOptions, BatchMode, BuildQuality, Coherence, Intersection, Observes,
};
use crate::ray::{Hit, Ray};
use crate::ray_columns::RayColumns;
use crate::render_scene::{self, Placement, RenderScene};
use crate::stats::TraversalCounters;
use std::sync::Arc;

/// Barycentric distance from a triangle's edge within which a packet hit may be a tie
/// Embree's single-ray kernel would break differently (see `EmbreeAccel::intersect_batch`).
/// Embree's robust test accepts hits a few ulps outside the edge, so this has a wide margin.
const TIE_EDGE: f32 = 1e-4;

/// Embree's defaults: all cores, ISA chosen at run time.
const DEVICE_CONFIG: &str = "";

/// The Embree backend.
///
/// # Counting mode (`AccelOptions::count_traversal`)
///
/// Embree's release builds keep no traversal statistics, so counting mode builds a
/// diagnostic scene in which Embree's own traversal has to call us back:
///
/// - Every triangle mesh becomes an Embree *user geometry* with one user primitive per
///   triangle, bounded by the triangle's exact AABB: attached to the top scene when baked,
///   else in the prototype's shared child scene (Embree calls it with the object-space
///   ray). Its callbacks run our watertight `crate::intersect::intersect_triangle` (the
///   obvhs backend's test) and report hits as Embree's native triangles do. Spheres are
///   user geometry in both modes.
/// - **`prim_tests`** counts user-primitive callback invocations, one per primitive per ray
///   (per valid packet lane): the primitives in the BVH leaves Embree's traversal reached,
///   through instances too (the count is per query, whatever scene the callback runs in).
///   Embree builds that BVH over the triangles' AABBs with its user-geometry builder (build
///   quality MEDIUM, as in normal mode; the ROBUST flag is set but, as the symbols of
///   Embree 3.13.5 show, it has no robust traversal for user-geometry or instance BVHs,
///   only for triangles, quads, grids and curves) and, as observed with Embree 3.13.5, puts
///   one primitive in each leaf, so a closest-hit query tests at least every primitive
///   whose box the ray enters before its hit and at most every primitive whose box it
///   enters in `[tmin, tmax]` (checked by a test; exactly the former for ~87 % of random
///   rays).
///   Shadow rays stop at the first occluder. This is *not* the BVH of Embree's native
///   triangle path, which packs several triangles per leaf and tests them with SIMD, so
///   has no per-triangle count to observe: the number measures how well Embree's BVH prunes
///   this scene (comparable with obvhs's `prim_tests`), not the exact work of a normal
///   render.
/// - **`node_visits`** is not observable (Embree has no hook for node tests and no
///   statistics in release builds); it stays 0 and `observes()` says so.
/// - Hits equal the obvhs backend's bit for bit wherever both report the same primitive,
///   and normal mode's up to the triangle test (t within 1e-4 relative; the two disagree
///   only on rays within rounding of an edge or of an equally near hit).
/// - Cost, measured on the 100k-triangle dragon with 200k random rays on one thread
///   (Embree 3.13.5): closest-hit queries 1.8-2.0x slower (3.9 → 2.0-2.2 Mrays/s),
///   occlusion 1.65-1.75x slower; the build takes ~1.7x longer (0.025 → 0.04 s) and keeps
///   a copy of the triangles (36 bytes each). The cost is the user-geometry path (a
///   callback per triangle instead of SIMD leaves): the same scene queried without
///   counters is as slow. Normal mode ignores the counters argument and costs nothing.
pub struct EmbreeAccel {
    scene: CommittedScene,
    counting: bool,
    motion_geometries: usize,
    /// Per geometry id: a triangle mesh (whose packet hits near an edge are re-traced, see
    /// [`EmbreeAccel::intersect_batch`]).
    triangle_meshes: Vec<bool>,
    batch: BatchKind,
}

/// Wraps Embree errors with what they concern.
fn named(what: impl Fn() -> String) -> impl Fn(AccelError) -> AccelError {
    move |e| match e {
        AccelError::Embree(msg) => AccelError::Embree(format!("{}: {msg}", what())),
        other => other,
    }
}

impl EmbreeAccel {
    /// Builds an Embree scene over `scene.instances`; instance `i` gets geometry id `i`.
    /// With `options.count_traversal`, builds the diagnostic counting scene described on
    /// [`EmbreeAccel`].
    ///
    /// # Instances and motion
    ///
    /// - `Placement::Baked`: the prototype's geometry (already in render space) is attached
    ///   directly to the top scene with id `i`.
    /// - `Placement::Static` / `Placement::Moving`: each prototype they use gets one child
    ///   scene, built and committed once and shared by all its instances; each instance is
    ///   an Embree instance geometry (id `i`) of that child, so an extra instance costs a
    ///   transform and a top-level BVH entry, never a copy of the geometry. Static
    ///   instances have one transform; moving ones two time steps (quaternion
    ///   decompositions of `start` and `end`, which Embree interpolates as `Trs::lerp`
    ///   does). Only moving instances get time steps, so a scene without them builds no
    ///   motion BVH at all ([`EmbreeAccel::motion_geometries`] is 0).
    ///
    /// Embree hands user geometry in a child scene the ray in object space, so spheres
    /// (and counting mode's triangles) work through instances, ellipsoids included.
    pub fn build(scene: &RenderScene, options: &AccelOptions) -> Result<EmbreeAccel, AccelError> {
        let counting = options.count_traversal;
        let device = Arc::new(Device::new(DEVICE_CONFIG)?);
        let new_scene = || new_scene(&device, options);
        let mut top = new_scene()?;
        let mut children: Vec<Option<Arc<CommittedScene>>> = vec![None; scene.prototypes.len()];
        let mut motion_geometries = 0;
        for (index, instance) in scene.instances.iter().enumerate() {
            let name_error = named(|| format!("instance {index} ('{}')", instance.name));
            let id = u32::try_from(index)
                .ok()
                .filter(|&id| id != ffi::RTC_INVALID_GEOMETRY_ID)
                .ok_or_else(|| name_error(AccelError::Embree("too many instances".into())))?;
            let p = instance.prototype as usize;
            let prototype = scene.prototypes.get(p).ok_or_else(|| {
                name_error(AccelError::Embree(format!(
                    "prototype {p} does not exist (the scene has {})",
                    scene.prototypes.len()
                )))
            })?;
            let mut child = || -> Result<Arc<CommittedScene>, AccelError> {
                if let Some(child) = &children[p] {
                    return Ok(Arc::clone(child));
                }
                let child = child_scene(new_scene()?, &device, &prototype.geometry, counting)
                    .map_err(named(|| format!("prototype {p} ('{}')", prototype.name)))?;
                motion_geometries += child.motion_geometries();
                children[p] = Some(Arc::clone(&child));
                Ok(child)
            };
            let geometry = match &instance.placement {
                Placement::Baked { .. } => {
                    prototype_geometry(&device, &prototype.geometry, counting)
                }
                Placement::Static { render_from_object, .. } => {
                    GeometryHandle::static_instance(&device, &child()?, render_from_object)
                }
                Placement::Moving { start, end } => {
                    GeometryHandle::moving_instance(&device, &child()?, start, end)
                }
            }
            .map_err(&name_error)?;
            top.attach(geometry, id).map_err(&name_error)?;
        }
        let top = top.commit()?;
        motion_geometries += top.motion_geometries();
        let triangle_meshes = scene
            .instances
            .iter()
            .map(|i| {
                let prototype = &scene.prototypes[i.prototype as usize];
                matches!(prototype.geometry, render_scene::Geometry::Triangles(_))
            })
            .collect();
        // Embree's packet kernels interpolate motion differently from its single-ray ones
        // (hits on moving instances differ in the last bits), so scenes with motion trace
        // batches one ray at a time; so does counting mode, to count exactly as before.
        let batch = match options.batch {
            _ if counting || motion_geometries > 0 => BatchKind::Single,
            BatchMode::Single => BatchKind::Single,
            BatchMode::Packets8 => BatchKind::Packet8,
            BatchMode::Packets16 => BatchKind::Packet16,
            BatchMode::Native => match super::library::library() {
                Ok(library) if library.isa == "AVX-512" => BatchKind::Packet16,
                _ => BatchKind::Packet8,
            },
        };
        Ok(EmbreeAccel { scene: top, counting, motion_geometries, triangle_meshes, batch })
    }

    /// How many Embree geometries were committed with more than one time step: one per
    /// moving instance, 0 for a static scene (which therefore pays nothing for motion blur).
    pub fn motion_geometries(&self) -> usize {
        self.motion_geometries
    }

    /// The flags of its top-level scene (child scenes get the same).
    #[cfg(test)]
    pub(crate) fn scene_flags(&self) -> ffi::RTCSceneFlags {
        self.scene.flags()
    }

    /// A bare `rtcIntersect1` loop over `rays` (one query context for all, no wrapper, no
    /// `Hit` conversion), returning how many rays hit: the baseline [`Accel::intersect`] is
    /// measured against (`benches/throughput.rs`).
    ///
    /// # Panics
    /// If any ray is one Embree would reject (Debian's Embree would abort the process):
    /// all rays are checked before the loop.
    pub fn raw_intersect_loop(&self, rays: &[Ray]) -> usize {
        self.scene.raw_intersect_loop(rays)
    }

    /// Closest hits of `rays` through the Embree entry point `kind` (normal mode; counting
    /// mode always traces one ray at a time).
    pub fn intersect_batch_with(&self, kind: BatchKind, rays: &[Ray], hits: &mut [Option<Hit>]) {
        self.scene.intersect_batch(kind, Coherence::Coherent, rays, hits);
    }

    /// Traces again, one ray at a time, every packet hit that may be a tie the single-ray
    /// kernel breaks otherwise (see `intersect_batch`); `ray(i)` is the ray of `hits[i]`.
    fn retrace_ties(&self, hits: &mut [Option<Hit>], ray: impl Fn(usize) -> Ray) {
        for (i, hit) in hits.iter_mut().enumerate() {
            // The rare edge first: most hits then need no look at their geometry.
            if let Some(h) = hit
                && h.u.min(h.v).min(1.0 - h.u - h.v) < TIE_EDGE
                && self.triangle_meshes.get(h.geom_id as usize).copied().unwrap_or(true)
            {
                *hit = self.scene.intersect(&ray(i), None);
            }
        }
    }

    fn counters<'a>(
        &self,
        counters: &'a mut TraversalCounters,
    ) -> Option<&'a mut TraversalCounters> {
        self.counting.then_some(counters)
    }
}

/// A scene as all of ours are built, with the build quality, triangle test and COMPACT flag
/// of `options`. ROBUST by default (`Intersection::Robust`): watertight-enough traversal
/// for rays grazing triangle edges and box faces, in child scenes too (that is where an
/// instanced mesh's BVH is). Embree 3.13.5 ignores it for instance and user-geometry BVHs
/// (it has no robust variant of those traversals): a ray within rounding of such a box's
/// face may miss it. With ROBUST it also builds triangles with the MEDIUM builder when asked
/// for HIGH (it has spatial splits only for the fast triangle layout), so
/// `BuildQuality::High` changes nothing then.
fn new_scene(device: &Arc<Device>, options: &AccelOptions) -> Result<Scene, AccelError> {
    let quality = match options.build_quality {
        BuildQuality::Low => ffi::RTCBuildQuality::LOW,
        BuildQuality::Medium => ffi::RTCBuildQuality::MEDIUM,
        BuildQuality::High => ffi::RTCBuildQuality::HIGH,
    };
    let mut flags = match options.intersection {
        Intersection::Robust => ffi::RTCSceneFlags::ROBUST,
        Intersection::Fast => ffi::RTCSceneFlags::NONE,
    };
    if options.compact {
        flags |= ffi::RTCSceneFlags::COMPACT;
    }
    Scene::new(device, quality, flags)
}

/// The Embree geometry of a prototype, in the prototype's own space.
fn prototype_geometry(
    device: &Arc<Device>,
    geometry: &render_scene::Geometry,
    counting: bool,
) -> Result<GeometryHandle, AccelError> {
    match geometry {
        render_scene::Geometry::Triangles(mesh) if counting => {
            user_triangle_geometry(device, &mesh.positions, &mesh.indices)
        }
        render_scene::Geometry::Triangles(mesh) => {
            GeometryHandle::triangles(device, &mesh.positions, &mesh.indices)
        }
        render_scene::Geometry::Sphere(sphere) => sphere_geometry(device, *sphere),
        render_scene::Geometry::SdfGrid(grid) => sdf_grid_geometry(device, grid.clone()),
    }
}

/// The child scene instances of a prototype share: its geometry alone, with id 0, in the
/// new `scene`.
fn child_scene(
    mut scene: Scene,
    device: &Arc<Device>,
    geometry: &render_scene::Geometry,
    counting: bool,
) -> Result<Arc<CommittedScene>, AccelError> {
    scene.attach(prototype_geometry(device, geometry, counting)?, 0)?;
    Ok(Arc::new(scene.commit()?))
}

impl Accel for EmbreeAccel {
    fn name(&self) -> &'static str {
        "embree"
    }

    fn intersect(&self, ray: &Ray, counters: &mut TraversalCounters) -> Option<Hit> {
        self.scene.intersect(ray, self.counters(counters))
    }

    fn occluded(&self, ray: &Ray, counters: &mut TraversalCounters) -> bool {
        self.scene.occluded(ray, self.counters(counters))
    }

    /// As `AccelOptions::batch` says: one `rtcIntersect1` per ray, or packets
    /// (`rtcIntersect8/16`) with invalid rays masked out (never handed to Embree). Counting
    /// mode and scenes with motion blur always trace one ray at a time.
    ///
    /// # Packets and single rays
    ///
    /// Embree's packet kernels compute `t`, `u`, `v` with the same arithmetic as its
    /// single-ray kernel almost always (bit for bit on millions of camera and bounce rays,
    /// `batch_tests`), but break ties between primitives at the same `t` differently: within
    /// a BVH leaf the single-ray kernel keeps the first primitive, the packet kernel the
    /// last. The common tie, a ray through an edge two triangles share, is caught: every
    /// packet hit within `TIE_EDGE` (barycentric) of its triangle's edge is traced again with
    /// `rtcIntersect1` (about 1e-3 of the hits on a million-triangle mesh). Not caught:
    /// exact or 1-ulp ties between coincident surfaces (faces in one plane that share no
    /// edge, duplicated faces), where the packet may report the other surface
    /// (`tests/batch_queries.rs` proves each such difference is a tie). With motion blur the
    /// packet kernels interpolate instance transforms differently (hits differ in the last
    /// bits), so moving scenes never use packets.
    fn intersect_batch(
        &self,
        rays: &[Ray],
        hits: &mut [Option<Hit>],
        coherence: Coherence,
        counters: &mut TraversalCounters,
    ) {
        assert_eq!(rays.len(), hits.len(), "one hit slot per ray");
        if self.counting || self.batch == BatchKind::Single {
            for (ray, hit) in rays.iter().zip(hits.iter_mut()) {
                *hit = self.scene.intersect(ray, self.counters(counters));
            }
            return;
        }
        self.scene.intersect_batch(self.batch, coherence, rays, hits);
        self.retrace_ties(hits, |i| rays[i]);
    }

    /// As `intersect_batch`, the packets filled a column at a time.
    fn intersect_columns(
        &self,
        rays: &RayColumns,
        hits: &mut [Option<Hit>],
        coherence: Coherence,
        counters: &mut TraversalCounters,
    ) {
        if self.counting || self.batch == BatchKind::Single {
            crate::accel::intersect_one_by_one(self, rays, hits, counters);
            return;
        }
        self.scene.intersect_columns(self.batch, coherence, rays, hits);
        self.retrace_ties(hits, |i| rays.ray(i));
    }

    /// As `intersect_batch`: packets unless counting or with motion blur (occlusion has
    /// no ties to break: a packet lane is blocked exactly when its single ray is).
    fn occluded_batch(&self, rays: &[Ray], blocked: &mut [bool], counters: &mut TraversalCounters) {
        if self.counting || self.batch == BatchKind::Single {
            crate::accel::occluded_one_by_one(self, rays, blocked, counters);
            return;
        }
        self.scene.occluded_batch(self.batch, rays, blocked);
    }

    /// As `occluded_batch`, the packets filled a column at a time.
    fn occluded_columns(
        &self,
        rays: &RayColumns,
        blocked: &mut [bool],
        counters: &mut TraversalCounters,
    ) {
        if self.counting || self.batch == BatchKind::Single {
            crate::accel::occluded_one_by_one(self, rays, blocked, counters);
            return;
        }
        self.scene.occluded_columns(self.batch, rays, blocked);
    }

    /// Primitive tests in counting mode; node visits never (see [`EmbreeAccel`]).
    fn observes(&self) -> Observes {
        Observes { node_visits: false, prim_tests: self.counting }
    }

    /// What Embree's memory monitor counted for this backend's device: its BVHs, buffers
    /// and allocator blocks.
    fn memory_bytes(&self) -> Option<usize> {
        Some(self.scene.device().allocated_bytes())
    }
}
