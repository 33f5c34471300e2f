//! Importance sampling of the specular term of the course's reflectance models
//! (`course_brdf`): directions drawn in proportion to the lobe's cos^p factor, in the local
//! shading frame (normal = +Z).
//!
//! * Phong models (`cos α_r`, α_r between wi and the mirror direction of wo): wi about the
//!   mirror direction with density (p+1)/(2π) cos^p α_r.
//! * Blinn-Phong models and Torrance-Sparrow (`cos α_h`, α_h between n and the half vector):
//!   h about n with density (p+1)/(2π) cos^p α_h, wi the reflection of wo about h; the
//!   density of wi is that of h over 4 (wo · h).
//!
//! Directions that end below the surface are returned as `None` (the lobe has nothing
//! there); the densities count them, so they integrate to at most 1 over the hemisphere.

use crate::sampling::{cosine_power_hemisphere, cosine_power_pdf, frame_from_normal};
use crate::scene::CourseBrdf;
use glam::{Vec2, Vec3};

/// Whether the model's lobe is about the mirror direction (else about the half vector).
fn about_mirror_direction(brdf: &CourseBrdf) -> bool {
    matches!(brdf, CourseBrdf::OriginalPhong | CourseBrdf::ModifiedPhong { .. })
}

fn mirror(wo: Vec3) -> Vec3 {
    Vec3::new(-wo.x, -wo.y, wo.z)
}

/// A direction for `wo` (local, wo.z > 0) drawn in proportion to the lobe of exponent `p`.
pub fn sample(brdf: &CourseBrdf, p: f32, wo: Vec3, u: Vec2) -> Option<Vec3> {
    let local = cosine_power_hemisphere(u, p);
    let wi = if about_mirror_direction(brdf) {
        frame_from_normal(mirror(wo)) * local
    } else {
        let h = local;
        let wo_h = wo.dot(h);
        if wo_h <= 0.0 {
            return None;
        }
        2.0 * wo_h * h - wo
    };
    (wi.z > 0.0 && wi.is_finite()).then(|| wi.normalize())
}

/// The density with which `sample` draws `wi` for `wo` (both local).
pub fn pdf(brdf: &CourseBrdf, p: f32, wo: Vec3, wi: Vec3) -> f32 {
    if wi.z <= 0.0 || wo.z <= 0.0 {
        return 0.0;
    }
    if about_mirror_direction(brdf) {
        return cosine_power_pdf(mirror(wo).dot(wi), p);
    }
    let h = (wo + wi).normalize_or_zero();
    let wo_h = wo.dot(h);
    if wo_h <= 0.0 {
        return 0.0;
    }
    cosine_power_pdf(h.z, p) / (4.0 * wo_h)
}

/// The lobe's directional albedo per unit of specular reflectance, ∫ f cos θi dωi / ks, as
/// a function of cos θo: tabulated once per material, by stratified sampling of the lobe's
/// own density (its weights f cos θi / pdf vary slowly, so 32² strata give it to about 0.1 %).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LobeAlbedo {
    /// At cos θo = i / (ENTRIES − 1).
    table: [f32; LobeAlbedo::ENTRIES],
}

impl LobeAlbedo {
    const ENTRIES: usize = 17;
    const STRATA: usize = 32;

    pub fn new(brdf: &CourseBrdf, p: f32) -> Self {
        use crate::shading::course_brdf::{CourseTerms, cos_weighted};
        let terms = CourseTerms { diffuse: Vec3::ZERO, specular: Vec3::ONE, exponent: p };
        let mut table = [0.0; Self::ENTRIES];
        for (i, entry) in table.iter_mut().enumerate() {
            // Exactly grazing views see nothing; take the nearest view that sees something.
            let cos_o = (i as f32 / (Self::ENTRIES - 1) as f32).max(1e-3);
            let wo = Vec3::new((1.0 - cos_o * cos_o).sqrt(), 0.0, cos_o);
            let mut sum = 0.0f64;
            for a in 0..Self::STRATA {
                for b in 0..Self::STRATA {
                    let u = Vec2::new(
                        (a as f32 + 0.5) / Self::STRATA as f32,
                        (b as f32 + 0.5) / Self::STRATA as f32,
                    );
                    let Some(wi) = sample(brdf, p, wo, u) else { continue };
                    let density = pdf(brdf, p, wo, wi);
                    if density > 0.0 {
                        sum += f64::from(cos_weighted(brdf, &terms, Vec3::Z, wi, wo).x / density);
                    }
                }
            }
            *entry = (sum / (Self::STRATA * Self::STRATA) as f64) as f32;
        }
        LobeAlbedo { table }
    }

    /// The albedo for a view at cos θo (clamped to [0, 1]), interpolated linearly.
    pub fn at(&self, cos_o: f32) -> f32 {
        let x = cos_o.clamp(0.0, 1.0) * (Self::ENTRIES - 1) as f32;
        let i = (x as usize).min(Self::ENTRIES - 2);
        let t = x - i as f32;
        self.table[i] * (1.0 - t) + self.table[i + 1] * t
    }

    /// The largest albedo over every view.
    pub fn max(&self) -> f32 {
        self.table.iter().copied().fold(0.0, f32::max)
    }
}
