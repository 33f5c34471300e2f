//! The principled BSDF's parameters as a material holds them (numbers or textures) and as
//! one hit sees them (numbers), for `bsdf::principled` and `bsdf::principled_thin`.

use super::texture::Texture;
use crate::scene::{ParamDesc, PrincipledDesc, SamplingRates};
use glam::Vec3;

/// A number, or a texture whose mean channel is looked up per hit.
#[derive(Clone, Debug, PartialEq)]
pub enum Param {
    Constant(f32),
    Texture(Texture),
}

impl Param {
    fn from_desc(desc: &ParamDesc) -> Self {
        match desc {
            ParamDesc::Constant(value) => Param::Constant(*value),
            ParamDesc::Texture(texture) => Param::Texture(Texture::from_desc(texture)),
        }
    }

    fn at(&self, lookup: &mut impl FnMut(&Texture) -> Vec3) -> f32 {
        match self {
            Param::Constant(value) => *value,
            Param::Texture(texture) => lookup(texture).element_sum() / 3.0,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct PrincipledMaterial {
    thin: bool,
    /// Some lobe transmits somewhere (a constant `spec_trans` of 0 does not).
    spec_trans_somewhere: bool,
    roughness: Param,
    anisotropic: Param,
    metallic: Param,
    spec_tint: Param,
    sheen: Param,
    sheen_tint: Param,
    clearcoat: Param,
    clearcoat_gloss: Param,
    spec_trans: Param,
    flatness: Param,
    diff_trans: Param,
    eta: Param,
    rates: SamplingRates,
}

/// The parameters at one hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipledParams {
    pub thin: bool,
    /// The material transmits somewhere: its inside is then told from its outside.
    pub spec_trans_somewhere: bool,
    pub base_color: Vec3,
    pub roughness: f32,
    pub anisotropic: f32,
    pub metallic: f32,
    pub spec_tint: f32,
    pub sheen: f32,
    pub sheen_tint: f32,
    pub clearcoat: f32,
    pub clearcoat_gloss: f32,
    pub spec_trans: f32,
    pub flatness: f32,
    /// Mitsuba's [0, 2] range halved, as its thin model uses it.
    pub diff_trans: f32,
    pub eta: f32,
    pub rates: SamplingRates,
}

impl PrincipledMaterial {
    pub fn from_desc(desc: &PrincipledDesc) -> Self {
        PrincipledMaterial {
            thin: desc.thin,
            spec_trans_somewhere: !desc.spec_trans.is_zero(),
            roughness: Param::from_desc(&desc.roughness),
            anisotropic: Param::from_desc(&desc.anisotropic),
            metallic: Param::from_desc(&desc.metallic),
            spec_tint: Param::from_desc(&desc.spec_tint),
            sheen: Param::from_desc(&desc.sheen),
            sheen_tint: Param::from_desc(&desc.sheen_tint),
            clearcoat: Param::from_desc(&desc.clearcoat),
            clearcoat_gloss: Param::from_desc(&desc.clearcoat_gloss),
            spec_trans: Param::from_desc(&desc.spec_trans),
            flatness: Param::from_desc(&desc.flatness),
            diff_trans: Param::from_desc(&desc.diff_trans),
            eta: Param::from_desc(&desc.eta),
            rates: desc.sampling_rates,
        }
    }

    /// The roughness differs along the tangent and the bitangent somewhere (the shading
    /// frame must then follow ∂p/∂u).
    pub fn is_anisotropic(&self) -> bool {
        self.anisotropic != Param::Constant(0.0)
    }

    /// The parameters at a hit whose base colour is `base_color`, each texture's colour
    /// there given by `lookup`.
    pub fn at(
        &self,
        base_color: Vec3,
        mut lookup: impl FnMut(&Texture) -> Vec3,
    ) -> PrincipledParams {
        let mut at = |param: &Param| param.at(&mut lookup);
        PrincipledParams {
            thin: self.thin,
            spec_trans_somewhere: self.spec_trans_somewhere,
            base_color,
            roughness: at(&self.roughness),
            anisotropic: at(&self.anisotropic),
            metallic: at(&self.metallic),
            spec_tint: at(&self.spec_tint),
            sheen: at(&self.sheen),
            sheen_tint: at(&self.sheen_tint),
            clearcoat: at(&self.clearcoat),
            clearcoat_gloss: at(&self.clearcoat_gloss),
            spec_trans: at(&self.spec_trans),
            flatness: at(&self.flatness),
            diff_trans: at(&self.diff_trans) / 2.0,
            eta: at(&self.eta),
            rates: self.rates,
        }
    }
}

impl PrincipledParams {
    /// The parameters of a material without textures (tests and tools).
    pub fn constant(desc: &PrincipledDesc, base_color: Vec3) -> Self {
        PrincipledMaterial::from_desc(desc).at(base_color, |_| Vec3::ZERO)
    }
}
