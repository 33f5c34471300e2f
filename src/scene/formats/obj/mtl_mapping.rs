//! What an MTL material's values mean to embray (README.md, "OBJ materials", has the table):
//! `illum` (or, without it, `Ks`, `Pr` and `Pm`) chooses the specular lobe, `Ns` (or `Pr`) its
//! roughness, `d`/`Tr` a mask; every value a lobe cannot show is a note.

use super::mtl_material::{At, Given, Problem};
use super::mtl_notes::Note;
use crate::scene::desc::{Distribution, MaterialDesc, Opacity, Specular};
use glam::Vec3;

/// The specular part an MTL material gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Lobe {
    /// Lambertian `Kd` only (`illum` 0, 1, 10, or no `Ks`).
    Diffuse,
    /// `Kd` under a white dielectric coating as strong as `Ks`'s mean (`illum` 2).
    Plastic,
    /// `Kd` and a mirror of reflectance `Ks` (`illum` 3, 5, 8).
    Mirror,
    /// A mirror of reflectance `Kd`, no diffuse part (`Pm` ≥ ½).
    Metal,
    /// Glass of index `Ni` (`illum` 4, 6, 7, 9).
    Glass,
}

/// The `Ns` from which a surface counts as perfectly smooth: the top of the range the MTL
/// specification gives (exporters clamp there; Blender writes it for roughness 0).
const SMOOTH_NS: f32 = 1000.0;

/// The index of refraction glass gets without `Ni`.
const GLASS_IOR: f32 = 1.5;

/// A principled material's specular level without `Ks` (Blender's default 0.5: F0 = 0.04).
const DEFAULT_KS: f32 = 0.5;

fn nonzero(c: Option<At<Vec3>>) -> bool {
    c.is_some_and(|c| c.value.max_element() > 0.0)
}

