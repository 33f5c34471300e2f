//! Light transport: the path tracer (NEE + MIS) and the course's Whitted model, siblings
//! over one shared trace helper.

pub mod path;
mod trace;
pub mod whitted;

use crate::accel::Accel;
use crate::ray::Ray;
use crate::render_options::{PathBatching, RenderOptions};
use crate::render_scene::RenderScene;
use crate::sampling::SampleStream;
use crate::scene::IntegratorKind;
use crate::stats::RenderStats;
use glam::Vec3;
pub use path::PathTracer;
pub(crate) use path::Wavefront;
use trace::SceneTracer;
pub use whitted::WhittedTracer;

/// What one camera sample contributes to a pixel.
#[derive(Clone, Copy, Debug, Default)]
pub struct PathSample {
    pub radiance: Vec3,
    /// Distance to the first hit along the (unit) camera ray.
    pub depth: Option<f32>,
    /// World-space shading normal at the first hit.
    pub normal: Option<Vec3>,
    /// The first hit's albedo (the fraction of light its surface reflects; for the
    /// `albedo` AOV, what a denoiser takes as the surface's colour).
    pub albedo: Option<Vec3>,
}

/// The light-transport algorithm of one render.
pub enum Tracer<'a> {
    Path(PathTracer<'a>),
    Whitted(WhittedTracer<'a>),
}

impl<'a> Tracer<'a> {
    /// The tracer `options` ask for: their integrator, `max_depth` (surface interactions
    /// for the path tracer, bounces after the camera ray for Whitted), the path tracer's
    /// shadow rays per shading point, spawning, lobe energy, and whether the first hit's
    /// albedo is wanted (the `albedo` AOV; not computed otherwise).
    pub fn new(scene: &'a RenderScene, accel: &'a dyn Accel, options: &RenderOptions) -> Self {
        let first_hit_albedo = options.first_hit_albedo;
        let tracer = SceneTracer { scene, accel, spawn: options.spawn, first_hit_albedo };
        let max_depth = options.max_depth;
        match options.integrator {
            IntegratorKind::Path => Tracer::Path(PathTracer::new(
                tracer,
                max_depth,
                options.rr_depth,
                options.light_samples,
                options.energy,
                options.paths != PathBatching::Reference,
            )),
            IntegratorKind::Whitted => {
                Tracer::Whitted(WhittedTracer::new(tracer, max_depth, options.stop.clone()))
            }
        }
    }

    pub fn scene(&self) -> &RenderScene {
        match self {
            Tracer::Path(t) => t.scene(),
            Tracer::Whitted(t) => t.scene(),
        }
    }

    /// One camera ray's sample; `backdrop`: what it sees if it leaves the scene, if the
    /// scene has a backdrop (`RenderScene::backdrop_at`).
    pub fn trace(
        &self,
        ray: Ray,
        backdrop: Option<Vec3>,
        stream: &mut SampleStream,
        stats: &mut RenderStats,
    ) -> PathSample {
        match self {
            Tracer::Path(t) => t.trace(ray, backdrop, stream, stats),
            Tracer::Whitted(t) => t.trace(ray, backdrop, stream, stats),
        }
    }
}
