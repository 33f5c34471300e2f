//! Surface materials as the integrators see them. `Material` is the scene's `MaterialDesc`
//! prepared for shading: textures mapped by an f32 transform, the one roughness split into
//! its two meanings (GGX α, Whitted perturbation), no name. The specular lobe and the
//! pattern are the scene's own types.

pub use super::texture::Texture;
use crate::scene::{Distribution, MaterialDesc, Opacity, PhongDesc, Shadowing, Specular};
use crate::shading::coating::{Coating, CoatingTables};
use crate::shading::course_lobe::LobeAlbedo;
use crate::shading::microfacet::Microfacet;
use crate::shading::principled::PrincipledMaterial;
use crate::shading::tex_coords::TexCoords;
use glam::Vec3;

/// Below this GGX α a lobe is treated as perfectly smooth (a delta distribution).
pub const SMOOTH_ROUGHNESS: f32 = 1e-3;

#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Lambertian reflectance (replaced by `texture` where there is one).
    pub albedo: Vec3,
    /// Emitted radiance, on the side the surface normal points to (a quad's u × v, a
    /// mesh's counter-clockwise winding, a sphere's outside).
    pub emission: Vec3,
    /// Emits on both sides (`MaterialDesc::two_sided_emission`).
    pub two_sided_emission: bool,
    /// What `emission` is multiplied by at each point (`MaterialDesc::emission_texture`).
    pub emission_texture: Option<std::sync::Arc<Texture>>,
    pub specular: Specular,
    /// Microfacet α of the specular lobe (the path tracer), along the shading frame's
    /// tangent where `ggx_alpha_v` differs.
    pub ggx_alpha: f32,
    /// α along the bitangent (the tangent is ∂p/∂u's direction): `ggx_alpha` unless the
    /// roughness is anisotropic.
    pub ggx_alpha_v: f32,
    /// α along the tangent and the bitangent looked up per hit (each texture's mean
    /// channel), in place of `ggx_alpha` and `ggx_alpha_v`.
    pub roughness_textures: Option<Box<[Texture; 2]>>,
    /// The distribution `ggx_alpha` is the α of.
    pub distribution: Distribution,
    /// The rough mirror's or conductor's masking-shadowing term.
    pub shadowing: Shadowing,
    /// What a plastic's coating lets through (set by `from_desc` for plastics).
    pub coating: Option<Box<Coating>>,
    /// Fraction of the light that meets the surface; the rest passes through.
    pub opacity: Option<MaskOpacity>,
    /// Black from behind (glass excepted).
    pub one_sided: bool,
    /// Side of the square on the tangent plane within which the course's Whitted model
    /// perturbs reflected rays (its glossy reflection).
    pub perturbation: f32,
    pub texture: Option<Texture>,
    /// Replaces `phong.specular` (the course's `replace_ks`).
    pub specular_texture: Option<Texture>,
    /// A tangent-space normal map (`shading::normal_map`).
    pub normal_map: Option<Texture>,
    /// A height field, its factor and what its heights are measured in
    /// (`shading::normal_map`).
    pub bump_map: Option<(Texture, f32, crate::scene::BumpScale)>,
    /// Mitsuba's shading of mapped normals (`MaterialDesc::bump_shadowing`).
    pub bump_shadowing: bool,
    pub phong: Option<PhongDesc>,
    /// The directional albedo of `phong`'s lobe (set with it by `from_desc` and
    /// `with_phong`), by which the path tracer keeps the material from reflecting more
    /// than it receives.
    pub course_lobe_albedo: Option<LobeAlbedo>,
    /// Scatters as a mixture of two materials (`MaterialDesc::blend`).
    pub blend: Option<Box<Blend>>,
    /// Mitsuba's principled BSDF, its base colour `albedo` (or `texture`).
    pub principled: Option<Box<PrincipledMaterial>>,
}

