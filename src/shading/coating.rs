//! What a dielectric coating of relative index η lets through, for the plastic BSDF: the
//! fraction of light from outside that enters at each angle, and the fraction of light
//! diffused by the base that the coating reflects back inside. A smooth coating's are
//! Fresnel's (and the fit of its hemispherical mean Mitsuba uses); a rough coating's are
//! integrated once per material over the microfacets seen from each angle, as Mitsuba's
//! `roughplastic` tabulates them (64 angles, linear in cos θ).

use super::microfacet::Microfacet;
use crate::scene::Distribution;
use crate::shading::fresnel::fresnel_dielectric;
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use std::collections::HashMap;

/// Angles of the table, evenly spaced in cos θ over [0, 1].
const ANGLES: usize = 64;
/// Points per side of the grid over the sampled microfacets.
const GRID: usize = 48;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coating {
    eta: f32,
    /// Entering fraction at cos θ = i / (ANGLES − 1); none for a smooth coating (exact
    /// Fresnel instead).
    rough_transmittance: Option<[f32; ANGLES]>,
    /// Fraction of the base's diffuse light the coating sends back to the base.
    pub internal_reflectance: f32,
}

impl Coating {
    /// The coating of relative index `eta` (inside over outside), smooth or with the
    /// roughness of `microfacet`.
    pub fn new(eta: f32, microfacet: Option<Microfacet>) -> Self {
        let Some(microfacet) = microfacet else {
            let internal_reflectance = diffuse_fresnel_reflectance(1.0 / eta);
            return Coating { eta, rough_transmittance: None, internal_reflectance };
        };
        // The angles in parallel (about 15 ms a table on one core), summed in order.
        let at_angle = |i: usize| {
            let cos = (i as f32 / (ANGLES - 1) as f32).max(1e-6);
            let w = Vec3::new((1.0 - cos * cos).max(0.0).sqrt(), 0.0, cos);
            let enters = seen_through(&microfacet, w, eta, Passage::Enters);
            (enters, seen_through(&microfacet, w, 1.0 / eta, Passage::Reflected) * cos)
        };
        let angles: Vec<(f32, f32)> = (0..ANGLES).into_par_iter().map(at_angle).collect();
        let mut table = [0.0; ANGLES];
        let mut internal = 0.0;
        for (i, (enters, reflected)) in angles.into_iter().enumerate() {
            table[i] = enters;
            internal += reflected;
        }
        // Mitsuba's rule: twice the mean of R(μ)·μ over the table's angles.
        let internal_reflectance = 2.0 * internal / ANGLES as f32;
        Coating { eta, rough_transmittance: Some(table), internal_reflectance }
    }

    /// Fraction of light arriving from outside at `cos` to the normal that enters.
    pub fn transmittance(&self, cos: f32) -> f32 {
        match &self.rough_transmittance {
            None => 1.0 - fresnel_dielectric(cos, self.eta),
            Some(table) => {
                let x = cos.clamp(0.0, 1.0) * (ANGLES - 1) as f32;
                let i = (x as usize).min(ANGLES - 2);
                let t = x - i as f32;
                table[i] * (1.0 - t) + table[i + 1] * t
            }
        }
    }
}

/// A coating's index and roughness (α along and across, as bits), as `CoatingTables` keys it.
type CoatingKey = (u32, Option<(Distribution, u32, u32)>);

/// Coatings already integrated, by their index and roughness: the materials that share one
/// (a scene's plastics of one roughness in many colours) integrate it once.
#[derive(Default)]
pub struct CoatingTables {
    made: HashMap<CoatingKey, Coating>,
}

