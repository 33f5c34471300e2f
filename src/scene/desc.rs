//! `SceneDesc`: a validated scene in world space with f64 transforms, independent of the file
//! format it came from.

use glam::{DAffine3, DVec2, DVec3, Vec2, Vec3};
use std::path::PathBuf;

#[derive(Clone, Debug, PartialEq)]
pub struct CameraDesc {
    pub lookfrom: DVec3,
    pub lookat: DVec3,
    pub up: DVec3,
    /// Vertical field of view in degrees.
    pub vfov_deg: f64,
    pub width: u32,
    pub height: u32,
    /// Lens diameter; 0 is a pinhole.
    pub aperture: f64,
    /// Distance to the plane in focus; `None` means the lookat distance.
    pub focus_distance: Option<f64>,
    pub lens_shape: LensShape,
    /// Lens shift: the image window's centre, at unit distance in front of the lens, along
    /// the camera's right and up axes (0 = centred; an off-axis projection otherwise, as the
    /// course's off-centre near planes need).
    pub shift: DVec2,
    /// A pixel's width over its height in the scene (1: square). The horizontal field of
    /// view is the vertical one's extent times width / height × this: the course stretches
    /// a near plane whose aspect differs from the resolution's over the image.
    pub pixel_aspect: f64,
}

impl CameraDesc {
    /// A pinhole camera at `lookfrom` looking at `lookat` (up +Y, no lens shift).
    pub fn pinhole(lookfrom: DVec3, lookat: DVec3, vfov_deg: f64, width: u32, height: u32) -> Self {
        CameraDesc {
            lookfrom,
            lookat,
            up: DVec3::Y,
            vfov_deg,
            width,
            height,
            aperture: 0.0,
            focus_distance: None,
            lens_shape: LensShape::Disk,
            shift: DVec2::ZERO,
            pixel_aspect: 1.0,
        }
    }
}

/// The shape of the lens aperture (`aperture` is its diameter, or its side for a square).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LensShape {
    #[default]
    Disk,
    /// The course's square lens.
    Square,
}

/// How a surface reflects light. Every material has a Lambertian part (`albedo`, possibly
/// replaced by a `texture`) and optionally one specular part.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialDesc {
    pub name: String,
    /// Diffuse reflectance in [0, 1].
    pub albedo: Vec3,
    /// Emitted radiance, on the side the surface normal points to.
    pub emission: Vec3,
    pub specular: Specular,
    /// GGX roughness α of the specular part (0 = perfectly smooth).
    pub roughness: f32,
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
    /// Terms only the course's Whitted shading model uses (ambient, Blinn-Phong highlight).
    pub phong: Option<PhongDesc>,
}

