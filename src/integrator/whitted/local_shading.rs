//! The course's local shading at one hit: ambient, and from every light with a clear
//! shadow ray, diffuse and specular terms of the material's reflectance model.

use super::WhittedTracer;
use crate::sampling::SampleStream;
use crate::scene::{CourseBrdf, TextureMode};
use crate::shading::course_brdf::{CourseTerms, cos_weighted};
use crate::shading::spawn::SurfacePoint;
use crate::shading::surface::SurfaceInteraction;
use crate::stats::RenderStats;
use glam::{Vec2, Vec3};

impl WhittedTracer<'_> {
    /// Ambient + diffuse + Blinn-Phong specular from every light at `si`.
    pub(super) fn local_shading(
        &self,
        si: &SurfaceInteraction,
        wo: Vec3,
        time: f32,
        stream: &mut SampleStream,
        stats: &mut RenderStats,
    ) -> Vec3 {
        let material = &self.tracer.scene.materials[si.material as usize];
        let lights = &self.tracer.scene.lights;
        let (ambient, specular, exponent, brdf) = match &material.phong {
            Some(p) => (p.ambient, p.specular, p.exponent, p.brdf),
            None => (Vec3::ZERO, Vec3::ZERO, 1.0, CourseBrdf::default()),
        };
        let mut diffuse = material.albedo;
        if let Some(t) = &material.texture {
            let color = self.tracer.texture_color(t, si, time);
            if t.mode == TextureMode::ReplaceAll {
                // Shading is off: the texture is the colour seen (in display units).
                return color;
            }
            diffuse = t.apply_to_albedo(diffuse, color);
        }
        let specular = match &material.specular_texture {
            Some(t) => self.tracer.texture_color(t, si, time),
            None => specular,
        };
        let terms = CourseTerms { diffuse, specular, exponent };
        // The course lights a surface on the side its own normal points to, whichever side
        // the ray arrived on: the back of a one-sided triangle is lit only by lights behind
        // it (so a sail seen from the back is dark where a two-sided surface would be lit).
        let side = if si.front_face { 1.0 } else { -1.0 };
        let n = side * si.shading_normal;
        let geometric = side * si.surface.normal;
        // As the course does: nothing from a light below the shading normal's horizon
        // (smooth shading otherwise lights the dark side of the terminator).
        let shade =
            |wi: Vec3, irradiance: Vec3| cos_weighted(&brdf, &terms, n, wi, wo) * irradiance;
        let mut color = ambient * lights.ambient;
        let faces = |wi: Vec3| geometric.dot(wi) > 0.0;
        for light in &lights.points {
            let to_light = light.position - si.surface.point;
            let dist2 = to_light.length_squared();
            let wi = to_light / dist2.sqrt();
            if !faces(wi) {
                continue;
            }
            let shadow =
                self.tracer.spawn.ray_to(&si.surface, &SurfacePoint::exact(light.position), time);
            if !self.occluded(&shadow, stats) {
                color += shade(wi, light.intensity_towards(-wi) / dist2);
            }
        }
        for light in &lights.directional {
            let wi = -light.direction;
            if faces(wi) && !self.occluded(&self.tracer.spawn.ray(&si.surface, wi, time), stats) {
                color += shade(wi, light.irradiance);
            }
        }
        if lights.has_emitters() {
            let [u0, u1, u2, u3] = stream.next_4d();
            let (pick, on_surface) = (Vec2::new(u2, u3), Vec2::new(u0, u1));
            if let Some(sample) = lights.sample_emitter(si.surface.point, pick, on_surface) {
                let wi = (sample.point - si.surface.point).normalize();
                let lit = sample.emitted_cosine(-wi) > 0.0;
                let target = SurfacePoint {
                    point: sample.point,
                    error: sample.error,
                    normal: sample.normal,
                };
                if faces(wi)
                    && lit
                    && sample.geom_id != si.geom_id
                    && !self.occluded(&self.tracer.spawn.ray_to(&si.surface, &target, time), stats)
                {
                    color += shade(wi, sample.emission / sample.pdf);
                }
            }
        }
        // One direction towards the environment (hw5.tex samples the hemisphere uniformly;
        // sampling by the map's luminance converges to the same image with less noise).
        if let Some(environment) = lights.environment.as_ref().filter(|e| e.is_lit()) {
            if let Some(sample) = environment.sample(stream.next_2d()) {
                let wi = sample.wi;
                if faces(wi) && !self.occluded(&self.tracer.spawn.ray(&si.surface, wi, time), stats)
                {
                    color += shade(wi, sample.radiance / sample.pdf);
                }
            }
        }
        color
    }
}
