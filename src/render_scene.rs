//! The scene as the backends and the integrator see it: f32 geometry in render space.
//! Built once from a `SceneDesc` by `render_space::to_render_scene`.
//!
//! Geometry lives in *prototypes*; the scene is a list of *instances* placing them. Most
//! objects are `Placement::Baked`: their prototype's vertices were transformed into render
//! space in f64 and then rounded (the most precise and fastest form). Meshes placed more than
//! once, moving objects and ellipsoids keep object-space prototypes and a transform.

use crate::camera::Camera;
use crate::compile::effects::Effects;
use crate::float_error::TrianglePlane;
use crate::light::LightSet;
use crate::shading::material::Material;
use crate::shading::texture::Texture;
use glam::{Affine3A, Mat3, Quat, Vec2, Vec3};

/// A triangle mesh (in render space when baked, else in object space). Build it with
/// [`TriangleMesh::new`] and leave its positions and indices as they are: the kept triangle
/// planes are derived from them once (a mesh built field by field keeps none and computes
/// each plane per hit, which is always right).
#[derive(Clone, Debug, Default)]
pub struct TriangleMesh {
    pub positions: Vec<Vec3>,
    pub indices: Vec<[u32; 3]>,
    /// Per-vertex shading normals (unit length, or zero where undefined), if any.
    pub normals: Option<Vec<Vec3>>,
    /// Per-vertex texture coordinates, if the mesh has them.
    pub uvs: Option<Vec<Vec2>>,
    /// Named per-vertex or per-triangle values (`mesh_attribute` textures look them up).
    pub attributes: Vec<crate::scene::MeshAttribute>,
    /// Each triangle's plane, kept for small meshes (see `CACHED_PLANES`); empty otherwise.
    planes: Vec<TrianglePlane>,
}

/// Meshes up to this many triangles keep their planes: every hit on them then skips three
/// square roots and two divisions. 44 bytes a triangle, so at most 1.4 MB a mesh, which
/// stays in cache; a larger mesh's planes would cost a cache miss per hit, more than
/// recomputing them.
const CACHED_PLANES: usize = 1 << 15;

impl TriangleMesh {
    pub fn new(
        positions: Vec<Vec3>,
        indices: Vec<[u32; 3]>,
        normals: Option<Vec<Vec3>>,
        uvs: Option<Vec<Vec2>>,
    ) -> Self {
        // Normals that only repeat each face's own add nothing but work to every hit, and
        // keep the mesh off the integrator's short way for flat surfaces (`plain_hit`).
        // Tools write them (Blender's OBJ export, Mitsuba's loaders computing a planar
        // wall's vertex normals), so such a mesh is shaded flat, as it would be.
        let normals = normals.filter(|normals| !normals_are_flat(&positions, &indices, normals));
        let mut mesh = TriangleMesh {
            positions,
            indices,
            normals,
            uvs,
            attributes: Vec::new(),
            planes: Vec::new(),
        };
        // A bad index keeps no planes: the backends report it when they build.
        let vertex = |i: u32| mesh.positions.get(i as usize).copied();
        if mesh.indices.len() <= CACHED_PLANES {
            mesh.planes = mesh
                .indices
                .iter()
                .map(|&[a, b, c]| Some(TrianglePlane::new(&[vertex(a)?, vertex(b)?, vertex(c)?])))
                .collect::<Option<_>>()
                .unwrap_or_default();
        }
        mesh
    }

    /// This mesh with its named attributes.
    pub fn with_attributes(self, attributes: Vec<crate::scene::MeshAttribute>) -> Self {
        TriangleMesh { attributes, ..self }
    }

