//! Objects into prototypes and instances: a mesh used once and not moving is baked into
//! render space; a mesh used by several objects (or moving) becomes one shared prototype
//! placed by transforms; a sphere under a uniform scale is baked, an ellipsoid or a moving
//! sphere is an object-space sphere placed by a transform.

use super::CompileError;
use crate::render_scene::{Geometry, Instance, Placement, Prototype, Sphere, TriangleMesh, Trs};
use crate::scene::{MeshData, ObjectDesc, SdfGridData, ShapeDesc};
use crate::sdf_grid::SdfGrid;
use crate::transform::{invertible_in_f32, motion_parts, normal_matrix, uniform_scale};
use glam::{Affine3A, DAffine3, DMat4, DQuat, DVec3, Vec3};
use std::collections::HashMap;
use std::sync::Arc;

pub(super) fn to_affine_f32(m: &DAffine3) -> Affine3A {
    Affine3A::from_mat4(DMat4::from(*m).as_mat4())
}

fn place_mesh(
    mesh: &MeshData,
    render_from_object: &DAffine3,
    name: &str,
) -> Result<TriangleMesh, CompileError> {
    let positions: Vec<Vec3> =
        mesh.positions.iter().map(|&p| render_from_object.transform_point3(p).as_vec3()).collect();
    if positions.iter().any(|p| !p.is_finite()) {
        return Err(CompileError::NotRepresentable(name.to_string()));
    }
    let normals = match &mesh.normals {
        Some(normals) => {
            let normal_from_object = normal_matrix(render_from_object)
                .ok_or_else(|| CompileError::SingularTransform(name.to_string()))?;
            Some(
                normals
                    .iter()
                    .map(|&n| (normal_from_object * n).normalize_or_zero().as_vec3())
                    .collect(),
            )
        }
        None => None,
    };
    // One handedness rule: a surface's outward side is where its normal, transformed as a
    // normal (`normal_matrix`), points. A mirroring transform reverses the winding's cross
    // product, so a mirrored mesh baked into render space gets its winding flipped, and its
    // normal agrees with the same mesh placed as an instance.
    let indices = if render_from_object.matrix3.determinant() < 0.0 {
        mesh.indices.iter().map(|&[a, b, c]| [a, c, b]).collect()
    } else {
        mesh.indices.clone()
    };
    let baked = TriangleMesh::new(positions, indices, normals, mesh.uvs.clone());
    Ok(baked.with_attributes(mesh.attributes.clone()))
}

/// The interpolated form of a transform's scale, rotation and translation.
fn trs((scale, rotation, translation): (DVec3, DQuat, DVec3)) -> Trs {
    Trs {
        translation: translation.as_vec3(),
        rotation: rotation.as_quat().normalize(),
        scale: scale.as_vec3(),
    }
}

/// Builds prototypes and instances object by object.
pub(super) struct Placer {
    render_from_world: DAffine3,
    /// Every object gets a motion placement (`EffectsMode::ForceAll`).
    force_motion: bool,
    /// How many objects name each mesh.
    mesh_users: HashMap<*const MeshData, usize>,
    /// The prototype of each mesh placed by transforms.
    shared_prototypes: HashMap<*const MeshData, u32>,
    /// The prototype of each signed distance grid.
    shared_grids: HashMap<*const SdfGridData, u32>,
    pub(super) prototypes: Vec<Prototype>,
    pub(super) instances: Vec<Instance>,
}

impl Placer {
    pub(super) fn new(
        objects: &[ObjectDesc],
        render_from_world: DAffine3,
        force_motion: bool,
    ) -> Self {
        let mut mesh_users: HashMap<*const MeshData, usize> = HashMap::new();
        for object in objects {
            if let ShapeDesc::Mesh(mesh) = &object.shape {
                *mesh_users.entry(Arc::as_ptr(mesh)).or_default() += 1;
            }
        }
        Placer {
            render_from_world,
            force_motion,
            mesh_users,
            shared_prototypes: HashMap::new(),
            shared_grids: HashMap::new(),
            prototypes: Vec::new(),
            instances: Vec::with_capacity(objects.len()),
        }
    }

    fn push_prototype(&mut self, geometry: Geometry, name: &str) -> u32 {
        self.prototypes.push(Prototype { geometry, name: name.to_owned() });
        (self.prototypes.len() - 1) as u32
    }

