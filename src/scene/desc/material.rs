//! Materials: the Lambertian part, the specular lobe, the course's reflectance models.

use super::texture::{BumpMapDesc, TextureDesc};
use glam::Vec3;

/// How a surface reflects light. Every material has a Lambertian part (`albedo`, possibly
/// replaced by a `texture`) and optionally one specular part.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialDesc {
    pub name: String,
    /// Diffuse reflectance in [0, 1].
    pub albedo: Vec3,
    /// Emitted radiance, on the side the surface normal points to.
    pub emission: Vec3,
    /// Emits on both sides, not only where the normal points (`two_sided` lights).
    pub two_sided_emission: bool,
    /// A pattern of texture coordinates that `emission` is multiplied by, point by point
    /// (Mitsuba's area emitter with a textured radiance); uv-mapped patterns only.
    pub emission_texture: Option<TextureDesc>,
    pub specular: Specular,
    /// Roughness α of the specular part (0 = perfectly smooth); along ∂p/∂u where
    /// `roughness_v` is given.
    pub roughness: f32,
    /// Anisotropic roughness: α along the bitangent (Mitsuba's `alpha_v`, `roughness`
    /// being its `alpha_u`). `None`: isotropic.
    pub roughness_v: Option<f32>,
    /// α along ∂p/∂u and across it, looked up per hit (each texture's mean channel) in
    /// place of `roughness` and `roughness_v` (Mitsuba's textured `alpha`, `alpha_u`,
    /// `alpha_v`).
    pub roughness_textures: Option<Box<[TextureDesc; 2]>>,
    /// The microfacet distribution `roughness` is the α of.
    pub distribution: Distribution,
    /// How a rough mirror's or conductor's microfacets mask and shadow each other.
    pub shadowing: Shadowing,
    /// Fraction of the light that meets the surface at all (Mitsuba's `mask`); the rest
    /// passes through unchanged. A texture's mean channel where given.
    pub opacity: Option<Opacity>,
    /// Scatters only on the side its normal points to (Mitsuba's BSDFs without
    /// `twosided`); black from behind. Glass is two-sided whatever this says.
    pub one_sided: bool,
    /// A pattern that replaces (or blends into) `albedo`, per its `mode`.
    pub texture: Option<TextureDesc>,
    /// A pattern that replaces the specular reflectance of the course's shading terms
    /// (`phong.specular`; the course's `replace_ks`).
    pub specular_texture: Option<TextureDesc>,
    /// A tangent-space normal map (colour c in [0, 1]³ is the normal 2c − 1 in the frame of
    /// ∂p/∂u, ∂p/∂v and the shading normal; the course's `replace_normal`).
    pub normal_map: Option<TextureDesc>,
    /// A height field (the texture's mean channel, times `factor`) that displaces the
    /// shading normal (the course's `bump_normal`); uv-mapped patterns only.
    pub bump_map: Option<BumpMapDesc>,
    /// Shades a normal- or bump-mapped surface as Mitsuba does: the view is kept above the
    /// mapped normal (mirrored about the unmapped one), light must arrive on the same side
    /// of both, and Estevez et al.'s shadowing term darkens the bump terminator.
    pub bump_shadowing: bool,
    /// Terms only the course's Whitted shading model uses (ambient, Blinn-Phong highlight).
    pub phong: Option<PhongDesc>,
    /// Scatters as a mixture of two materials instead of its own lobes (Mitsuba's
    /// `blendbsdf`); its emission, opacity and mapped normals are still its own.
    pub blend: Option<Box<BlendDesc>>,
    /// Mitsuba's principled BSDF, whose base colour is `albedo` (or `texture`); `specular`
    /// is then `None`.
    pub principled: Option<Box<super::principled::PrincipledDesc>>,
}

/// `weight` of the second material's scattering and the rest of the first's.
#[derive(Clone, Debug, PartialEq)]
pub struct BlendDesc {
    /// In [0, 1]: a constant or a texture's mean channel (as a mask's opacity).
    pub weight: Opacity,
    pub materials: [MaterialDesc; 2],
}