    /// The value of the attribute `name` at barycentric coordinates `barycentric` of
    /// triangle `prim` (a per-vertex one interpolated), or `None` if the mesh has none.
    pub fn attribute(&self, name: &str, prim: u32, barycentric: Vec2) -> Option<Vec3> {
        let attribute = self.attributes.iter().find(|a| a.name == name)?;
        if attribute.per_face() {
            return Some(attribute.value(prim as usize));
        }
        let [a, b, c] = self.indices[prim as usize].map(|i| attribute.value(i as usize));
        Some(a * (1.0 - barycentric.x - barycentric.y) + b * barycentric.x + c * barycentric.y)
    }

    pub fn triangle(&self, prim: u32) -> [Vec3; 3] {
        let [a, b, c] = self.indices[prim as usize];
        [self.positions[a as usize], self.positions[b as usize], self.positions[c as usize]]
    }

    /// The plane of triangle `prim`, as `TrianglePlane::new` of its vertices.
    pub fn plane(&self, prim: u32, triangle: &[Vec3; 3]) -> TrianglePlane {
        match self.planes.get(prim as usize) {
            Some(plane) => *plane,
            None => TrianglePlane::new(triangle),
        }
    }
}

/// How far (the sine of the angle) a vertex normal may lean from its face's normal and
/// still be that normal: 1e-4 rad, a few times the rounding of a normal computed in f64 and
/// stored in f32, or of a face normal from f32 vertices, and a ten-thousandth of a shading
/// cosine at most.
const FLAT_NORMAL_SINE: f32 = 1e-4;

/// Whether every triangle's vertex normals are its face normal, all three on the same side
/// of it (then the interpolated normal is the face normal up to rounding, and the shading
/// normal, turned to the geometric side, is the geometric normal). A degenerate triangle, a
/// zero normal or an index out of range keeps the normals.
fn normals_are_flat(positions: &[Vec3], indices: &[[u32; 3]], normals: &[Vec3]) -> bool {
    indices.iter().all(|&[a, b, c]| {
        let corners = [a, b, c].map(|i| positions.get(i as usize).zip(normals.get(i as usize)));
        let [Some((&p0, &n0)), Some((&p1, &n1)), Some((&p2, &n2))] = corners else {
            return false;
        };
        let face = TrianglePlane::new(&[p0, p1, p2]).normal;
        let along = |n: Vec3| {
            let n = n.normalize_or_zero();
            let parallel = n != Vec3::ZERO && n.cross(face).length() <= FLAT_NORMAL_SINE;
            parallel.then(|| n.dot(face) > 0.0)
        };
        let sides = [n0, n1, n2].map(along);
        face != Vec3::ZERO && sides[0].is_some() && sides.iter().all(|side| *side == sides[0])
    })
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    pub center: Vec3,
    pub radius: f32,
}

#[derive(Clone, Debug)]
pub enum Geometry {
    Triangles(TriangleMesh),
    Sphere(Sphere),
    /// A signed distance grid in grid units (always placed by a transform).
    SdfGrid(std::sync::Arc<crate::sdf_grid::SdfGrid>),
}

impl Geometry {
    /// Axis-aligned bounds as (min, max).
    pub fn bounds(&self) -> (Vec3, Vec3) {
        match self {
            Geometry::Triangles(mesh) => {
                let mut lo = Vec3::splat(f32::INFINITY);
                let mut hi = Vec3::splat(f32::NEG_INFINITY);
                for tri in &mesh.indices {
                    for &i in tri {
                        lo = lo.min(mesh.positions[i as usize]);
                        hi = hi.max(mesh.positions[i as usize]);
                    }
                }
                (lo, hi)
            }
            Geometry::Sphere(s) => (s.center - s.radius, s.center + s.radius),
            Geometry::SdfGrid(grid) => {
                grid.boxes.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), (a, b)| {
                    (lo.min(*a), hi.max(*b))
                })
            }
        }
    }
}

/// Geometry that one or more instances place in the scene.
#[derive(Clone, Debug)]
pub struct Prototype {
    pub geometry: Geometry,
    pub name: String,
}

/// Translation · rotation · scale, the form in which motion is interpolated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trs {
    pub translation: Vec3,
    pub rotation: Quat,
    pub scale: Vec3,
}