    /// Adds one object as an instance (and its prototype, unless it shares one).
    pub(super) fn place(&mut self, object: &ObjectDesc) -> Result<(), CompileError> {
        let name = &object.name;
        let render_from_object = self.render_from_world * object.world_from_object;
        // Refused here for both backends, in the precision they hold it in.
        if !render_from_object.is_finite() || !invertible_in_f32(&render_from_object) {
            return Err(CompileError::SingularTransform(name.clone()));
        }
        let moving = object.is_moving() || self.force_motion;
        let render_from_world = self.render_from_world;
        // `object_from_prototype` maps the prototype's own space (a grid's units) to the
        // object's.
        let transformed = |object_from_prototype: DAffine3| -> Result<Placement, CompileError> {
            let render_from_object = render_from_object * object_from_prototype;
            // Checked again with the prototype's map composed in (a grid's 1/voxels scale
            // can make an invertible transform singular in f32), at both shutter ends.
            if !render_from_object.is_finite() || !invertible_in_f32(&render_from_object) {
                return Err(CompileError::SingularTransform(name.clone()));
            }
            if moving {
                let end = render_from_world
                    * object.world_from_object_end.unwrap_or(object.world_from_object)
                    * object_from_prototype;
                if !end.is_finite() || !invertible_in_f32(&end) {
                    return Err(CompileError::SingularTransform(name.clone()));
                }
                // Refused here for both backends (Embree would refuse a change of sign too).
                let [start, end] = motion_parts(&render_from_object, &end)
                    .map_err(|problem| CompileError::Motion(name.clone(), problem))?;
                Ok(Placement::Moving { start: trs(start), end: trs(end) })
            } else {
                Ok(Placement::Static {
                    render_from_object: to_affine_f32(&render_from_object),
                    object_from_render: to_affine_f32(&render_from_object.inverse()),
                })
            }
        };
        let baked =
            Placement::Baked { object_from_render: to_affine_f32(&render_from_object.inverse()) };
        let (prototype, placement) = match &object.shape {
            ShapeDesc::Mesh(mesh) => {
                let key = Arc::as_ptr(mesh);
                if self.mesh_users[&key] == 1 && !moving {
                    let geometry =
                        Geometry::Triangles(place_mesh(mesh, &render_from_object, name)?);
                    (self.push_prototype(geometry, name), baked)
                } else {
                    let index = match self.shared_prototypes.get(&key) {
                        Some(&index) => index,
                        None => {
                            let geometry =
                                Geometry::Triangles(place_mesh(mesh, &DAffine3::IDENTITY, name)?);
                            let index = self.push_prototype(geometry, name);
                            self.shared_prototypes.insert(key, index);
                            index
                        }
                    };
                    (index, transformed(DAffine3::IDENTITY)?)
                }
            }
            ShapeDesc::Sphere { center, radius } => {
                match uniform_scale(&object.world_from_object).filter(|_| !moving) {
                    Some(scale) => {
                        let sphere = Sphere {
                            center: render_from_object.transform_point3(*center).as_vec3(),
                            radius: (radius * scale) as f32,
                        };
                        if !sphere.center.is_finite()
                            || !(sphere.radius > 0.0)
                            || !sphere.radius.is_finite()
                        {
                            return Err(CompileError::NotRepresentable(name.clone()));
                        }
                        (self.push_prototype(Geometry::Sphere(sphere), name), baked)
                    }
                    None => {
                        // Ellipsoids and moving spheres: an object-space sphere, transformed.
                        let sphere = Sphere { center: center.as_vec3(), radius: *radius as f32 };
                        let placement = transformed(DAffine3::IDENTITY)?;
                        (self.push_prototype(Geometry::Sphere(sphere), name), placement)
                    }
                }
            }
            ShapeDesc::SdfGrid(data) => {
                // Always placed by a transform: the grid's prototype is in grid units (every
                // voxel a unit cube), scaled onto the object's [0, 1]³.
                let key = Arc::as_ptr(data);
                let index = match self.shared_grids.get(&key) {
                    Some(&index) => index,
                    None => {
                        let grid = SdfGrid::new(data.clone())
                            .ok_or_else(|| CompileError::EmptySdfGrid(name.clone()))?;
                        let index = self.push_prototype(Geometry::SdfGrid(Arc::new(grid)), name);
                        self.shared_grids.insert(key, index);
                        index
                    }
                };
                let voxels = DVec3::from_array(data.voxels().map(f64::from));
                (index, transformed(DAffine3::from_scale(voxels.recip()))?)
            }
        };
        self.instances.push(Instance {
            prototype,
            material: object.material,
            placement,
            name: name.clone(),
        });
        Ok(())
    }
}