impl MaterialDesc {
    /// The images its textures look up (for the memory estimate).
    pub fn images(&self) -> impl Iterator<Item = &std::sync::Arc<crate::texels::TextureImage>> {
        let opacity = self.opacity.as_ref().and_then(Opacity::texture);
        [&self.texture, &self.specular_texture, &self.normal_map, &self.emission_texture]
            .into_iter()
            .flatten()
            .chain(self.bump_map.as_ref().map(|b| &b.texture))
            .chain(opacity)
            .chain(self.roughness_textures.iter().flat_map(|t| t.iter()))
            .chain(self.principled.iter().flat_map(|p| p.textures()))
            .filter_map(TextureDesc::image)
            .chain(self.blend_images())
    }

    /// The mesh attributes its textures look up (`Pattern::MeshAttribute`), a blend's
    /// included.
    pub fn mesh_attributes(&self) -> Vec<&str> {
        let blend = self.blend.as_deref();
        let own = [&self.texture, &self.specular_texture, &self.normal_map]
            .into_iter()
            .flatten()
            .chain(self.bump_map.as_ref().map(|b| &b.texture))
            .chain(self.opacity.as_ref().and_then(Opacity::texture))
            .chain(self.roughness_textures.iter().flat_map(|t| t.iter()))
            .chain(blend.and_then(|b| b.weight.texture()));
        let mut names: Vec<&str> = own
            .filter_map(|t| match &t.pattern {
                super::Pattern::MeshAttribute { name, .. } => Some(name.as_str()),
                _ => None,
            })
            .collect();
        for part in blend.iter().flat_map(|b| b.materials.iter()) {
            names.extend(part.mesh_attributes());
        }
        names
    }

    /// The materials of its blend: itself, and each of the blend's parts as often as it is
    /// named (1 for a material that is not a blend). What `limits::MAX_BLEND_MATERIALS`
    /// bounds: a reader checks each blend as it builds it, so its parts are in bounds and
    /// this costs at most the limit.
    pub fn blend_materials(&self) -> usize {
        let parts = self.blend.iter().flat_map(|b| b.materials.iter());
        1 + parts.map(MaterialDesc::blend_materials).sum::<usize>()
    }

    /// What of this material the course's Whitted model would leave out without a word:
    /// it shades the Lambertian part, the course's terms and one specular part, so a
    /// principled BSDF or a blend would render as its base colour, and a partly transparent
    /// surface as an opaque one.
    pub fn unshaded_by_whitted(&self) -> Option<WhittedGap> {
        if self.principled.is_some() {
            Some(WhittedGap::Principled)
        } else if self.blend.is_some() {
            Some(WhittedGap::Blend)
        } else if self.opacity.as_ref().is_some_and(|o| *o != Opacity::Constant(1.0)) {
            Some(WhittedGap::Opacity)
        } else {
            None
        }
    }

    /// The images a blend's weight and materials look up.
    fn blend_images(
        &self,
    ) -> Box<dyn Iterator<Item = &std::sync::Arc<crate::texels::TextureImage>> + '_> {
        let Some(blend) = &self.blend else { return Box::new(std::iter::empty()) };
        let weight = blend.weight.texture().and_then(TextureDesc::image);
        Box::new(weight.into_iter().chain(blend.materials.iter().flat_map(|m| m.images())))
    }
}

impl Default for MaterialDesc {
    fn default() -> Self {
        MaterialDesc {
            name: String::new(),
            albedo: Vec3::splat(0.8),
            emission: Vec3::ZERO,
            two_sided_emission: false,
            emission_texture: None,
            specular: Specular::None,
            roughness: 0.0,
            roughness_v: None,
            roughness_textures: None,
            distribution: Distribution::Ggx,
            shadowing: Shadowing::HeightCorrelated,
            opacity: None,
            one_sided: false,
            texture: None,
            specular_texture: None,
            normal_map: None,
            bump_map: None,
            bump_shadowing: false,
            phong: None,
            blend: None,
            principled: None,
        }
    }
}

/// A part of a material the Whitted integrator cannot shade.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WhittedGap {
    Principled,
    Blend,
    Opacity,
}