impl Trs {
    pub fn to_affine(&self) -> Affine3A {
        Affine3A::from_scale_rotation_translation(self.scale, self.rotation, self.translation)
    }

    /// Linear in translation and scale, spherical in rotation.
    pub fn lerp(&self, end: &Trs, t: f32) -> Trs {
        Trs {
            translation: self.translation.lerp(end.translation, t),
            rotation: self.rotation.slerp(end.rotation, t),
            scale: self.scale.lerp(end.scale, t),
        }
    }
}

/// Where an instance's prototype sits in render space.
#[derive(Clone, Debug)]
pub enum Placement {
    /// The prototype is already in render space. `object_from_render` maps back to the
    /// object's own space (for solid textures).
    Baked { object_from_render: Affine3A },
    /// A fixed transform of an object-space prototype.
    Static { render_from_object: Affine3A, object_from_render: Affine3A },
    /// Moves over the shutter interval: `start` at time 0, `end` at time 1.
    Moving { start: Trs, end: Trs },
}

impl Placement {
    /// `render_from_object` at `time`; `None` for baked geometry (identity).
    pub fn render_from_object(&self, time: f32) -> Option<Affine3A> {
        match self {
            Placement::Baked { .. } => None,
            Placement::Static { render_from_object, .. } => Some(*render_from_object),
            // Times outside the shutter are clamped, as Embree does.
            Placement::Moving { start, end } => {
                Some(start.lerp(end, time.clamp(0.0, 1.0)).to_affine())
            }
        }
    }

    /// `object_from_render` at `time`; `None` for baked geometry (identity).
    pub fn object_from_render(&self, time: f32) -> Option<Affine3A> {
        match self {
            Placement::Baked { .. } => None,
            Placement::Static { object_from_render, .. } => Some(*object_from_render),
            Placement::Moving { .. } => self.render_from_object(time).map(|m| m.inverse()),
        }
    }

    /// The object's own space for textures, at `time`.
    pub fn texture_object_from_render(&self, time: f32) -> Affine3A {
        match self {
            Placement::Baked { object_from_render } => *object_from_render,
            _ => self.object_from_render(time).unwrap_or(Affine3A::IDENTITY),
        }
    }

    pub fn is_moving(&self) -> bool {
        matches!(self, Placement::Moving { .. })
    }
}

/// Render-space bounds of object-space box (`lo`, `hi`) under `transform`.
pub fn transformed_bounds(transform: &Affine3A, lo: Vec3, hi: Vec3) -> (Vec3, Vec3) {
    let center = transform.transform_point3((lo + hi) * 0.5);
    let half = (hi - lo) * 0.5;
    let m = Mat3::from(transform.matrix3);
    let abs = Mat3::from_cols(m.x_axis.abs(), m.y_axis.abs(), m.z_axis.abs());
    let extent = abs * half;
    (center - extent, center + extent)
}

/// One placement of a prototype; its index in `RenderScene::instances` is the backends'
/// geometry id.
#[derive(Clone, Debug)]
pub struct Instance {
    pub prototype: u32,
    pub material: u32,
    pub placement: Placement,
    /// The scene object it came from (for messages).
    pub name: String,
}

#[derive(Clone, Debug)]
pub struct RenderScene {
    pub camera: Camera,
    pub prototypes: Vec<Prototype>,
    pub instances: Vec<Instance>,
    pub materials: Vec<Material>,
    pub lights: LightSet,
    /// Radiance of rays that leave the scene.
    pub background: Vec3,
    /// What camera rays that leave the scene see instead, over the image plane.
    pub backdrop: Option<Texture>,
    pub effects: Effects,
    /// Where in its pixel each sample falls, and its weight.
    pub pixel_filter: crate::sampling::filter::FilterSampler,
    /// Camera rays see no light source (`RenderSettings::hide_emitters`).
    pub hide_emitters: bool,
    /// Which normal decides the side of a surface (`RenderSettings::sides`).
    pub sides: crate::scene::Sides,
}