impl Given<'_> {
    /// `Pr` or `Pm`: the PBR extension (tinyobjloader's, Blender's), whose materials are
    /// principled ones: a dielectric has a specular layer even without `Ks`.
    fn principled(&self) -> bool {
        self.pr.is_some() || self.pm.is_some()
    }

    /// The lobe by `Pm`, then `illum`, then (without `illum`) whether there is a highlight.
    pub fn lobe(&self, notes: &mut Vec<Note>) -> Lobe {
        if let Some(pm) = self.pm {
            let metal = pm.value >= 0.5;
            if pm.value > 0.0 && pm.value < 1.0 {
                notes.push(Note::new(
                    pm.line,
                    format!(
                        "Pm between 0 and 1 (a partly metallic surface) is not modelled: read as {}",
                        if metal { 1 } else { 0 }
                    ),
                ));
            }
            if metal {
                return Lobe::Metal;
            }
        }
        let highlight = nonzero(self.ks) || (self.principled() && self.ks.is_none());
        let no_highlight = |notes: &mut Vec<Note>, illum: u8| {
            if let Some(ks) = self.ks.filter(|_| nonzero(self.ks)) {
                let message = format!("Ks is not used: illum {illum} has no specular highlight");
                notes.push(Note::new(ks.line, message));
            }
            Lobe::Diffuse
        };
        let Some(illum) = self.illum else {
            return if highlight { Lobe::Plastic } else { Lobe::Diffuse };
        };
        let line = illum.line;
        match illum.value {
            0 => {
                notes.push(Note::new(
                    line,
                    "illum 0 (a constant colour, unlit) is shaded as illum 1 (Lambertian)",
                ));
                no_highlight(notes, 0)
            }
            1 => no_highlight(notes, 1),
            2 if highlight => Lobe::Plastic,
            3 | 5 | 8 if nonzero(self.ks) => {
                if illum.value == 5 {
                    notes.push(Note::new(
                        line,
                        "illum 5's Fresnel reflection is not modelled: the mirror reflects Ks at \
                         every angle",
                    ));
                }
                Lobe::Mirror
            }
            2 | 3 | 5 | 8 => Lobe::Diffuse,
            4 | 6 | 7 | 9 => Lobe::Glass,
            10 => {
                notes.push(Note::new(
                    line,
                    "illum 10 (shadows cast onto invisible surfaces) is not modelled: shaded as \
                     illum 1",
                ));
                no_highlight(notes, 10)
            }
            n => {
                notes.push(Note::new(
                    line,
                    format!("illum {n} is not one of MTL's models (0 to 10): read as if absent"),
                ));
                if highlight { Lobe::Plastic } else { Lobe::Diffuse }
            }
        }
    }

    /// The lobe's α and its distribution: `Pr`² (GGX, the principled convention) where given,
    /// else from the Blinn-Phong exponent `Ns` the Beckmann α = √(2 / (Ns + 2)) whose
    /// highlight has the same shape (Walter et al. 2007's Phong–Beckmann correspondence
    /// αp = 2 αb⁻² − 2); smooth without either and from `SMOOTH_NS`.
    pub fn roughness(&self) -> (f32, Distribution) {
        match (self.pr, self.ns) {
            (Some(pr), _) => (pr.value * pr.value, Distribution::Ggx),
            (None, Some(ns)) if ns.value < SMOOTH_NS => {
                ((2.0 / (ns.value + 2.0)).sqrt(), Distribution::Beckmann)
            }
            _ => (0.0, Distribution::Ggx),
        }
    }

    /// The material without its textures, and its lobe.
    pub fn material(&self, notes: &mut Vec<Note>) -> Result<(MaterialDesc, Lobe), Problem> {
        let lobe = self.lobe(notes);
        let kd = self.kd.map_or(Vec3::splat(0.8), |kd| kd.value);
        let ks = self.ks.map_or(Vec3::splat(DEFAULT_KS), |ks| ks.value);
        let mut material = MaterialDesc {
            albedo: kd,
            emission: self.ke.map_or(Vec3::ZERO, |ke| ke.value),
            ..Default::default()
        };
        material.specular = match lobe {
            Lobe::Diffuse => Specular::None,
            Lobe::Plastic => {
                if ks.max_element() - ks.min_element() > 1e-3 {
                    notes.push(Note::new(
                        self.ks.map_or(0, |k| k.line),
                        "Ks's tint is not modelled: the coating reflects white, as strongly as \
                         Ks's mean",
                    ));
                }
                Specular::Plastic { ior: coating_ior(ks.element_sum() / 3.0), nonlinear: false }
            }
            Lobe::Mirror => Specular::Mirror { reflectance: ks },
            Lobe::Metal => {
                material.albedo = Vec3::ZERO;
                Specular::Mirror { reflectance: kd }
            }
            Lobe::Glass => {
                let ior = match self.ni {
                    None => GLASS_IOR,
                    Some(ni) if ni.value > 0.0 => ni.value,
                    Some(ni) => {
                        return Err((
                            ni.line,
                            format!("Ni is {}, but glass needs Ni > 0", ni.value),
                        ));
                    }
                };
                if let Some(kd) = self.kd.filter(|_| nonzero(self.kd)) {
                    notes.push(Note::new(kd.line, "Kd is not used: glass has no diffuse part"));
                }
                Specular::dielectric(ior, Vec3::ZERO)
            }
        };
        if lobe != Lobe::Diffuse {
            (material.roughness, material.distribution) = self.roughness();
        }
        if let Some(ni) = self.ni.filter(|ni| lobe != Lobe::Glass && ni.value <= 0.0) {
            let message = "Ni is not an index of refraction (it must be > 0); only glass reads it";
            notes.push(Note::new(ni.line, message));
        }
        if nonzero(self.ka) {
            let line = self.ka.map_or(0, |ka| ka.line);
            notes.push(Note::new(line, "Ka (an ambient colour) is not used"));
        }
        if let Some(tf) = self.tf.filter(|tf| tf.value != Vec3::ONE) {
            notes.push(Note::new(tf.line, "Tf (a transmission filter) is not modelled"));
        }
        material.opacity = self.opacity(notes).map(Opacity::Constant);
        Ok((material, lobe))
    }

    /// `d`, else 1 − `Tr`; `None` for opaque.
    fn opacity(&self, notes: &mut Vec<Note>) -> Option<f32> {
        let opacity = match (self.d, self.tr) {
            (Some(d), Some(tr)) => {
                if (d.value - (1.0 - tr.value)).abs() > 1e-6 {
                    notes.push(Note::new(tr.line, "Tr is not 1 − d: d is used"));
                }
                d.value
            }
            (Some(d), None) => d.value,
            (None, Some(tr)) => {
                if tr.value == 1.0 {
                    notes.push(Note::new(
                        tr.line,
                        "Tr 1 (fully transparent) hides the surface; some exporters write Tr \
                         for the opacity: if this one does, write d 1",
                    ));
                }
                1.0 - tr.value
            }
            (None, None) => 1.0,
        };
        (opacity < 1.0).then_some(opacity)
    }
}

/// The index of a coating whose reflectance at normal incidence is 0.08 × `ks` (the
/// principled convention: Ks 0.5 → 0.04, index 1.5).
pub(super) fn coating_ior(ks: f32) -> f32 {
    let root = (0.08 * ks.clamp(0.0, 1.0)).sqrt();
    (1.0 + root) / (1.0 - root)
}
