//! Surface materials as the integrator sees them (f32, textures ready to evaluate).

use crate::scene::{MaterialDesc, PatternDesc, PhongDesc, SpecularDesc};
use glam::{Affine3A, Vec2, Vec3};

/// Below this GGX α a lobe is treated as perfectly smooth (a delta distribution).
pub const SMOOTH_ROUGHNESS: f32 = 1e-3;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Specular {
    None,
    Mirror { reflectance: Vec3 },
    Conductor { eta: Vec3, k: Vec3, reflectance: Vec3 },
    Dielectric { ior: f32, absorption: Vec3 },
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pattern {
    Checker2d { scale: f32, even: Vec3, odd: Vec3 },
    Checker3d { scale: f32, even: Vec3, odd: Vec3 },
}

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
    /// GGX α of the specular lobe.
    pub roughness: f32,
    pub texture: Option<Texture>,
    pub phong: Option<PhongDesc>,
}

impl Default for Material {
    fn default() -> Self {
        Material {
            albedo: Vec3::splat(0.8),
            emission: Vec3::ZERO,
            specular: Specular::None,
            roughness: 0.0,
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
        let specular = match desc.specular {
            SpecularDesc::None => Specular::None,
            SpecularDesc::Mirror { reflectance } => Specular::Mirror { reflectance },
            SpecularDesc::Conductor { eta, k, reflectance } => {
                Specular::Conductor { eta, k, reflectance }
            }
            SpecularDesc::Dielectric { ior, absorption } => {
                Specular::Dielectric { ior, absorption }
            }
        };
        let texture = desc.texture.as_ref().map(|t| Texture {
            pattern: match t.pattern {
                PatternDesc::Checker2d { scale, even, odd } => {
                    Pattern::Checker2d { scale: scale as f32, even, odd }
                }
                PatternDesc::Checker3d { scale, even, odd } => {
                    Pattern::Checker3d { scale: scale as f32, even, odd }
                }
            },
            texture_from_object: Affine3A::from_mat4(
                glam::DMat4::from(t.texture_from_object).as_mat4(),
            ),
        });
        Material {
            albedo: desc.albedo,
            emission: desc.emission,
            specular,
            roughness: desc.roughness,
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
            _ => self.roughness < SMOOTH_ROUGHNESS,
        }
    }
}
