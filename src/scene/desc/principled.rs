//! Disney's principled BSDF as Mitsuba 3 defines it (`principled`, `principledthin`): a base
//! colour (the material's `albedo`, or its `texture`) and weights that each may vary over
//! the surface. Parameter names, ranges and defaults are Mitsuba's.

use super::texture::TextureDesc;

/// One scalar parameter: a number, or a texture's mean channel looked up per hit.
#[derive(Clone, Debug, PartialEq)]
pub enum ParamDesc {
    Constant(f32),
    Texture(TextureDesc),
}

impl ParamDesc {
    /// Zero everywhere: the lobe it weights is absent (Mitsuba leaves it out then).
    pub fn is_zero(&self) -> bool {
        *self == ParamDesc::Constant(0.0)
    }

    pub fn texture(&self) -> Option<&TextureDesc> {
        match self {
            ParamDesc::Constant(_) => None,
            ParamDesc::Texture(texture) => Some(texture),
        }
    }
}

/// The relative probabilities with which the lobes are sampled (Mitsuba's `*_sampling_rate`;
/// `principled`'s `main_specular_sampling_rate` sets both specular ones).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SamplingRates {
    pub specular_reflectance: f32,
    pub specular_transmittance: f32,
    pub clearcoat: f32,
    pub diffuse_reflectance: f32,
    pub diffuse_transmittance: f32,
}

impl Default for SamplingRates {
    fn default() -> Self {
        SamplingRates {
            specular_reflectance: 1.0,
            specular_transmittance: 1.0,
            clearcoat: 1.0,
            diffuse_reflectance: 1.0,
            diffuse_transmittance: 1.0,
        }
    }
}

impl SamplingRates {
    /// Every rate the model (`thin` or not) reads is 0: no lobe would ever be sampled, and
    /// the image would be dark without a word.
    pub fn samples_nothing(&self, thin: bool) -> bool {
        let read: &[f32] = if thin {
            &[
                self.specular_reflectance,
                self.specular_transmittance,
                self.diffuse_transmittance,
                self.diffuse_reflectance,
            ]
        } else {
            &[self.specular_reflectance, self.clearcoat, self.diffuse_reflectance]
        };
        read.iter().all(|&rate| rate == 0.0)
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct PrincipledDesc {
    /// `principledthin`: a two-sided sheet (no interior), with diffuse transmission.
    pub thin: bool,
    pub roughness: ParamDesc,
    pub anisotropic: ParamDesc,
    /// Not in the thin model.
    pub metallic: ParamDesc,
    pub spec_tint: ParamDesc,
    pub sheen: ParamDesc,
    pub sheen_tint: ParamDesc,
    /// Not in the thin model.
    pub clearcoat: ParamDesc,
    /// Not in the thin model.
    pub clearcoat_gloss: ParamDesc,
    pub spec_trans: ParamDesc,
    pub flatness: ParamDesc,
    /// The thin model's only, in [0, 2] as Mitsuba takes it.
    pub diff_trans: ParamDesc,
    /// Interior over exterior index; a constant except in the thin model (`principled`'s
    /// `specular` is converted to it).
    pub eta: ParamDesc,
    pub sampling_rates: SamplingRates,
}

impl PrincipledDesc {
    /// Mitsuba's defaults: roughness 0.5, specular 0.5 (η 1.5) or thin η 1.5, the rest 0.
    pub fn new(thin: bool) -> Self {
        let zero = || ParamDesc::Constant(0.0);
        let eta = if thin { 1.5 } else { eta_from_specular(0.5) };
        PrincipledDesc {
            thin,
            roughness: ParamDesc::Constant(0.5),
            anisotropic: zero(),
            metallic: zero(),
            spec_tint: zero(),
            sheen: zero(),
            sheen_tint: zero(),
            clearcoat: zero(),
            clearcoat_gloss: zero(),
            spec_trans: zero(),
            flatness: zero(),
            diff_trans: zero(),
            eta: ParamDesc::Constant(eta),
            sampling_rates: SamplingRates::default(),
        }
    }

    /// Every parameter with its Mitsuba name, the ones the model does not read left out.
    pub fn params(&self) -> Vec<(&'static str, &ParamDesc)> {
        let mut params = vec![
            ("roughness", &self.roughness),
            ("anisotropic", &self.anisotropic),
            ("spec_tint", &self.spec_tint),
            ("sheen", &self.sheen),
            ("sheen_tint", &self.sheen_tint),
            ("spec_trans", &self.spec_trans),
            ("flatness", &self.flatness),
            ("eta", &self.eta),
        ];
        if self.thin {
            params.push(("diff_trans", &self.diff_trans));
        } else {
            params.extend([
                ("metallic", &self.metallic),
                ("clearcoat", &self.clearcoat),
                ("clearcoat_gloss", &self.clearcoat_gloss),
            ]);
        }
        params
    }

    /// Light can come out on the side it did not arrive from.
    pub fn transmits(&self) -> bool {
        self.thin || !self.spec_trans.is_zero()
    }

    /// The textures it looks up (for the memory estimate).
    pub fn textures(&self) -> impl Iterator<Item = &TextureDesc> {
        self.params().into_iter().filter_map(|(_, p)| p.texture())
    }

    /// The same, to place them in the space of the object they are attached to.
    pub fn textures_mut(&mut self) -> impl Iterator<Item = &mut TextureDesc> {
        [
            &mut self.roughness,
            &mut self.anisotropic,
            &mut self.metallic,
            &mut self.spec_tint,
            &mut self.sheen,
            &mut self.sheen_tint,
            &mut self.clearcoat,
            &mut self.clearcoat_gloss,
            &mut self.spec_trans,
            &mut self.flatness,
            &mut self.diff_trans,
            &mut self.eta,
        ]
        .into_iter()
        .filter_map(|p| match p {
            ParamDesc::Constant(_) => None,
            ParamDesc::Texture(texture) => Some(texture),
        })
    }
}

/// `principled`'s η from its `eta` or `specular` (the default specular 0.5 if neither;
/// `None` if both are given), kept off 1 (specular off 0) where light is transmitted, as
/// Mitsuba does: a transmitting interface must bend.
pub fn solid_eta(eta: Option<f32>, specular: Option<f32>, transmits: bool) -> Option<f32> {
    match (eta, specular) {
        (Some(_), Some(_)) => None,
        (Some(eta), None) => Some(if transmits && eta == 1.0 { 1.001 } else { eta }),
        (None, specular) => {
            let specular = specular.unwrap_or(0.5);
            Some(eta_from_specular(if transmits && specular == 0.0 { 1e-3 } else { specular }))
        }
    }
}

/// Mitsuba's index for a `specular` reflectance s at normal incidence: s · 0.08 = R₀ =
/// ((η − 1)/(η + 1))², solved for η (in f32, as Mitsuba computes it).
pub fn eta_from_specular(specular: f32) -> f32 {
    2.0 / (1.0 - (0.08 * specular).sqrt()) - 1.0
}
