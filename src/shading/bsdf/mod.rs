//! Scattering at a surface, by the kind of material: the mixture most materials are
//! (`mixture`: Lambertian, mirror, metal, smooth glass, the course's lobes), a dielectric
//! coating over a Lambertian base (`plastic`), rough glass (`rough_dielectric`), a thin
//! sheet of glass (`thin_dielectric`), Mitsuba's
//! principled models (`principled`, `principled_thin`). A mask's
//! opacity wraps any of them: the rest of the light passes through unchanged. Directions
//! are in render space; `frame` maps the local shading frame (normal = +Z) to it.

mod blend;
mod coupling;
mod mixture;
mod plastic;
mod principled;
mod principled_terms;
mod principled_thin;
mod rough_dielectric;
mod thin_dielectric;

pub use coupling::Energy;

use crate::scene::Specular;
use crate::shading::coating::Coating;
use crate::shading::material::{Material, SMOOTH_ROUGHNESS};
use blend::Blend;
use glam::{Mat3, Vec2, Vec3};
use mixture::Mixture;
use plastic::Plastic;
use principled::Principled;
use principled_thin::PrincipledThin;
use rough_dielectric::RoughDielectric;
use thin_dielectric::ThinDielectric;

/// A sampled scattering direction.
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    pub wi: Vec3,
    /// f · |cos θ| / pdf.
    pub weight: Vec3,
    /// (η_t/η_i)² for a refraction, else 1: undoes the radiance compression `weight`
    /// includes, so that Russian roulette can judge a path by its energy (pbrt's etaScale).
    pub eta_scale: f32,
    /// Density of `wi` (0 for a delta lobe).
    pub pdf: f32,
    pub delta: bool,
    /// The direction passes through the surface (refraction, or `passes`).
    pub transmitted: bool,
    /// The light went on as if the surface were not there (a mask's transparent part).
    pub passes: bool,
}

impl BsdfSample {
    /// A sample of a smooth (non-delta) lobe, `value` = f·cos and `pdf` the whole BSDF's
    /// (for MIS to be consistent); none where the density is 0.
    fn smooth(wi: Vec3, value: Vec3, pdf: f32) -> Option<Self> {
        (pdf > 0.0).then(|| Self::smooth_weighted(wi, value / pdf, pdf))
    }

    /// A reflected sample of a non-delta lobe whose weight f·cos/pdf is known (`pdf` > 0).
    fn smooth_weighted(wi: Vec3, weight: Vec3, pdf: f32) -> Self {
        BsdfSample {
            wi,
            weight,
            eta_scale: 1.0,
            pdf,
            delta: false,
            transmitted: false,
            passes: false,
        }
    }

    /// Straight on through the surface, unchanged.
    fn pass_through(wo: Vec3) -> Self {
        BsdfSample {
            wi: -wo,
            weight: Vec3::ONE,
            eta_scale: 1.0,
            pdf: 0.0,
            delta: true,
            transmitted: true,
            passes: true,
        }
    }
}

#[derive(Clone, Debug)]
enum Scatter {
    Mixture(Mixture),
    Plastic(Plastic),
    RoughDielectric(RoughDielectric),
    Blend(Box<Blend>),
    Principled(Principled),
    PrincipledThin(PrincipledThin),
    ThinDielectric(ThinDielectric),
    /// A one-sided material seen from behind.
    Black,
}

/// The scattering function at one shading point.
#[derive(Clone, Debug)]
pub struct Bsdf {
    scatter: Scatter,
    /// Local (tangent, bitangent, normal) → render space, for the kinds other than the
    /// mixture (which keeps its own).
    frame: Mat3,
    /// The fraction of the light that meets the surface; the rest passes through.
    opacity: f32,
    /// The shading normal before a normal or bump map changed it, when the mapped normal
    /// is shaded as Mitsuba does (`with_bump_shadowing`).
    unmapped: Option<Vec3>,
}

