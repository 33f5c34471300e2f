//! `EmbreeAccel`: the `Accel` implementation over a committed Embree scene.

use super::device::Device;
use super::ffi;
use super::geometry::Geometry;
use super::scene::{CommittedScene, Scene};
use super::sphere::sphere_geometry;
use crate::accel::{Accel, AccelError, AccelOptions, Hit, Ray};
use crate::render_scene::{self, RenderScene};
use crate::stats::TraversalCounters;
use std::sync::Arc;

/// Embree's defaults: all cores, ISA chosen at run time.
const DEVICE_CONFIG: &str = "";

pub struct EmbreeAccel {
    scene: CommittedScene,
}

impl EmbreeAccel {
    /// Builds an Embree scene over `scene.shapes`; shape `i` gets geometry id `i`.
    pub fn build(scene: &RenderScene, options: &AccelOptions) -> Result<EmbreeAccel, AccelError> {
        // Counting mode is not implemented yet: see `observes`.
        let _ = options.count_traversal;
        let device = Arc::new(Device::new(DEVICE_CONFIG)?);
        // ROBUST: watertight-enough traversal for rays grazing edges and box faces.
        let mut embree_scene =
            Scene::new(&device, ffi::RTCBuildQuality::MEDIUM, ffi::RTCSceneFlags::ROBUST)?;
        for (index, shape) in scene.shapes.iter().enumerate() {
            let name_error = |e: AccelError| match e {
                AccelError::Embree(msg) => {
                    AccelError::Embree(format!("shape {index} ('{}'): {msg}", shape.name))
                }
                other => other,
            };
            let id = u32::try_from(index)
                .ok()
                .filter(|&id| id != ffi::RTC_INVALID_GEOMETRY_ID)
                .ok_or_else(|| name_error(AccelError::Embree("too many shapes".into())))?;
            let geometry = match &shape.geometry {
                render_scene::Geometry::Triangles(mesh) => {
                    Geometry::triangles(&device, &mesh.positions, &mesh.indices)
                }
                render_scene::Geometry::Sphere(sphere) => sphere_geometry(&device, *sphere),
            }
            .map_err(name_error)?;
            embree_scene.attach(geometry, id).map_err(name_error)?;
        }
        Ok(EmbreeAccel { scene: embree_scene.commit()? })
    }
}

impl Accel for EmbreeAccel {
    fn name(&self) -> &'static str {
        "embree"
    }

    fn intersect(&self, ray: &Ray, _counters: &mut TraversalCounters) -> Option<Hit> {
        self.scene.intersect(ray)
    }

    fn occluded(&self, ray: &Ray, _counters: &mut TraversalCounters) -> bool {
        self.scene.occluded(ray)
    }

    /// Not yet. The place for it: with `options.count_traversal`, pass `counters` to Embree
    /// in a query context extended past Embree's own struct (the usual trick; callbacks
    /// receive the context) and count primitive tests in the user-geometry and filter
    /// callbacks; Embree exposes no node-visit count.
    fn observes(&self) -> crate::accel::Observes {
        crate::accel::Observes::default()
    }
}