impl CoatingTables {
    /// `Coating::new(eta, microfacet)`, integrated the first time it is asked for.
    pub fn get(&mut self, eta: f32, microfacet: Option<Microfacet>) -> Coating {
        let roughness =
            microfacet.map(|m| (m.distribution, m.alpha_x.to_bits(), m.alpha_y.to_bits()));
        *self
            .made
            .entry((eta.to_bits(), roughness))
            .or_insert_with(|| Coating::new(eta, microfacet))
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Passage {
    Enters,
    Reflected,
}

/// The fraction of light from `w` that the rough interface of index `eta` refracts through
/// (or reflects), each microfacet's share masked on the way out (Smith's G1).
fn seen_through(microfacet: &Microfacet, w: Vec3, eta: f32, passage: Passage) -> f32 {
    let mut sum = 0.0f64;
    for i in 0..GRID {
        for j in 0..GRID {
            let u = Vec2::new((i as f32 + 0.5) / GRID as f32, (j as f32 + 0.5) / GRID as f32);
            let m = microfacet.sample(w, u);
            let pdf = microfacet.pdf(w, m);
            let cos_m = w.dot(m);
            if !(pdf > 0.0) || cos_m <= 0.0 {
                continue;
            }
            // Visible-normal density over the sampling density.
            let visible = microfacet.g1(w) * microfacet.d(m) * cos_m / w.z / pdf;
            let fresnel = fresnel_dielectric(cos_m, eta);
            let share = match passage {
                Passage::Reflected => {
                    let out = 2.0 * cos_m * m - w;
                    if out.z <= 0.0 {
                        continue;
                    }
                    fresnel * microfacet.g1(out)
                }
                Passage::Enters => {
                    let Some(out) = refract(w, m, eta) else { continue };
                    if out.z >= 0.0 || out.dot(m) >= 0.0 {
                        continue;
                    }
                    (1.0 - fresnel) * microfacet.g1(out)
                }
            };
            sum += (visible * share) as f64;
        }
    }
    (sum / (GRID * GRID) as f64) as f32
}

/// `w` refracted through the facet `m` (w·m > 0) into a medium `eta` times denser; none
/// under total internal reflection.
pub(crate) fn refract(w: Vec3, m: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = w.dot(m);
    let sin2_t = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((-w / eta + (cos_i / eta - cos_t) * m).normalize())
}

/// The hemispherical mean of Fresnel reflectance at relative index `eta`, as Mitsuba
/// approximates it (`fresnel_diffuse_reflectance`: Egan and Hilgeman's fit below 1,
/// d'Eon and Irving's above).
fn diffuse_fresnel_reflectance(eta: f32) -> f32 {
    let inv = 1.0 / eta;
    if eta < 1.0 {
        0.0636 * inv + eta * (eta * -1.4399 + 0.7099) + 0.6681
    } else {
        let coefficients = [0.919317, -3.4793, 6.75335, -7.80989, 4.98554, -1.36881];
        coefficients.iter().rev().fold(0.0, |acc, c| acc * inv + c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The hemispherical mean 2∫F(μ)μ dμ by a fine midpoint rule.
    fn exact_diffuse_reflectance(eta: f32) -> f32 {
        let n = 20_000;
        let sum: f64 = (0..n)
            .map(|i| {
                let mu = (i as f32 + 0.5) / n as f32;
                (fresnel_dielectric(mu, eta) * mu) as f64
            })
            .sum();
        (2.0 * sum / n as f64) as f32
    }

    #[test]
    fn the_fit_of_the_diffuse_fresnel_reflectance_is_close_to_the_integral() {
        for eta in [1.0 / 1.9, 1.0 / 1.5, 1.0 / 1.33, 1.33, 1.5, 1.9] {
            let (fit, exact) = (diffuse_fresnel_reflectance(eta), exact_diffuse_reflectance(eta));
            assert!((fit - exact).abs() < 0.01 * exact.max(0.05), "η {eta}: {fit} vs {exact}");
        }
    }

    #[test]
    fn a_slightly_rough_coating_lets_through_what_a_smooth_one_does() {
        for distribution in [Distribution::Ggx, Distribution::Beckmann] {
            let microfacet = Microfacet::isotropic(distribution, 0.01);
            let (rough, smooth) = (Coating::new(1.5, Some(microfacet)), Coating::new(1.5, None));
            for cos in [0.95, 0.7, 0.4] {
                let (r, s) = (rough.transmittance(cos), smooth.transmittance(cos));
                assert!((r - s).abs() < 5e-3, "{distribution:?} cos {cos}: {r} vs {s}");
            }
            let (r, s) = (rough.internal_reflectance, exact_diffuse_reflectance(1.0 / 1.5));
            assert!((r - s).abs() < 0.02, "{distribution:?}: internal {r} vs {s}");
        }
    }

    #[test]
    fn a_rough_coating_lets_less_through_at_grazing_angles_than_at_normal_incidence() {
        let microfacet = Microfacet::isotropic(Distribution::Ggx, 0.5);
        let coating = Coating::new(1.5, Some(microfacet));
        let (normal, grazing) = (coating.transmittance(1.0), coating.transmittance(0.1));
        assert!(normal > 0.9 && normal < 0.97, "{normal}");
        assert!(grazing < normal - 0.2, "{grazing} vs {normal}");
    }

    /// A table is integrated once per index and roughness, and is the one `new` makes.
    #[test]
    fn tables_are_shared_by_index_and_roughness() {
        let rough = |alpha| Some(Microfacet::isotropic(Distribution::Ggx, alpha));
        let mut tables = CoatingTables::default();
        let first = tables.get(1.5, rough(0.2));
        assert_eq!(first, Coating::new(1.5, rough(0.2)));
        assert_eq!(tables.get(1.5, rough(0.2)), first);
        assert_ne!(tables.get(1.5, rough(0.3)), first);
        assert_ne!(tables.get(1.4, rough(0.2)), first);
        let beckmann = Some(Microfacet::isotropic(Distribution::Beckmann, 0.2));
        assert_ne!(tables.get(1.5, beckmann), first);
        assert_eq!(tables.get(1.5, None), Coating::new(1.5, None));
        assert_eq!(tables.made.len(), 5);
    }
}