impl Bsdf {
    /// The BSDF of `material` with Lambertian reflectance `albedo` (its texture's value here).
    pub fn new(material: &Material, albedo: Vec3, frame: Mat3, front_face: bool) -> Self {
        let course_specular = material.phong.as_ref().map_or(Vec3::ZERO, |p| p.specular);
        let energy = Energy::Conserving;
        let roughness = None;
        Self::with_reflectances(
            material,
            albedo,
            course_specular,
            roughness,
            frame,
            front_face,
            energy,
        )
    }

    /// `new` with the course model's specular reflectance given (a `specular_texture`'s
    /// value here) instead of the material's `phong.specular`, and the `energy` model.
    pub fn with_reflectances(
        material: &Material,
        albedo: Vec3,
        course_specular: Vec3,
        roughness: Option<(f32, f32)>,
        frame: Mat3,
        front_face: bool,
        energy: Energy,
    ) -> Self {
        let (rough, microfacet) = match roughness {
            None => (material.is_rough(), material.microfacet()),
            Some((u, v)) => (u.max(v) >= SMOOTH_ROUGHNESS, material.microfacet_at((u, v))),
        };
        let scatter = match material.specular {
            Specular::Dielectric { ior, reflectance, transmittance, .. } if rough => {
                let tints = [reflectance, transmittance];
                Scatter::RoughDielectric(RoughDielectric::new(ior, front_face, microfacet, tints))
            }
            // Two-sided by nature, and never rough (Mitsuba has no rough sheet).
            Specular::ThinDielectric { ior, reflectance, transmittance } => {
                Scatter::ThinDielectric(ThinDielectric::new(ior, reflectance, transmittance))
            }
            _ if material.one_sided && !front_face && !material.is_dielectric() => Scatter::Black,
            Specular::Plastic { ior, nonlinear } => {
                let coating = material
                    .coating
                    .as_deref()
                    .copied()
                    .unwrap_or_else(|| Coating::new(ior, rough.then_some(microfacet)));
                let microfacet = rough.then_some(microfacet);
                Scatter::Plastic(Plastic::new(albedo, ior, nonlinear, microfacet, coating))
            }
            _ => Scatter::Mixture(Mixture::with_reflectances(
                material,
                albedo,
                course_specular,
                microfacet,
                frame,
                front_face,
                energy,
            )),
        };
        Bsdf { scatter, frame, opacity: 1.0, unmapped: None }
    }

    /// `weight` (in [0, 1]) of `second`'s scattering and the rest of `first`'s, in `frame`
    /// (the parts keep their own frames).
    pub fn blend(first: Bsdf, second: Bsdf, weight: f32, frame: Mat3) -> Self {
        let blend = Blend::new(first, second, weight.clamp(0.0, 1.0));
        Bsdf { scatter: Scatter::Blend(Box::new(blend)), frame, opacity: 1.0, unmapped: None }
    }

    /// Mitsuba's principled BSDF with the parameters `p` of this hit. Its inside is told
    /// from its outside where it is one-sided (Mitsuba's own) or transmits (a two-sided
    /// wrapper sees the front from both sides, which only an opaque one allows).
    pub fn principled(
        p: &crate::shading::principled::PrincipledParams,
        frame: Mat3,
        front_face: bool,
        one_sided: bool,
    ) -> Self {
        let scatter = if p.thin {
            Scatter::PrincipledThin(PrincipledThin::new(p))
        } else {
            let mitsuba_frame = front_face || !one_sided && !p.spec_trans_somewhere;
            Scatter::Principled(Principled::new(p, mitsuba_frame))
        };
        Bsdf { scatter, frame, opacity: 1.0, unmapped: None }
    }

    /// This BSDF under a mask: only `opacity` of the light meets it, the rest passes on.
    pub fn with_opacity(mut self, opacity: f32) -> Self {
        self.set_opacity(opacity);
        self
    }

    /// As `with_opacity`, in place (a `Bsdf` is a few hundred bytes: the integrator
    /// changes its own rather than copying it).
    pub fn set_opacity(&mut self, opacity: f32) {
        self.opacity = opacity.clamp(0.0, 1.0);
    }

