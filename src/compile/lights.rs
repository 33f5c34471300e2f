//! Lights into render space: each kind of the description compiles itself (see
//! `light::kinds`); here are the emitters of every emissive instance (a quad per pair of
//! triangles that form a parallelogram, else one per primitive).

use crate::light::{
    Ellipsoid, Emitter, EmitterShape, InstanceEmitters, LightDesc, LightParts, LightSet,
    SphereShape,
};
use crate::render_scene::{Geometry, Instance, Placement, Prototype};
use crate::shading::material::Material;
use glam::{DAffine3, Vec3};

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
/// emitter among them; `None` if the instance is not sampled.
fn emitters_of_instance(
    geom_id: u32,
    prototype: &Prototype,
    instance: &Instance,
    material: &Material,
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
    match &prototype.geometry {
        Geometry::Triangles(mesh) => {
            let triangle = |prim: u32| {
                let mut tri = mesh.triangle(prim);
                if let Some(m) = transform {
                    tri = tri.map(|p| m.transform_point3(p));
                    // Sampled normals must face where hit normals do (see `place_mesh`).
                    if m.matrix3.determinant() < 0.0 {
                        tri.swap(1, 2);
                    }
                }
                tri
            };
            let count = mesh.indices.len() as u32;
            let mut emitters = Vec::new();
            let mut of_prim = Vec::with_capacity(count as usize);
            let mut prim = 0;
            while prim < count {
                let tri = triangle(prim);
                let index = emitters.len() as u32;
                let quad = (prim + 1 < count).then(|| as_quad(&tri, &triangle(prim + 1))).flatten();
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
                emitters.push(Emitter::new(geom_id, shape, material.emission, two_sided));
            }
            Some((emitters, of_prim))
        }
        Geometry::Sphere(s) => {
            let shape = match transform {
                None => EmitterShape::Sphere(SphereShape { center: s.center, radius: s.radius }),
                Some(m) => {
                    EmitterShape::Ellipsoid(Box::new(Ellipsoid::new(s.center, s.radius, m)?))
                }
            };
            Some((vec![Emitter::new(geom_id, shape, material.emission, two_sided)], vec![0]))
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
    let mut instance_emitters = InstanceEmitters::default();
    for (geom_id, instance) in instances.iter().enumerate() {
        let material = &materials[instance.material as usize];
        let sampled = material
            .is_emissive()
            .then(|| {
                let prototype = &prototypes[instance.prototype as usize];
                emitters_of_instance(geom_id as u32, prototype, instance, material)
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
