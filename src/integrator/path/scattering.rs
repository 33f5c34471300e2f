//! The BSDF of a material at one hit: its textures looked up, its frame built, a mask's
//! opacity applied; a blend's two materials each so, then mixed.

use super::PathTracer;
use crate::shading::bsdf::Bsdf;
use crate::shading::material::Material;
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
        let bsdf = match &material.blend {
            Some(blend) => {
                let [first, second] = &blend.materials;
                let weight = self.opacity(&blend.weight, si, time);
                let frame = self.shading_frame(si.shading_normal);
                let parts = (self.scattering(first, si, time), self.scattering(second, si, time));
                Bsdf::blend(parts.0, parts.1, weight, frame)
            }
            None => self.own_scattering(material, si, time),
        };
        match &material.opacity {
            None => bsdf,
            Some(opacity) => bsdf.with_opacity(self.opacity(opacity, si, time)),
        }
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