    /// This BSDF on a surface whose shading normal `unmapped` a map replaced by the frame's:
    /// light must arrive on the same side of both, and is shadowed by Estevez et al.'s
    /// microfacet term for the bump terminator (Ray Tracing Gems, 2019), as in Mitsuba.
    pub fn with_bump_shadowing(mut self, unmapped: Vec3) -> Self {
        self.set_bump_shadowing(unmapped);
        self
    }

    /// As `with_bump_shadowing`, in place.
    pub fn set_bump_shadowing(&mut self, unmapped: Vec3) {
        self.unmapped = Some(unmapped);
    }

    /// The bump terminator's shadowing of light from `wi` on a mapped normal whose
    /// unmapped one is `unmapped`, or none if `wi` is on different sides of the two.
    fn bump_shadowing(&self, unmapped: Vec3, wi: Vec3) -> Option<f32> {
        let mapped = self.frame.z_axis;
        let cos_unmapped = wi.dot(unmapped);
        if cos_unmapped * wi.dot(mapped) <= 0.0 {
            return None;
        }
        let tan2 = |cos: f32| (1.0 - cos * cos).max(0.0) / (cos * cos);
        let alpha2 = (0.125 * tan2(mapped.dot(unmapped))).min(1.0);
        Some(2.0 / (1.0 + (1.0 + alpha2 * tan2(cos_unmapped)).sqrt()))
    }

    /// True if light sampling can contribute (some lobe is not a delta distribution).
    pub fn has_smooth_lobe(&self) -> bool {
        self.has_smooth_lobe_at::<false>()
    }

    // A blend's parts are never blends (`Bsdf::blend` flattens them); each method has a
    // `LEAF` form for them, which knows no blend, so that no method calls itself and the
    // compiler may inline them into the integrator as it did before blends existed.
    pub(super) fn has_smooth_lobe_at<const LEAF: bool>(&self) -> bool {
        self.opacity > 0.0
            && match &self.scatter {
                Scatter::Mixture(m) => m.has_smooth_lobe(),
                Scatter::Plastic(_)
                | Scatter::RoughDielectric(_)
                | Scatter::Principled(_)
                | Scatter::PrincipledThin(_) => true,
                Scatter::Blend(b) => !LEAF && b.has_smooth_lobe(),
                Scatter::ThinDielectric(_) | Scatter::Black => false,
            }
    }

    /// True if light arriving from behind the surface can be scattered towards the front
    /// (rough glass, a principled material's transmission): light sampling must then look
    /// on both sides.
    pub fn transmits(&self) -> bool {
        self.transmits_at::<false>()
    }

    pub(super) fn transmits_at<const LEAF: bool>(&self) -> bool {
        match &self.scatter {
            Scatter::RoughDielectric(_) => true,
            Scatter::Blend(b) => !LEAF && b.transmits(),
            Scatter::Principled(p) => p.transmits(),
            Scatter::PrincipledThin(p) => p.transmits(),
            _ => false,
        }
    }

    /// An upper bound of the fraction of energy arriving from `wo` (render space) that this
    /// BSDF reflects or transmits, per channel: at most 1 by construction. Except for the
    /// principled models, which are not energy-conserving (their retro-reflection and sheen
    /// add to the diffuse lobe): their base colour, as Mitsuba's denoiser albedo is.
    pub fn albedo_bound(&self, wo: Vec3) -> Vec3 {
        self.albedo_bound_at::<false>(wo)
    }