/// `weight` of the second material's scattering and the rest of the first's.
#[derive(Clone, Debug, PartialEq)]
pub struct Blend {
    pub weight: MaskOpacity,
    pub materials: [Material; 2],
}

impl Default for Material {
    fn default() -> Self {
        Material {
            albedo: Vec3::splat(0.8),
            emission: Vec3::ZERO,
            two_sided_emission: false,
            emission_texture: None,
            specular: Specular::None,
            ggx_alpha: 0.0,
            ggx_alpha_v: 0.0,
            roughness_textures: None,
            distribution: Distribution::Ggx,
            shadowing: Shadowing::HeightCorrelated,
            coating: None,
            opacity: None,
            one_sided: false,
            perturbation: 0.0,
            texture: None,
            specular_texture: None,
            normal_map: None,
            bump_map: None,
            bump_shadowing: false,
            phong: None,
            course_lobe_albedo: None,
            blend: None,
            principled: None,
        }
    }
}

/// A mask's opacity as the integrator looks it up.
#[derive(Clone, Debug, PartialEq)]
pub enum MaskOpacity {
    Constant(f32),
    /// The texture's mean channel.
    Texture(Texture),
}

fn mask_opacity(opacity: &Opacity) -> MaskOpacity {
    match opacity {
        Opacity::Constant(c) => MaskOpacity::Constant(*c),
        Opacity::Texture(t) => MaskOpacity::Texture(Texture::from_desc(t)),
    }
}

/// The coating table of a plastic (integrated once per scene and roughness, not per hit).
fn coating(material: &Material, tables: &mut CoatingTables) -> Option<Box<Coating>> {
    let Specular::Plastic { ior, .. } = material.specular else { return None };
    let microfacet = material.is_rough().then(|| material.microfacet());
    Some(Box::new(tables.get(ior, microfacet)))
}

impl Material {
    /// A Lambertian material (tests and tools).
    pub fn diffuse(albedo: Vec3) -> Self {
        Material { albedo, ..Material::default() }
    }

    pub fn from_desc(desc: &MaterialDesc) -> Self {
        Self::from_desc_sharing(desc, &mut CoatingTables::default())
    }

    /// `from_desc`, its coating table taken from `tables` (made there if new).
    pub fn from_desc_sharing(desc: &MaterialDesc, tables: &mut CoatingTables) -> Self {
        let material = Self::from_desc_without_coating(desc, tables);
        Material { coating: coating(&material, tables), ..material }
    }

    fn from_desc_without_coating(desc: &MaterialDesc, tables: &mut CoatingTables) -> Self {
        Material {
            albedo: desc.albedo,
            emission: desc.emission,
            two_sided_emission: desc.two_sided_emission,
            emission_texture: desc
                .emission_texture
                .as_ref()
                .map(|t| std::sync::Arc::new(Texture::from_desc(t))),
            specular: desc.specular,
            // The scene's one roughness means a GGX α to the path tracer and the side of the
            // perturbation square to the course's Whitted model.
            ggx_alpha: desc.roughness,
            ggx_alpha_v: desc.roughness_v.unwrap_or(desc.roughness),
            roughness_textures: desc
                .roughness_textures
                .as_deref()
                .map(|[u, v]| Box::new([Texture::from_desc(u), Texture::from_desc(v)])),
            distribution: desc.distribution,
            shadowing: desc.shadowing,
            coating: None,
            opacity: desc.opacity.as_ref().map(mask_opacity),
            one_sided: desc.one_sided,
            perturbation: desc.roughness,
            texture: desc.texture.as_ref().map(Texture::from_desc),
            specular_texture: desc.specular_texture.as_ref().map(Texture::from_desc),
            normal_map: desc.normal_map.as_ref().map(Texture::from_desc),
            bump_map: desc
                .bump_map
                .as_ref()
                .map(|b| (Texture::from_desc(&b.texture), b.factor, b.scale)),
            bump_shadowing: desc.bump_shadowing,
            phong: None,
            course_lobe_albedo: None,
            blend: desc.blend.as_deref().map(|b| {
                Box::new(Blend {
                    weight: mask_opacity(&b.weight),
                    materials: [
                        Material::from_desc_sharing(&b.materials[0], tables),
                        Material::from_desc_sharing(&b.materials[1], tables),
                    ],
                })
            }),
            principled: desc
                .principled
                .as_deref()
                .map(|p| Box::new(PrincipledMaterial::from_desc(p))),
        }
        .with_phong(desc.phong.clone())
    }

