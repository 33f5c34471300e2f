//! Light sampling and its multiple-importance weights: next-event estimation towards
//! point, spot, projector and directional lights, emitters and the environment, and the
//! weights of the emission BSDF sampling finds.

use super::{PathTracer, ShadowSink};
use crate::sampling::SampleStream;
use crate::shading::bsdf::Bsdf;
use crate::shading::spawn::SurfacePoint;
use crate::shading::surface::SurfaceInteraction;
use crate::stats::RenderStats;
use glam::{Vec2, Vec3};

/// Power-heuristic weight of a strategy with density `a` against one with density `b`.
/// Written as selects, so that the Lambertian lanes' loop (`lambert`) vectorises with it.
#[inline(always)]
pub(super) fn power_heuristic(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    let ratio = a2 / (a2 + b2);
    let otherwise = if a2.is_infinite() { 1.0 } else { 0.0 };
    if a2 + b2 > 0.0 && a2.is_finite() { ratio } else { otherwise }
}

impl PathTracer<'_> {
    /// Light arriving directly from the lights at `si` and scattered towards `wo`: each
    /// shadow ray and the light it brings unless blocked, handed to `shadows` in a fixed
    /// order.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn direct_light(
        &self,
        si: &SurfaceInteraction,
        bsdf: &Bsdf,
        wo: Vec3,
        time: f32,
        stream: &mut SampleStream,
        stats: &mut RenderStats,
        shadows: &mut impl ShadowSink,
    ) {
        let lights = &self.tracer.scene.lights;
        let p = si.surface.point;
        // Light from the side the surface faces; from both for rough glass, where the
        // shading normal must then agree with the surface about the side. Where the shading
        // normal alone decides (`Sides::Shading`), the BSDF's own cosines do.
        let transmits = bsdf.transmits();
        let shading_sides = self.spaces.shading_sides;
        let faces = |wi: Vec3| {
            let above = si.surface.normal.dot(wi) > 0.0;
            shading_sides
                || above && (!transmits || si.shading_normal.dot(wi) > 0.0)
                || transmits && !above && si.shading_normal.dot(wi) < 0.0
        };
        for light in &lights.points {
            let to_light = light.position - p;
            let dist2 = to_light.length_squared();
            let wi = to_light / dist2.sqrt();
            let (f_cos, _) = bsdf.eval(wo, wi);
            if f_cos == Vec3::ZERO || !faces(wi) || !(dist2 > 0.0) {
                continue;
            }
            let shadow =
                self.tracer.spawn.ray_to(&si.surface, &SurfacePoint::exact(light.position), time);
            shadows.shadow(shadow, f_cos * light.intensity_towards(-wi) / dist2, stats);
        }
        for light in &lights.directional {
            let wi = -light.direction;
            let (f_cos, _) = bsdf.eval(wo, wi);
            if f_cos == Vec3::ZERO || !faces(wi) {
                continue;
            }
            shadows.shadow(
                self.tracer.spawn.ray(&si.surface, wi, time),
                f_cos * light.irradiance,
                stats,
            );
        }
        if lights.has_emitters() {
            let n = self.light_samples as f32;
            for _ in 0..self.light_samples {
                // The light point takes the draw's best stratified pair, the light choice
                // the other two.
                let [u0, u1, u2, u3] = stream.next_4d();
                // A point on the shading point's own emitter is a sample like any other: a
                // concave emitter lights itself, and its BSDF hits are MIS-weighted against it.
                let Some(sample) = lights.sample_emitter(p, Vec2::new(u2, u3), Vec2::new(u0, u1))
                else {
                    continue;
                };
                let to_light = sample.point - p;
                let dist2 = to_light.length_squared();
                let wi = to_light / dist2.sqrt();
                let cos_light = sample.emitted_cosine(-wi);
                if !faces(wi) || !(cos_light > 0.0) || !(dist2 > 0.0) {
                    continue;
                }
                let (f_cos, pdf_bsdf) = bsdf.eval(wo, wi);
                if f_cos == Vec3::ZERO {
                    continue;
                }
                let target = SurfacePoint {
                    point: sample.point,
                    error: sample.error,
                    normal: sample.normal,
                };
                let shadow = self.tracer.spawn.ray_to(&si.surface, &target, time);
                let pdf_light = sample.pdf;
                // An invisible emitter (the course's area light) can never be found by the
                // BSDF sample either.
                let weight =
                    if sample.visible { power_heuristic(n * pdf_light, pdf_bsdf) } else { 1.0 };
                shadows.shadow(shadow, f_cos * sample.emission * (weight / (n * pdf_light)), stats);
            }
        }
        if let Some(environment) = lights.environment.as_ref().filter(|e| e.is_lit()) {
            let n = self.light_samples as f32;
            for _ in 0..self.light_samples {
                let Some(sample) = environment.sample(stream.next_2d()) else { continue };
                if !faces(sample.wi) {
                    continue;
                }
                let (f_cos, pdf_bsdf) = bsdf.eval(wo, sample.wi);
                if f_cos == Vec3::ZERO {
                    continue;
                }
                let weight = power_heuristic(n * sample.pdf, pdf_bsdf);
                let shadow = self.tracer.spawn.ray(&si.surface, sample.wi, time);
                shadows.shadow(
                    shadow,
                    f_cos * sample.radiance * (weight / (n * sample.pdf)),
                    stats,
                );
            }
        }
    }

    /// MIS weight of the environment's radiance found by BSDF sampling (density `pdf_bsdf`)
    /// along `dir`.
    pub(super) fn environment_weight(&self, dir: Vec3, pdf_bsdf: f32) -> f32 {
        match &self.tracer.scene.lights.environment {
            Some(environment) => {
                power_heuristic(pdf_bsdf, self.light_samples as f32 * environment.pdf(dir))
            }
            None => 1.0,
        }
    }

    /// MIS weight of emission found at `si` by BSDF sampling with density `pdf_bsdf` from
    /// the shading point `from`.
    pub(super) fn emission_weight(
        &self,
        from: Vec3,
        si: &SurfaceInteraction,
        pdf_bsdf: f32,
    ) -> f32 {
        let lights = &self.tracer.scene.lights;
        let point = si.surface.point;
        let Some(pdf_light) = lights.pdf(from, si.geom_id, si.prim_id, point, si.surface.normal)
        else {
            return 1.0; // not sampled by next-event estimation
        };
        power_heuristic(pdf_bsdf, self.light_samples as f32 * pdf_light)
    }
}

#[cfg(test)]
mod tests {
    use super::power_heuristic;

    #[test]
    fn power_heuristic_handles_extremes() {
        assert_eq!(power_heuristic(1.0, 0.0), 1.0);
        assert_eq!(power_heuristic(0.0, 0.0), 0.0);
        assert!((power_heuristic(1.0, 1.0) - 0.5).abs() < 1e-6);
    }
}
