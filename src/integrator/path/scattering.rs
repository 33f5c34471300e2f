//! The BSDF of a material at one hit: its textures looked up, its frame built, a mask's
//! opacity applied; a blend's two materials each so, then mixed.

use super::PathTracer;
use crate::shading::bsdf::Bsdf;
use crate::shading::material::{Blend, Material};
use crate::shading::surface::SurfaceInteraction;
use glam::Vec3;

impl PathTracer<'_> {
    /// The BSDF of `material` at `si` (shading normal already mapped).
    pub(super) fn scattering(
        &self,
        material: &Material,
        si: &SurfaceInteraction,
        time: f32,
    ) -> Bsdf {
        if material.blend.is_none() && material.opacity.is_none() {
            // Returned as it is built: a `Bsdf` is a few hundred bytes, and a value bound
            // and returned again was copied once more on every hit.
            return self.own_scattering(material, si, time);
        }
        let mut bsdf = match &material.blend {
            Some(blend) => self.blend_scattering(blend, si, time),
            None => self.own_scattering(material, si, time),
        };
        self.mask(material, &mut bsdf, si, time);
        bsdf
    }

    /// Puts `bsdf` under `material`'s mask, if it has one.
    fn mask(&self, material: &Material, bsdf: &mut Bsdf, si: &SurfaceInteraction, time: f32) {
        if let Some(opacity) = &material.opacity {
            bsdf.set_opacity(self.opacity(opacity, si, time));
        }
    }

    /// A blend's BSDF (blends of blends by recursion here, so that `scattering`, which every
    /// hit calls, is not recursive and may be inlined).
    #[cold]
    #[inline(never)]
    fn blend_scattering(&self, blend: &Blend, si: &SurfaceInteraction, time: f32) -> Bsdf {
        let part = |material: &Material| {
            let mut bsdf = match &material.blend {
                Some(inner) => self.blend_scattering(inner, si, time),
                None => self.own_scattering(material, si, time),
            };
            self.mask(material, &mut bsdf, si, time);
            bsdf
        };
        let [first, second] = &blend.materials;
        let weight = self.opacity(&blend.weight, si, time);
        let frame = self.shading_frame(si.shading_normal);
        Bsdf::blend(part(first), part(second), weight, frame)
    }

    /// The BSDF of `material`'s own lobes.
    fn own_scattering(&self, material: &Material, si: &SurfaceInteraction, time: f32) -> Bsdf {
        let albedo = self.tracer.surface_albedo(material, si, time);
        let course_specular = match (&material.specular_texture, &material.phong) {
            (Some(t), Some(_)) => self.tracer.texture_color(t, si, time),
            (_, phong) => phong.as_ref().map_or(Vec3::ZERO, |p| p.specular),
        };
        let frame = if material.is_anisotropic() {
            self.tangent_frame(si, time)
        } else {
            self.shading_frame(si.shading_normal)
        };
        let roughness = material.roughness_textures.as_deref().map(|[u, v]| {
            let alpha = |t| self.tracer.texture_color(t, si, time).element_sum() / 3.0;
            (alpha(u), alpha(v))
        });
        match &material.principled {
            Some(principled) => {
                let at = principled.at(albedo, |t| self.tracer.texture_color(t, si, time));
                Bsdf::principled(&at, frame, si.front_face, material.one_sided)
            }
            None => Bsdf::with_reflectances(
                material,
                albedo,
                course_specular,
                roughness,
                frame,
                si.front_face,
                self.energy,
            ),
        }
    }
}