    /// This material with the course's reflectance model `phong` (set `specular_texture`
    /// first). The lobe's albedo table is made only where the path tracer can see a lobe:
    /// a specular reflectance above 0, or a texture that gives one per hit.
    pub fn with_phong(self, phong: Option<PhongDesc>) -> Self {
        let course_lobe_albedo = phong
            .as_ref()
            .filter(|p| p.specular.max_element() > 0.0 || self.specular_texture.is_some())
            .map(|p| LobeAlbedo::new(&p.brdf, p.exponent));
        Material { phong, course_lobe_albedo, ..self }
    }

    /// The specular lobe's microfacet distribution (α at least 10⁻⁴).
    pub fn microfacet(&self) -> Microfacet {
        self.microfacet_at((self.ggx_alpha, self.ggx_alpha_v))
    }

    /// Its distribution with the α (along the tangent, the bitangent) of one hit, where
    /// `roughness_textures` gave them.
    pub fn microfacet_at(&self, (alpha_u, alpha_v): (f32, f32)) -> Microfacet {
        Microfacet {
            distribution: self.distribution,
            alpha_x: alpha_u.max(1e-4),
            alpha_y: alpha_v.max(1e-4),
        }
    }

    /// Whether the specular lobe is rough (not a delta), along either axis.
    pub fn is_rough(&self) -> bool {
        self.ggx_alpha.max(self.ggx_alpha_v) >= SMOOTH_ROUGHNESS
    }

    /// Whether the roughness differs along the tangent and the bitangent (the shading
    /// frame must then follow ∂p/∂u).
    pub fn is_anisotropic(&self) -> bool {
        self.ggx_alpha != self.ggx_alpha_v
            || self.roughness_textures.is_some()
            || self.principled.as_ref().is_some_and(|p| p.is_anisotropic())
    }

    /// Whether its BSDF is a Lambertian lobe alone, in the shading normal's frame, wherever
    /// it is seen from its front (no other lobe, no mask, no blend).
    pub fn is_plain_lambertian(&self) -> bool {
        self.specular == Specular::None
            && self.phong.is_none()
            && self.principled.is_none()
            && self.blend.is_none()
            && self.opacity.is_none()
            && !self.is_anisotropic()
    }

    pub fn is_emissive(&self) -> bool {
        self.emission.max_element() > 0.0
    }

    /// What it emits at texture coordinates `uv`, on the side it emits to.
    #[inline]
    pub fn emission_at(&self, uv: TexCoords) -> Vec3 {
        match &self.emission_texture {
            None => self.emission,
            Some(texture) => self.emission * texture.eval(Vec3::ZERO, uv.get()),
        }
    }

    /// What it emits at `uv` towards a ray that met it on its front (`front_face`) or back.
    pub fn emission_seen(&self, front_face: bool, uv: TexCoords) -> Vec3 {
        if front_face || self.two_sided_emission { self.emission_at(uv) } else { Vec3::ZERO }
    }

    pub fn is_dielectric(&self) -> bool {
        matches!(self.specular, Specular::Dielectric { .. })
    }

    /// True if the specular lobe is a delta distribution (perfect mirror, smooth glass,
    /// a smooth plastic's coating).
    pub fn specular_is_delta(&self) -> bool {
        match self.specular {
            Specular::None => false,
            _ => !self.is_rough(),
        }
    }
}
