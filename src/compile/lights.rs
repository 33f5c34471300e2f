//! Lights into render space: point, directional, ambient and the course's square lights from
//! the description, and one emitter per primitive of every emissive instance.

use crate::render_scene::{Geometry, Instance, Placement, Prototype};
use crate::scene::LightDesc;
use crate::shading::light::{
    DirectionalLight, Emitter, EmitterShape, LightSet, NO_GEOMETRY, PointLight,
};
use crate::shading::material::Material;
use crate::transform::course_square_axes;
use glam::{DAffine3, DVec3, Vec3};

/// The emitters of one emissive instance: a triangle per mesh primitive, or its sphere.
fn instance_emitters(
    geom_id: u32,
    prototype: &Prototype,
    instance: &Instance,
    emission: Vec3,
) -> Vec<Emitter> {
    // Emitters that really move are not sampled: their emission is counted where rays hit
    // them (an emitter "moving" from a pose to the same pose is static).
    let transform = match &instance.placement {
        Placement::Baked { .. } => None,
        Placement::Static { render_from_object, .. } => Some(*render_from_object),
        Placement::Moving { start, end } if start == end => Some(start.to_affine()),
        Placement::Moving { .. } => return Vec::new(),
    };
    match &prototype.geometry {
        Geometry::Triangles(mesh) => (0..mesh.indices.len() as u32)
            .map(|prim| {
                let mut tri = mesh.triangle(prim);
                if let Some(m) = transform {
                    tri = tri.map(|p| m.transform_point3(p));
                    // Sampled normals must face where hit normals do (see `place_mesh`).
                    if m.matrix3.determinant() < 0.0 {
                        tri.swap(1, 2);
                    }
                }
                let area = 0.5 * (tri[1] - tri[0]).cross(tri[2] - tri[0]).length();
                Emitter { geom_id, shape: EmitterShape::Triangle(tri), emission, area }
            })
            .collect(),
        Geometry::Sphere(s) => {
            if transform.is_some() {
                // Ellipsoids are not sampled either (no closed-form area sampling).
                return Vec::new();
            }
            let area = 4.0 * std::f32::consts::PI * s.radius * s.radius;
            vec![Emitter {
                geom_id,
                shape: EmitterShape::Sphere { center: s.center, radius: s.radius },
                emission,
                area,
            }]
        }
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
    let mut points = Vec::new();
    let mut directional = Vec::new();
    let mut ambient = Vec3::ZERO;
    let mut squares = Vec::new();
    for light in descs {
        match light {
            LightDesc::Point { position, intensity } => points.push(PointLight {
                position: render_from_world.transform_point3(*position).as_vec3(),
                intensity: *intensity,
            }),
            LightDesc::Directional { direction, irradiance } => {
                directional.push(DirectionalLight {
                    direction: render_from_world
                        .transform_vector3(*direction)
                        .normalize()
                        .as_vec3(),
                    irradiance: *irradiance,
                })
            }
            LightDesc::Ambient { radiance } => ambient += *radiance,
            LightDesc::Area { center, normal, size, radiance } => {
                let (u, v) = course_square_axes(*normal);
                let half = 0.5 * size;
                let edge = |e: DVec3| render_from_world.transform_vector3(e * half).as_vec3();
                let (edge_u, edge_v) = (edge(u), edge(v));
                squares.push(Emitter {
                    geom_id: NO_GEOMETRY,
                    shape: EmitterShape::Square {
                        center: render_from_world.transform_point3(*center).as_vec3(),
                        edge_u,
                        edge_v,
                        normal: render_from_world.transform_vector3(*normal).normalize().as_vec3(),
                    },
                    emission: *radiance,
                    area: 4.0 * edge_u.length() * edge_v.length(),
                });
            }
        }
    }
    let mut emitters = Vec::new();
    let mut first_emitter = vec![None; instances.len()];
    for (geom_id, instance) in instances.iter().enumerate() {
        let material = &materials[instance.material as usize];
        if !material.is_emissive() {
            continue;
        }
        let prototype = &prototypes[instance.prototype as usize];
        let mine = instance_emitters(geom_id as u32, prototype, instance, material.emission);
        if !mine.is_empty() {
            first_emitter[geom_id] = Some(emitters.len() as u32);
            emitters.extend(mine);
        }
    }
    // The course's squares come last: they are no instance's, so `first_emitter` skips them.
    emitters.extend(squares);
    let mut lights = LightSet::new(points, directional, emitters, first_emitter);
    lights.ambient = ambient;
    lights
}