impl RenderScene {
    /// The radiance a camera ray through film position `raster` (pixels, from the top left)
    /// sees if it leaves the scene, when the scene has a backdrop. The image is laid over
    /// the film with texel centres on pixel centres when their sizes agree, so a backdrop of
    /// the film's size is seen texel for texel (galactica_static: 96.9 % of pixels within
    /// 3/255 of the reference; centres half a texel apart blur it, 51.6 %).
    pub fn backdrop_at(&self, raster: Vec2) -> Option<Vec3> {
        let texture = self.backdrop.as_ref()?;
        let size = Vec2::new(self.camera.width as f32, self.camera.height as f32);
        // Clamped, not repeated: the film's edges must not wrap to the image's far side.
        let uv =
            ((raster - Vec2::splat(0.5)) / size).clamp(Vec2::ZERO, Vec2::splat(1.0f32.next_down()));
        Some(texture.eval(Vec3::ZERO, uv))
    }

    pub fn prototype_of(&self, instance: u32) -> &Prototype {
        &self.prototypes[self.instances[instance as usize].prototype as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Vertex normals that repeat their faces' are dropped, on either side; any that bends
    /// (a smooth box's shared corners) or that is not a normal keeps them all.
    #[test]
    fn normals_of_flat_faces_are_dropped() {
        let square = vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
        let faces = vec![[0, 1, 2], [0, 2, 3]];
        let with = |normals: Vec<Vec3>| {
            TriangleMesh::new(square.clone(), faces.clone(), Some(normals), None).normals
        };
        assert_eq!(with(vec![Vec3::Z; 4]), None);
        assert_eq!(with(vec![Vec3::NEG_Z * 3.0; 4]), None, "one side, any length");
        // Off by 1e-5 rad (rounding) is flat; 1e-3 rad (a slight bevel) is not.
        let lean = |angle: f32| Vec3::new(angle.sin(), 0.0, angle.cos());
        assert_eq!(with(vec![Vec3::Z, Vec3::Z, lean(1e-5), Vec3::Z]), None);
        for normals in [
            vec![Vec3::Z, Vec3::Z, lean(1e-3), Vec3::Z],
            vec![Vec3::Z, Vec3::Z, Vec3::NEG_Z, Vec3::Z],
            vec![Vec3::Z, Vec3::Z, Vec3::ZERO, Vec3::Z],
            vec![Vec3::Z; 3],
        ] {
            assert_eq!(with(normals.clone()), Some(normals));
        }
        // A degenerate triangle has no face normal to repeat.
        let line = vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0];
        let mesh = TriangleMesh::new(line, vec![[0, 1, 2]], Some(vec![Vec3::Z; 3]), None);
        assert!(mesh.normals.is_some());
    }

    #[test]
    fn kept_planes_are_the_triangles_planes() {
        let positions =
            vec![Vec3::ZERO, Vec3::X, Vec3::new(0.3, 2.0, -1.0), Vec3::new(5.0, -1.0, 0.5)];
        let mesh = TriangleMesh::new(positions, vec![[0, 1, 2], [1, 3, 2], [3, 0, 2]], None, None);
        assert_eq!(mesh.planes.len(), 3);
        for prim in 0..3 {
            let triangle = mesh.triangle(prim);
            let (kept, fresh) = (mesh.plane(prim, &triangle), TrianglePlane::new(&triangle));
            assert_eq!(format!("{kept:?}"), format!("{fresh:?}"), "triangle {prim}");
            assert_eq!(kept.normal, fresh.normal);
        }
        // A mesh built field by field (no kept planes) computes them.
        let bare = TriangleMesh { planes: Vec::new(), ..mesh.clone() };
        assert_eq!(
            bare.plane(1, &bare.triangle(1)).normal,
            mesh.plane(1, &mesh.triangle(1)).normal
        );
    }
}
