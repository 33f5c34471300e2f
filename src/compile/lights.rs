//! Lights into render space: each kind of the description compiles itself (see
//! `light::kinds`); here are the emitters of every emissive instance (a quad per pair of
//! triangles that form a parallelogram, else one per primitive).

use crate::light::{
    Ellipsoid, EmissionMap, Emitter, EmitterShape, InstanceEmitters, LightDesc, LightParts,
    LightSet, SphereShape, UvSource,
};
use crate::render_scene::{Geometry, Instance, Placement, Prototype};
use crate::shading::material::Material;
use glam::{DAffine3, Mat3, Vec2, Vec3};

/// The two triangles as the quad v0 v1 v2 v3 of `EmitterShape::Quad` ((v0, v1, v3) and
/// (v2, v3, v1)), if they share an edge, have the same winding and form a parallelogram.
fn as_quad(a: &[Vec3; 3], b: &[Vec3; 3]) -> Option<EmitterShape> {
    let rotate = |t: &[Vec3; 3], r: usize| [t[r], t[(r + 1) % 3], t[(r + 2) % 3]];
    for ra in 0..3 {
        let [x, y, z] = rotate(a, ra);
        for rb in 0..3 {
            let [w, z2, y2] = rotate(b, rb);
            if z2 == z && y2 == y {
                return EmitterShape::quad([x, y, w, z]);
            }
        }
    }
    None
}

/// The emitters of one emissive instance (a triangle per mesh primitive, one quad per pair
/// of consecutive triangles that form a parallelogram, or its sphere) and each primitive's
/// emitter among them; `None` if the instance is not sampled. `texture_mean` is the mean of
/// the material's emission texture (`Texture::mean_over_unit_square`), if it has one.
fn emitters_of_instance(
    geom_id: u32,
    prototype: &Prototype,
    instance: &Instance,
    material: &Material,
    texture_mean: Vec3,
) -> Option<(Vec<Emitter>, Vec<u32>)> {
    // Emitters that really move are not sampled: their emission is counted where rays hit
    // them (an emitter "moving" from a pose to the same pose is static).
    let transform = match &instance.placement {
        Placement::Baked { .. } => None,
        Placement::Static { render_from_object, .. } => Some(*render_from_object),
        Placement::Moving { start, end } if start == end => Some(start.to_affine()),
        Placement::Moving { .. } => return None,
    };
    let two_sided = material.two_sided_emission;
    let texture = material.emission_texture.as_ref();
    let map = |uvs: UvSource| {
        texture.map(|t| EmissionMap { texture: t.clone(), mean: texture_mean, uvs })
    };
    let emitter =
        |shape, uvs| Emitter::new(geom_id, shape, material.emission, two_sided).textured(map(uvs));
    match &prototype.geometry {
        Geometry::Triangles(mesh) => {
            // Sampled normals must face where hit normals do (see `place_mesh`).
            let mirrored = transform.is_some_and(|m| m.matrix3.determinant() < 0.0);
            let triangle = |prim: u32| {
                let mut tri = mesh.triangle(prim);
                if let Some(m) = transform {
                    tri = tri.map(|p| m.transform_point3(p));
                    if mirrored {
                        tri.swap(1, 2);
                    }
                }
                tri
            };
            // Each corner's texture coordinates, in the order of `triangle`'s (a hit on a
            // mesh without them has its barycentrics as coordinates).
            let corner_uvs = |prim: u32| {
                let mut uvs = match &mesh.uvs {
                    Some(uvs) => mesh.indices[prim as usize].map(|i| uvs[i as usize]),
                    None => [Vec2::ZERO, Vec2::X, Vec2::Y],
                };
                if mirrored {
                    uvs.swap(1, 2);
                }
                uvs
            };
            let count = mesh.indices.len() as u32;
            let mut emitters = Vec::new();
            let mut of_prim = Vec::with_capacity(count as usize);
            let mut prim = 0;
            while prim < count {
                let tri = triangle(prim);
                let index = emitters.len() as u32;
                // A textured emitter's coordinates are interpolated per triangle.
                let quad = (prim + 1 < count && texture.is_none())
                    .then(|| as_quad(&tri, &triangle(prim + 1)))
                    .flatten();
                let uvs = UvSource::Triangle { vertices: tri, uvs: corner_uvs(prim) };
                let shape = match quad {
                    Some(quad) => {
                        of_prim.extend([index, index]);
                        prim += 2;
                        quad
                    }
                    None => {
                        of_prim.push(index);
                        prim += 1;
                        EmitterShape::triangle(tri)
                    }
                };
                emitters.push(emitter(shape, uvs));
            }
            Some((emitters, of_prim))
        }
        Geometry::Sphere(s) => {
            // The frame a hit's texture coordinates are measured in (see `interaction`).
            let (shape, uvs) = match (transform, &instance.placement) {
                (None, placement) => {
                    // (Only a baked sphere has no transform: its own frame turned into render
                    // space.)
                    let object_from_render = match placement {
                        Placement::Baked { object_from_render } => object_from_render.matrix3,
                        Placement::Static { .. } | Placement::Moving { .. } => {
                            glam::Mat3A::IDENTITY
                        }
                    };
                    let uvs = UvSource::Sphere {
                        center: s.center,
                        object_from_render: Mat3::from(object_from_render),
                    };
                    (EmitterShape::Sphere(SphereShape { center: s.center, radius: s.radius }), uvs)
                }
                (Some(m), _) => {
                    let uvs = UvSource::Sphere {
                        center: m.transform_point3(s.center),
                        object_from_render: Mat3::from(m.matrix3).inverse(),
                    };
                    let ellipsoid = Ellipsoid::new(s.center, s.radius, m)?;
                    (EmitterShape::Ellipsoid(Box::new(ellipsoid)), uvs)
                }
            };
            Some((vec![emitter(shape, uvs)], vec![0]))
        }
        // Refused by the readers (as in Mitsuba, a grid has no area to sample).
        Geometry::SdfGrid(_) => None,
    }
}

/// The scene's lights in render space.
pub(super) fn compile_lights(
    descs: &[LightDesc],
    render_from_world: &DAffine3,
    prototypes: &[Prototype],
    instances: &[Instance],
    materials: &[Material],
) -> LightSet {
    let mut parts = LightParts::default();
    for light in descs {
        light.compile(render_from_world, &mut parts);
    }
    // Each emission texture's mean, computed once a material rather than once an instance.
    let texture_means: Vec<Vec3> = materials
        .iter()
        .map(|m| m.emission_texture.as_ref().map_or(Vec3::ONE, |t| t.mean_over_unit_square()))
        .collect();
    let mut instance_emitters = InstanceEmitters::default();
    for (geom_id, instance) in instances.iter().enumerate() {
        let material = &materials[instance.material as usize];
        let sampled = material
            .is_emissive()
            .then(|| {
                let prototype = &prototypes[instance.prototype as usize];
                let mean = texture_means[instance.material as usize];
                emitters_of_instance(geom_id as u32, prototype, instance, material, mean)
            })
            .flatten()
            .map(|(emitters, of_prim)| {
                let first = instance_emitters.emitters.len() as u32;
                instance_emitters.emitters.extend(emitters);
                of_prim.into_iter().map(|i| first + i).collect()
            });
        instance_emitters.by_instance.push(sampled);
    }
    let mut lights =
        LightSet::new(parts.points, parts.directional, instance_emitters, parts.invisible);
    lights.ambient = parts.ambient;
    lights.environment = parts.environment;
    lights
}
