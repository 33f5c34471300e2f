//! Textures: patterns, images, how they combine with a material, bump maps.

use super::shape::TextureImage;
use glam::{DAffine3, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub struct TextureDesc {
    pub pattern: Pattern,
    /// What the pattern's colour does to the surface (only `Replace` for a specular texture).
    pub mode: TextureMode,
    /// Maps the space of the object the material is attached to (the mesh's own vertex
    /// space, or for a material given at the instance level the instance's space) to the
    /// pattern's space. Set by the loader; identity for object-level materials.
    pub texture_from_object: DAffine3,
}

#[derive(Clone, Debug, PartialEq)]
pub struct BumpMapDesc {
    pub texture: TextureDesc,
    /// Height per unit of the texture's value.
    pub factor: f32,
    pub scale: BumpScale,
}

/// What a bump map's heights and slopes are measured in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BumpScale {
    /// Heights in scene units (texture value × factor), slopes per unit of texture
    /// coordinate, the surface displaced in render space: the bumps keep their size in the
    /// scene whatever the texture's resolution.
    #[default]
    Scene,
    /// The CENG795 course's `bump_normal`: heights in the image's own 0–255 units (× the
    /// `BumpFactor`), differenced between neighbouring texels (not divided by the texel's
    /// size), displacing the object in its own space before its transformation.
    CourseTexels,
}

/// How a colour texture combines with the material (the course's decal modes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TextureMode {
    /// The texture is the diffuse reflectance (`replace_kd`).
    #[default]
    Replace,
    /// The mean of the material's diffuse reflectance and the texture (`blend_kd`).
    Blend,
    /// The texture is the surface's colour, unshaded (`replace_all`): the Whitted
    /// integrator shows it as is; the path tracer treats it as `Replace`.
    ReplaceAll,
}

crate::choice::named_choices!(TextureMode, "texture mode", {
    Replace => "replace",
    Blend => "blend",
    ReplaceAll => "replace_all",
});

#[derive(Clone, Debug, PartialEq)]
pub enum Pattern {
    /// Checkerboard in texture coordinates: `scale` checks per unit of u and v.
    Checker2d { scale: f32, even: Vec3, odd: Vec3 },
    /// Solid checkerboard in the object's space: cubes of side 1/`scale`.
    Checker3d { scale: f32, even: Vec3, odd: Vec3 },
    /// The course's solid checkerboard: cells of side 1/`scale` shifted by `offset`, cell
    /// indices truncated towards zero (so the cells that touch an axis plane are twice as
    /// wide as the others, as in the course's definition).
    CourseChecker { scale: f32, offset: f32, black: Vec3, white: Vec3 },
    /// Perlin's improved gradient noise of the object-space point times `scale`, grey.
    Perlin { scale: f32, conversion: NoiseConversion },
    /// An image looked up at the texture coordinates (repeating outside [0, 1]; v = 0 is
    /// the image's top row), divided by `normalizer`.
    Image { image: std::sync::Arc<TextureImage>, interpolation: Interpolation, normalizer: f32 },
    /// One value everywhere, unclamped (Mitsuba's `rawconstant`).
    Constant(Vec3),
    /// The hit mesh's attribute `name` (`MeshAttribute`: per triangle, or per vertex
    /// interpolated) times `scale` (Mitsuba's `mesh_attribute`).
    MeshAttribute { name: String, scale: f32 },
    /// A texture-coordinate pattern looked up at mapped coordinates (Mitsuba's `to_uv` and
    /// `wrap_mode`).
    UvMapped(Box<UvMapped>),
}

/// `inner` looked up at `uv_from_surface` of the surface's texture coordinates, wrapped.
#[derive(Clone, Debug, PartialEq)]
pub struct UvMapped {
    pub uv_from_surface: glam::Affine2,
    pub wrap: Wrap,
    /// An image or a 2-D checkerboard.
    pub inner: Pattern,
}

/// What an image shows outside [0, 1]².
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Wrap {
    /// The image again.
    #[default]
    Repeat,
    /// The image mirrored at each edge.
    Mirror,
    /// The edge texels.
    Clamp,
}

impl TextureDesc {
    /// The image it looks up, if it is an image texture.
    pub fn image(&self) -> Option<&std::sync::Arc<TextureImage>> {
        match &self.pattern {
            Pattern::Image { image, .. } => Some(image),
            Pattern::UvMapped(mapped) => match &mapped.inner {
                Pattern::Image { image, .. } => Some(image),
                _ => None,
            },
            _ => None,
        }
    }
}

/// How Perlin noise in [-1, 1] becomes a grey level in [0, 1].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum NoiseConversion {
    /// |noise|: vein-like patterns.
    #[default]
    Absolute,
    /// (noise + 1) / 2: soft patches.
    Linear,
}

crate::choice::named_choices!(NoiseConversion, "noise conversion", {
    Absolute => "absval",
    Linear => "linear",
});

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Interpolation {
    Nearest,
    /// The course's: texel i spans [i, i + 1), blended with the next by the fraction.
    #[default]
    Bilinear,
    /// Between texel centres (texel i at i + ½), repeating across the edges: Mitsuba's
    /// bitmap lookup (and OpenGL's).
    BilinearCentered,
}

crate::choice::named_choices!(Interpolation, "interpolation", {
    Nearest => "nearest",
    Bilinear => "bilinear",
    BilinearCentered => "bilinear_centered",
});
