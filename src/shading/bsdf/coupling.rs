//! Energy coupling between the course's specular lobe and the rest of a material.
//!
//! The course adds its specular term (ks times a Phong-like lobe) to whatever else a
//! material does: a Lambertian part, a mirror, glass. Its own renderer does not conserve
//! energy (hw6's glass returns up to 1.3 times what arrives; Veach Ajar's floor, kd 0.98 +
//! mirror 0.3 + ks 0.5, up to 1.78), and on long paths that compounds without bound. Here
//! the lobe keeps what it reflects, and the other lobes give up, for the view at hand, just
//! what would make the sum exceed 1: a material that already conserves energy for that view
//! is left exactly as the course defines it. The lobe's directional albedo is tabulated per
//! material (`LobeAlbedo`), so the rest gives up no more than the lobe really takes.

use crate::shading::course_lobe::LobeAlbedo;
use glam::Vec3;

/// How the path tracer combines a material's lobes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Energy {
    /// No material reflects more than it receives: a mirror's Lambertian part gets
    /// `albedo · (1 − reflectance)`, albedos are clamped to 1, and the course's lobe takes
    /// its share from the rest (`Coupling`).
    #[default]
    Conserving,
    /// The CENG795 course's renderer: kd, the mirror's reflectance and the specular lobe
    /// added as they are, albedos above 1 included. Reproduces the instructor's path-traced
    /// images; such materials can reflect more than they receive, and on long paths (glass
    /// with its lobe, with Russian roulette) their estimates grow without bound.
    Additive,
}

impl Energy {
    /// The reflectance a Lambertian lobe of albedo `albedo` gets under this model.
    #[inline]
    pub fn lambertian(self, albedo: Vec3) -> Vec3 {
        match self {
            Energy::Conserving => albedo.clamp(Vec3::ZERO, Vec3::ONE),
            Energy::Additive => albedo.max(Vec3::ZERO),
        }
    }
}

crate::choice::named_choices!(Energy, "energy", {
    Conserving => "conserving",
    Additive => "additive",
});

#[derive(Clone, Copy, Debug)]
pub struct Coupling {
    /// The most the other lobes reflect or transmit, per channel.
    rest: Vec3,
    /// The lobe's specular reflectance (scaled down where the lobe alone would exceed 1).
    ks: Vec3,
    albedo: LobeAlbedo,
}

impl Coupling {
    /// `rest`: the other lobes' albedo; `ks` and the tabulated albedo of the course lobe.
    pub fn new(rest: Vec3, ks: Vec3, albedo: LobeAlbedo) -> Self {
        // A lobe that alone could reflect more than arrives reflects at most that.
        let ks = ks / (ks * albedo.max()).max(Vec3::ONE);
        Coupling { rest, ks, albedo }
    }

    /// The lobe's specular reflectance to evaluate it with.
    pub fn ks(&self) -> Vec3 {
        self.ks
    }

    /// What the lobe reflects of what arrives, for a view at `cos_o`.
    pub fn lobe_albedo(&self, cos_o: f32) -> Vec3 {
        self.ks * self.albedo.at(cos_o)
    }

    /// The factor for the other lobes, per channel, for a view at `cos_o`.
    pub fn rest_scale(&self, cos_o: f32) -> Vec3 {
        let room = (Vec3::ONE - self.lobe_albedo(cos_o)).max(Vec3::ZERO);
        Vec3::select(
            self.rest.cmpgt(room),
            room / self.rest.max(Vec3::splat(f32::MIN_POSITIVE)),
            Vec3::ONE,
        )
    }

    /// An upper bound of the whole material's albedo for a view at `cos_o`.
    pub fn total_albedo(&self, cos_o: f32) -> Vec3 {
        self.rest * self.rest_scale(cos_o) + self.lobe_albedo(cos_o)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::CourseBrdf;

    #[test]
    fn a_conserving_material_is_left_as_the_course_defines_it() {
        let lobe = CourseBrdf::ModifiedPhong { normalized: true };
        let table = LobeAlbedo::new(&lobe, 90.0);
        // kd 0.5 with ks 0.3: at most 0.8, nothing to give up.
        let c = Coupling::new(Vec3::splat(0.5), Vec3::splat(0.3), table);
        for cos_o in [0.05, 0.5, 1.0] {
            assert_eq!(c.rest_scale(cos_o), Vec3::ONE);
        }
        // Glass (1) with ks 0.3 gives up the lobe's share, more where the lobe takes more.
        let glass = Coupling::new(Vec3::ONE, Vec3::splat(0.3), table);
        let (head_on, grazing) = (glass.rest_scale(1.0).x, glass.rest_scale(0.2).x);
        assert!((head_on - 0.7).abs() < 0.01, "{head_on}");
        assert!(grazing > head_on && grazing < 1.0, "{grazing}");
        for cos_o in [0.0, 0.1, 0.3, 0.7, 1.0] {
            assert!((glass.total_albedo(cos_o).x - 1.0).abs() < 1e-5);
        }
    }

    #[test]
    fn the_table_agrees_with_the_normalized_phong_lobe_head_on() {
        // (p+2)/(2π) cos^p α cos θi reflects exactly 1 viewed along the normal.
        let lobe = CourseBrdf::ModifiedPhong { normalized: true };
        for p in [1.0, 20.0, 200.0, 600.0] {
            let head_on = LobeAlbedo::new(&lobe, p).at(1.0);
            assert!((head_on - 1.0).abs() < 3e-3, "p {p}: {head_on}");
        }
    }
}