    pub(super) fn albedo_bound_at<const LEAF: bool>(&self, wo: Vec3) -> Vec3 {
        let met = match &self.scatter {
            Scatter::Mixture(m) => m.albedo_bound(wo),
            Scatter::Plastic(p) => p.albedo_bound(),
            Scatter::RoughDielectric(_) => Vec3::ONE,
            Scatter::Blend(b) if !LEAF => b.albedo_bound(wo),
            Scatter::Principled(p) => p.base_color().clamp(Vec3::ZERO, Vec3::ONE),
            Scatter::PrincipledThin(p) => p.base_color().clamp(Vec3::ZERO, Vec3::ONE),
            Scatter::ThinDielectric(t) => t.albedo(self.frame.transpose() * wo),
            Scatter::Black | Scatter::Blend(_) => Vec3::ZERO,
        };
        met * self.opacity + Vec3::splat(1.0 - self.opacity)
    }

    /// f · |cos θi| and the density of sampling `wi`, for the non-delta lobes.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        self.eval_at::<false>(wo, wi)
    }

    pub(super) fn eval_at<const LEAF: bool>(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        let local = |w: Vec3| self.frame.transpose() * w;
        let (value, pdf) = match &self.scatter {
            Scatter::Mixture(m) => m.eval(wo, wi),
            Scatter::Plastic(p) => p.eval(local(wo), local(wi)),
            Scatter::RoughDielectric(d) => d.eval(local(wo), local(wi)),
            Scatter::Blend(b) if !LEAF => b.eval(wo, wi),
            Scatter::Principled(p) => p.eval(local(wo), local(wi)),
            Scatter::PrincipledThin(p) => p.eval(local(wo), local(wi)),
            Scatter::ThinDielectric(_) | Scatter::Black | Scatter::Blend(_) => (Vec3::ZERO, 0.0),
        };
        let value = match self.unmapped {
            None => value,
            Some(unmapped) => match self.bump_shadowing(unmapped, wi) {
                Some(shadowing) => value * shadowing,
                None => return (Vec3::ZERO, 0.0),
            },
        };
        if self.opacity == 1.0 { (value, pdf) } else { (value * self.opacity, pdf * self.opacity) }
    }

    /// Samples an incident direction for outgoing `wo` (both render space).
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        self.sample_at::<false>(wo, u_lobe, u)
    }

    pub(super) fn sample_at<const LEAF: bool>(
        &self,
        wo: Vec3,
        u_lobe: f32,
        u: Vec2,
    ) -> Option<BsdfSample> {
        if u_lobe >= self.opacity {
            return Some(BsdfSample::pass_through(wo));
        }
        // The weights f·cos/pdf of the rest are unchanged: both carry the opacity.
        let u_lobe = if self.opacity == 1.0 { u_lobe } else { u_lobe / self.opacity };
        // The mixture and a blend's parts keep their own frames; the other kinds work in the
        // local one.
        let local = || self.frame.transpose() * wo;
        let mut sample = match &self.scatter {
            Scatter::Mixture(m) => return m.sample(wo, u_lobe, u).and_then(|s| self.masked(s)),
            Scatter::Blend(b) if !LEAF => {
                return b.sample(wo, u_lobe, u).and_then(|s| self.masked(s));
            }
            Scatter::Plastic(p) => p.sample(local(), u_lobe, u)?,
            Scatter::RoughDielectric(d) => d.sample(local(), u_lobe, u)?,
            Scatter::Principled(p) => p.sample(local(), u_lobe, u)?,
            Scatter::PrincipledThin(p) => p.sample(local(), u_lobe, u)?,
            Scatter::ThinDielectric(t) => t.sample(local(), u_lobe),
            Scatter::Black | Scatter::Blend(_) => return None,
        };
        sample.wi = self.frame * sample.wi;
        self.masked(sample)
    }

    /// A sample of the scattering part with its density as the whole mask's, and shadowed
    /// at the bump terminator.
    fn masked(&self, mut sample: BsdfSample) -> Option<BsdfSample> {
        if self.opacity != 1.0 {
            sample.pdf *= self.opacity;
        }
        if let Some(unmapped) = self.unmapped {
            sample.weight *= self.bump_shadowing(unmapped, sample.wi)?;
        }
        Some(sample)
    }
}

#[cfg(test)]
mod test_grid;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_blend;
#[cfg(test)]
mod tests_kinds;
#[cfg(test)]
mod tests_principled;
