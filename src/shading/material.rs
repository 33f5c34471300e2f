//! Surface materials as the integrators see them. `Material` is the scene's `MaterialDesc`
//! prepared for shading: textures mapped by an f32 transform, the one roughness split into
//! its two meanings (GGX α, Whitted perturbation), no name. The specular lobe and the
//! pattern are the scene's own types.

use crate::scene::{MaterialDesc, Pattern, PhongDesc, Specular};
use glam::{Affine3A, Vec2, Vec3};

/// Below this GGX α a lobe is treated as perfectly smooth (a delta distribution).
pub const SMOOTH_ROUGHNESS: f32 = 1e-3;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Texture {
    pub pattern: Pattern,
    /// From the attached object's space to the pattern's space.
    pub texture_from_object: Affine3A,
}

impl Texture {
    /// The colour at object-space point `p_object` with texture coordinates `uv`.
    pub fn eval(&self, p_object: Vec3, uv: Vec2) -> Vec3 {
        let parity = |cells: &[f32]| cells.iter().map(|c| c.floor() as i64).sum::<i64>() & 1;
        match self.pattern {
            Pattern::Checker2d { scale, even, odd } => {
                if parity(&[uv.x * scale, uv.y * scale]) == 0 { even } else { odd }
            }
            Pattern::Checker3d { scale, even, odd } => {
                let p = self.texture_from_object.transform_point3(p_object) * scale;
                if parity(&[p.x, p.y, p.z]) == 0 { even } else { odd }
            }
        }
    }

    pub fn needs_object_point(&self) -> bool {
        matches!(self.pattern, Pattern::Checker3d { .. })
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Lambertian reflectance (replaced by `texture` where there is one).
    pub albedo: Vec3,
    /// Emitted radiance, on the side the surface normal points to (a quad's u × v, a
    /// mesh's counter-clockwise winding, a sphere's outside).
    pub emission: Vec3,
    pub specular: Specular,
    /// GGX α of the specular lobe (the path tracer).
    pub ggx_alpha: f32,
    /// Side of the square on the tangent plane within which the course's Whitted model
    /// perturbs reflected rays (its glossy reflection).
    pub perturbation: f32,
    pub texture: Option<Texture>,
    pub phong: Option<PhongDesc>,
}

impl Default for Material {
    fn default() -> Self {
        Material {
            albedo: Vec3::splat(0.8),
            emission: Vec3::ZERO,
            specular: Specular::None,
            ggx_alpha: 0.0,
            perturbation: 0.0,
            texture: None,
            phong: None,
        }
    }
}

impl Material {
    /// A Lambertian material (tests and tools).
    pub fn diffuse(albedo: Vec3) -> Self {
        Material { albedo, ..Material::default() }
    }

    pub fn from_desc(desc: &MaterialDesc) -> Self {
        let texture = desc.texture.as_ref().map(|t| Texture {
            pattern: t.pattern,
            texture_from_object: Affine3A::from_mat4(
                glam::DMat4::from(t.texture_from_object).as_mat4(),
            ),
        });
        Material {
            albedo: desc.albedo,
            emission: desc.emission,
            specular: desc.specular,
            // The scene's one roughness means a GGX α to the path tracer and the side of the
            // perturbation square to the course's Whitted model.
            ggx_alpha: desc.roughness,
            perturbation: desc.roughness,
            texture,
            phong: desc.phong.clone(),
        }
    }

    pub fn is_emissive(&self) -> bool {
        self.emission.max_element() > 0.0
    }

    pub fn is_dielectric(&self) -> bool {
        matches!(self.specular, Specular::Dielectric { .. })
    }

    /// True if the specular lobe is a delta distribution (perfect mirror or smooth glass).
    pub fn specular_is_delta(&self) -> bool {
        match self.specular {
            Specular::None => false,
            // The path tracer treats glass as smooth whatever its roughness.
            Specular::Dielectric { .. } => true,
            _ => self.ggx_alpha < SMOOTH_ROUGHNESS,
        }
    }
}