impl Default for MaterialDesc {
    fn default() -> Self {
        MaterialDesc {
            name: String::new(),
            albedo: Vec3::splat(0.8),
            emission: Vec3::ZERO,
            specular: Specular::None,
            roughness: 0.0,
            texture: None,
            specular_texture: None,
            normal_map: None,
            bump_map: None,
            phong: None,
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
    /// attenuated by exp(−absorption · distance) (Beer's law).
    Dielectric {
        ior: f32,
        absorption: Vec3,
    },
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
    #[default]
    Bilinear,
}

crate::choice::named_choices!(Interpolation, "interpolation", {
    Nearest => "nearest",
    Bilinear => "bilinear",
});

/// Decoded texels, row-major from the top-left, in the file's own units (0–255 for 8-bit
/// files, 0–65535 for 16-bit ones, linear values for float ones) unless the loader was
/// asked to decode sRGB into linear [0, 1]. `file` is kept for messages and for writing
/// the scene back out.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureImage {
    pub file: PathBuf,
    pub width: u32,
    pub height: u32,
    pub texels: Vec<Vec3>,
    /// True if the texels were decoded from sRGB to linear [0, 1].
    pub srgb_decoded: bool,
    /// True if the texels are an EXR file's linear values (high dynamic range).
    pub hdr: bool,
}

/// Mesh data in object space. Positions are f64 so that no precision is lost before the
/// object is placed in render space.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    pub positions: Vec<DVec3>,
    pub indices: Vec<[u32; 3]>,
    pub normals: Option<Vec<DVec3>>,
    pub uvs: Option<Vec<Vec2>>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ShapeDesc {
    /// Shared (`Arc`) so that every placement of one mesh uses the same data: objects whose
    /// meshes are the same `Arc` become instances of one prototype, O(1) memory each.
    Mesh(std::sync::Arc<MeshData>),
    Sphere {
        center: DVec3,
        radius: f64,
    },
}

#[derive(Clone, Debug, PartialEq)]
pub struct ObjectDesc {
    /// Human-readable name for messages ("objects[3] (bunny.obj: Bunny)").
    pub name: String,
    pub shape: ShapeDesc,
    /// Index into `SceneDesc::materials`.
    pub material: u32,
    /// Placement at shutter open (t = 0).
    pub world_from_object: DAffine3,
    /// Placement at shutter close (t = 1) for a moving object; interpolated as translation,
    /// rotation (slerp) and scale in between. `None` for a static object.
    pub world_from_object_end: Option<DAffine3>,
}

impl ObjectDesc {
    pub fn is_moving(&self) -> bool {
        self.world_from_object_end.is_some_and(|end| end != self.world_from_object)
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum LightDesc {
    /// Isotropic point light; `intensity` is radiant intensity (W/sr per channel).
    Point { position: DVec3, intensity: Vec3 },
    /// A point light that sends its light into a cone around `direction` (unit, from the
    /// light into the scene): the course's SpotLight. Full `intensity` within half the
    /// `falloff_degrees` of the axis, none beyond half the `coverage_degrees`, and in
    /// between `intensity` times ((cos α − cos(coverage/2)) / (cos(falloff/2) −
    /// cos(coverage/2)))⁴. (hw5.tex prints cos(falloff/2) as the first term, which makes
    /// the light drop to 0 just outside the falloff cone and jump back to full at the
    /// coverage edge, against its own description: "diminish non-linearly" from the first to
    /// the second. The pack has no SpotLight reference to settle it.)
    Spot {
        position: DVec3,
        direction: DVec3,
        intensity: Vec3,
        coverage_degrees: f64,
        falloff_degrees: f64,
    },
    /// Light from infinitely far away arriving along `direction` (pointing from the light
    /// into the scene); `irradiance` on a surface facing it.
    Directional { direction: DVec3, irradiance: Vec3 },
    /// Constant light added to every surface's ambient reflectance (the course's
    /// AmbientLight; only the Whitted integrator uses it).
    Ambient { radiance: Vec3 },
    /// The course's AreaLight: a square of side `size` centred at `center`, facing `normal`
    /// (unit length), emitting `radiance` (two-sided). It lights the scene (sampled by area)
    /// but has no geometry: rays never hit it, so the camera does not see it.
    Area { center: DVec3, normal: DVec3, size: f64, radiance: Vec3 },
    /// Radiance from every direction far away: a latitude-longitude map (the course's
    /// SphericalDirectionalLight; see `shading::light::EnvironmentLight` for the mapping)
    /// times `scale`. Rays that leave the scene see it in place of the background.
    Environment { map: EnvironmentMap, scale: Vec3, mapping: EnvironmentMapping },
}

/// How an environment image covers the sphere of directions (see
/// `shading::light::env_mapping`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EnvironmentMapping {
    /// Latitude-longitude (equirectangular), hw5.tex's mapping.
    #[default]
    LatLong,
    /// Debevec's light probe (angular map).
    Probe,
}

crate::choice::named_choices!(EnvironmentMapping, "environment mapping", {
    LatLong => "latlong",
    Probe => "probe",
});

/// What an environment light's radiance comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum EnvironmentMap {
    /// The same radiance from every direction.
    Constant(Vec3),
    /// A latitude-longitude image of linear radiances.
    Image(std::sync::Arc<TextureImage>),
}

/// Which light-transport algorithm renders the scene.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum IntegratorKind {
    /// Path tracing with next-event estimation and MIS.
    #[default]
    Path,
    /// The CENG795 course model: ambient + Blinn-Phong direct light with shadow rays,
    /// recursive mirror/conductor/dielectric, values in 0–255 units clamped.
    Whitted,
}

crate::choice::named_choices!(IntegratorKind, "integrator", {
    Path => "path",
    Whitted => "whitted",
});

impl IntegratorKind {
    /// The curve a scene gets unless one is asked for: the course's clamp for Whitted
    /// (CENG795) scenes, ACES otherwise.
    pub fn default_tone_map(self) -> crate::output::ToneMap {
        match self {
            IntegratorKind::Whitted => crate::output::ToneMap::Clamp255,
            IntegratorKind::Path => crate::output::ToneMap::Aces,
        }
    }
}

/// Defaults for the renderer that a scene may carry; command-line options override them.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    pub spp: u32,
    pub max_depth: u32,
    pub background: Vec3,
    /// Shadow rays towards area lights per shading point.
    pub light_samples: u32,
    pub integrator: IntegratorKind,
    /// The photographic tone mapping the scene asks for its PNG (a CENG795 camera's
    /// `<Tonemap>`); `None`: the integrator's default curve.
    pub tonemap: Option<crate::output::Photographic>,
    /// A picture behind the scene (the course's replace_background): camera rays that leave
    /// the scene see it stretched over the image (u across, v down from the top), in place
    /// of the background colour or the environment. Other rays that leave see those.
    pub background_texture: Option<TextureDesc>,
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            spp: 16,
            max_depth: 5,
            background: Vec3::ZERO,
            light_samples: 1,
            integrator: IntegratorKind::Path,
            tonemap: None,
            background_texture: None,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct SceneDesc {
    /// The file it was loaded from, for messages.
    pub source: PathBuf,
    pub camera: CameraDesc,
    pub settings: RenderSettings,
    pub materials: Vec<MaterialDesc>,
    pub objects: Vec<ObjectDesc>,
    pub lights: Vec<LightDesc>,
}

impl SceneDesc {
    /// Moves the whole scene, camera included, by `offset` (exactly, in f64). Used to
    /// reproduce the far-from-origin precision problem with any scene.
    pub fn translate(&mut self, offset: DVec3) {
        let shift = DAffine3::from_translation(offset);
        self.camera.lookfrom += offset;
        self.camera.lookat += offset;
        for object in &mut self.objects {
            object.world_from_object = shift * object.world_from_object;
            if let Some(end) = &mut object.world_from_object_end {
                *end = shift * *end;
            }
        }
        for light in &mut self.lights {
            match light {
                LightDesc::Point { position, .. } | LightDesc::Spot { position, .. } => {
                    *position += offset
                }
                LightDesc::Area { center, .. } => *center += offset,
                _ => {}
            }
        }
    }
}