impl WhittedGap {
    pub fn describe(self) -> &'static str {
        match self {
            WhittedGap::Principled => "a principled BSDF",
            WhittedGap::Blend => "a blend of two materials",
            WhittedGap::Opacity => "partial opacity",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Specular {
    None,
    /// Perfect (or, with roughness, glossy) reflection scaled by `reflectance`.
    Mirror {
        reflectance: Vec3,
    },
    /// Metal: Fresnel reflectance from the complex index `eta + i·k` (per channel), scaled
    /// by `reflectance`.
    Conductor {
        eta: Vec3,
        k: Vec3,
        reflectance: Vec3,
    },
    /// Glass: Fresnel reflection and refraction with index `ior`; light travelling inside is
    /// attenuated by exp(−absorption · distance) (Beer's law). `reflectance` and
    /// `transmittance` scale what is reflected and refracted (Mitsuba's
    /// `specular_reflectance` and `specular_transmittance`), not how often.
    Dielectric {
        ior: f32,
        absorption: Vec3,
        reflectance: Vec3,
        transmittance: Vec3,
    },
    /// A thin sheet of glass of index `ior` (Mitsuba's `thindielectric`): it reflects what
    /// its two faces and the reflections between them do, and lets the rest straight
    /// through; `reflectance` and `transmittance` scale the two.
    ThinDielectric {
        ior: f32,
        reflectance: Vec3,
        transmittance: Vec3,
    },
    /// A dielectric coating of index `ior` over the Lambertian part (Mitsuba's `plastic`,
    /// `roughplastic`): light the coating lets in is scattered by the base and internally
    /// reflected by the coating; `nonlinear` accounts for the colour shift of repeated
    /// internal bounces.
    Plastic {
        ior: f32,
        nonlinear: bool,
    },
}

impl Specular {
    /// Untinted glass of index `ior` and `absorption` inside.
    pub const fn dielectric(ior: f32, absorption: Vec3) -> Self {
        Specular::Dielectric { ior, absorption, reflectance: Vec3::ONE, transmittance: Vec3::ONE }
    }
}

/// A microfacet distribution of normals, by its roughness α.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Distribution {
    /// Trowbridge–Reitz: long tails.
    #[default]
    Ggx,
    /// Gaussian slopes: Mitsuba's default.
    Beckmann,
}

crate::choice::named_choices!(Distribution, "distribution", {
    Ggx => "ggx",
    Beckmann => "beckmann",
});

/// The masking-shadowing term G₂ of a rough mirror's or conductor's lobe: height-correlated,
/// 1 / (1 + Λ(ωo) + Λ(ωi)) (Heitz 2014; pbrt's), embray's own; or separable, G₁(ωo)·G₁(ωi),
/// which Mitsuba's `roughconductor` uses (darker at grazing angles: 4 % on a GGX sphere
/// of α 0.8 in a white furnace).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Shadowing {
    #[default]
    HeightCorrelated,
    Separable,
}

crate::choice::named_choices!(Shadowing, "shadowing", {
    HeightCorrelated => "height-correlated",
    Separable => "separable",
});

/// How much of a surface is there (Mitsuba's `mask` opacity), or any other number a
/// texture may give per hit (a blend's weight).
#[derive(Clone, Debug, PartialEq)]
pub enum Opacity {
    Constant(f32),
    /// The texture's mean channel.
    Texture(TextureDesc),
}

impl Opacity {
    pub fn texture(&self) -> Option<&TextureDesc> {
        match self {
            Opacity::Texture(t) => Some(t),
            Opacity::Constant(_) => None,
        }
    }
}

/// The course's shading terms (CENG795): ambient reflectance and a highlight, by default the
/// Blinn-Phong one of the earlier homeworks, or one of hw6's `<BRDFs>`.
#[derive(Clone, Debug, PartialEq)]
pub struct PhongDesc {
    pub ambient: Vec3,
    pub specular: Vec3,
    pub exponent: f32,
    pub brdf: CourseBrdf,
}

/// The course's reflectance models (hw6 `<BRDFs>`); `shading::course_brdf` defines each.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum CourseBrdf {
    /// The shading model of the earlier homeworks.
    #[default]
    OriginalBlinnPhong,
    OriginalPhong,
    ModifiedBlinnPhong {
        normalized: bool,
    },
    ModifiedPhong {
        normalized: bool,
    },
    /// A Blinn distribution, Fresnel from a conductor's complex index `eta + i·k` (the
    /// material's RefractionIndex and AbsorptionIndex) and the V-cavity shadowing term;
    /// `kd_fresnel` scales the diffuse term by `1 − F`.
    TorranceSparrow {
        kd_fresnel: bool,
        eta: Vec3,
        k: Vec3,
    },
}
