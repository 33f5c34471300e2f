//! `<shape>` → objects: obj, ply, rectangle, cube, sphere, disk and cylinder, each with its
//! BSDF (nested or by reference; Mitsuba's default is a one-sided diffuse 0.5) and an `area`
//! emitter's radiance; `shapegroup`s placed by `instance`s share their meshes.

mod checks;
mod sdfgrid;
mod winding;

pub(super) use winding::Prepared;

use super::Builder;
use super::bsdfs::bsdf;
use super::transform::transform;
use super::tree::Element;
use super::values::vec3;
use super::values::{boolean, float, property};
use crate::scene::desc::{MaterialDesc, MeshData, ObjectDesc, ShapeDesc};
use crate::scene::error::{Line, SceneError};
use crate::scene::formats::obj::ObjRef;
use crate::scene::round_shapes::{cylinder_mesh, disk_mesh};
use crate::scene::shapes::{mitsuba_cube_mesh, quad_mesh};
use crate::scene::vertex_normals::{VertexNormals, keeps_angles};
use glam::{DAffine3, DMat3, DVec3};
use std::sync::Arc;

impl Builder<'_> {
    pub(super) fn shape(&mut self, element: &Element) -> Result<(), SceneError> {
        let kind = element.required("type")?;
        match kind {
            "shapegroup" => {
                let id = element.required("id")?;
                if !self.groups.contains_key(id) {
                    let group = self.shape_group(element)?;
                    self.groups.insert(id.to_owned(), group);
                }
                return Ok(());
            }
            "instance" => return self.instance(element),
            _ => {}
        }
        let known: &[&str] = match kind {
            "obj" => &["filename", "face_normals", "flip_normals", "flip_tex_coords", "to_world"],
            "ply" => &["filename", "face_normals", "flip_normals", "to_world"],
            "serialized" => {
                &["filename", "shape_index", "face_normals", "flip_normals", "to_world"]
            }
            "sphere" => &["center", "radius", "flip_normals", "to_world"],
            "cylinder" => &["p0", "p1", "radius", "flip_normals", "to_world"],
            "sdfgrid" => &["filename", "normals", "to_world"],
            _ => &["flip_normals", "to_world"],
        };
        for child in &element.children {
            if child.tag == "medium" || matches!(child.attr("name"), Some("interior" | "exterior"))
            {
                return Err(child.error("participating media (<medium>) are not supported"));
            }
            match child.attr("name") {
                Some(name) if known.contains(&name) => {}
                Some(_) if matches!(child.tag.as_str(), "ref" | "bsdf" | "emitter") => {}
                Some(name) => {
                    return Err(child.error(format!(
                        "{} does not take `{name}` (it takes: {})",
                        element.describe(),
                        known.join(", ")
                    )));
                }
                None if matches!(child.tag.as_str(), "ref" | "bsdf" | "emitter") => {}
                None => {
                    return Err(child.error(format!("a shape does not take a <{}>", child.tag)));
                }
            }
        }
        let world_from_object = match property(element, "transform", "to_world") {
            Some(t) => transform(t)?,
            None => DAffine3::IDENTITY,
        };
        let flip_normals = boolean(element, "flip_normals")?.unwrap_or(false);
        if flip_normals && kind == "sphere" {
            return Err(element.error("flip_normals on a sphere is not supported yet"));
        }
        if let (Some(file), "obj" | "ply" | "serialized") =
            (property(element, "string", "filename"), kind)
        {
            mesh_type_matches(file, kind)?;
        }
        let material = self.shape_material(element)?;
        let name = format!("{} (line {})", element.describe(), element.line);
        let shapes: Vec<ShapeDesc> = match kind {
            "obj" | "ply" => {
                let file = property(element, "string", "filename")
                    .ok_or_else(|| element.error("the property `filename` is missing"))?;
                let face_normals = boolean(element, "face_normals")?.unwrap_or(false);
                let mesh_ref = ObjRef {
                    obj: self.files.resolve(file.required("value")?),
                    scene: &file.file,
                    item: file.describe(),
                    line: Line(Some(file.line)),
                    // Mitsuba's OBJ reader ignores `mtllib` and `usemtl`.
                    read_mtl: false,
                };
                // Mitsuba computes a smooth mesh's missing normals after `to_world`: the same
                // as before it (the cache's shared variant) unless `to_world` bends angles.
                let linear = world_from_object.matrix3;
                let placed = !face_normals && !keeps_angles(linear);
                let smooth = if placed { None } else { Some(!face_normals) };
                // Under a mirror, models without normals in the file turn inside out.
                let mirrored = linear.determinant() < 0.0;
                let own = match mirrored {
                    true => self.meshes.models(&mesh_ref, None, self.warnings)?.1,
                    false => Vec::new(),
                };
                let (_, mut models) = self.meshes.models(&mesh_ref, smooth, self.warnings)?;
                for (i, model) in models.iter_mut().enumerate() {
                    if placed {
                        model.mesh = with_normals_placed(Arc::clone(&model.mesh), linear);
                    }
                    if mirrored && (face_normals || own[i].mesh.normals.is_none()) {
                        model.mesh = Arc::new(flipped(&model.mesh));
                    }
                }
                // Mitsuba turns an OBJ's v upside down (flip_tex_coords, on by default), so
                // that v = 0 is the image's top row as for every other texture lookup.
                let flip = kind == "obj" && boolean(element, "flip_tex_coords")?.unwrap_or(true);
                models
                    .into_iter()
                    .map(|m| ShapeDesc::Mesh(self.prepared.mesh(m.mesh, flip)))
                    .collect()
            }
            "rectangle" => {
                let mesh = quad_mesh(DVec3::new(-1.0, -1.0, 0.0), 2.0 * DVec3::X, 2.0 * DVec3::Y)
                    .map_err(|p| element.error(p))?;
                vec![ShapeDesc::Mesh(Arc::new(mesh))]
            }
            "cube" => vec![ShapeDesc::Mesh(Arc::new(mitsuba_cube_mesh()))],
            "serialized" => {
                let linear = world_from_object.matrix3;
                let (mesh, computed) = self.serialized(element, linear)?;
                let mesh = winding::wound_as_normals(Arc::new(mesh));
                match linear.determinant() < 0.0 && computed {
                    true => vec![ShapeDesc::Mesh(Arc::new(flipped(&mesh)))],
                    false => vec![ShapeDesc::Mesh(mesh)],
                }
            }
            "disk" => vec![ShapeDesc::Mesh(Arc::new(disk_mesh()))],
            "sdfgrid" => vec![self.sdf_grid(element, &world_from_object)?],
            "cylinder" => {
                let radius = float(element, "radius")?.unwrap_or(1.0);
                let point = |name: &str, default: DVec3| {
                    property(element, "point", name).map_or(Ok(default), |p| vec3(p, None))
                };
                let (p0, p1) = (point("p0", DVec3::ZERO)?, point("p1", DVec3::Z)?);
                let length = (p1 - p0).length();
                if !(radius > 0.0 && length > 0.0) {
                    return Err(element.error("a cylinder needs a radius > 0 and p0 ≠ p1"));
                }
                // Mitsuba's placement of the unit cylinder between p0 and p1.
                let axis = (p1 - p0) / length;
                let frame = DAffine3::from_quat(glam::DQuat::from_rotation_arc(DVec3::Z, axis));
                let own = DAffine3::from_translation(p0)
                    * frame
                    * DAffine3::from_scale(DVec3::new(radius, radius, length));
                self.push_objects(
                    &name,
                    vec![ShapeDesc::Mesh(Arc::new(cylinder_mesh()))],
                    material,
                    world_from_object * own,
                    flip_normals,
                );
                return Ok(());
            }
            "sphere" => {
                let center = property(element, "point", "center")
                    .map_or(Ok(DVec3::ZERO), |c| vec3(c, None))?;
                let radius = float(element, "radius")?.unwrap_or(1.0);
                if !(radius > 0.0) {
                    return Err(element.error(format!("radius is {radius}, but must be > 0")));
                }
                checks::sphere_to_world(element, &world_from_object)?;
                // Mitsuba's sphere is to_world · translate(center) · scale(radius) of the
                // unit sphere, with u = φ/2π about its z axis and v = θ/π from +z; embray's
                // measures u = ½ − atan2(z, x)/2π about y. Its frame turned (x, y, z) →
                // (−x, z, y) makes the two the same coordinates.
                let mitsuba_from_embray = glam::DMat3::from_cols(DVec3::NEG_X, DVec3::Z, DVec3::Y);
                let own = DAffine3::from_translation(center)
                    * DAffine3::from_scale(DVec3::splat(radius))
                    * DAffine3::from_mat3(mitsuba_from_embray);
                let shapes = vec![ShapeDesc::Sphere { center: DVec3::ZERO, radius: 1.0 }];
                checks::mesh_attributes(element, &shapes, &self.materials[material as usize])?;
                self.push_objects(&name, shapes, material, world_from_object * own, false);
                return Ok(());
            }
            other => {
                return Err(element.error(format!(
                    "the shape '{other}' is not supported yet (obj, ply, serialized, rectangle, \
                     cube, sphere, disk, cylinder, sdfgrid, shapegroup, instance are)"
                )));
            }
        };
        checks::mesh_attributes(element, &shapes, &self.materials[material as usize])?;
        self.push_objects(&name, shapes, material, world_from_object, flip_normals);
        Ok(())
    }

    fn push_objects(
        &mut self,
        name: &str,
        shapes: Vec<ShapeDesc>,
        material: u32,
        world_from_object: DAffine3,
        flip_normals: bool,
    ) {
        for shape in shapes {
            let shape = match shape {
                ShapeDesc::Mesh(mesh) if flip_normals => ShapeDesc::Mesh(Arc::new(flipped(&mesh))),
                shape => shape,
            };
            self.objects.push(ObjectDesc {
                name: name.to_owned(),
                shape,
                material,
                world_from_object,
                world_from_object_end: None,
            });
        }
    }

    /// The mesh of a `serialized` shape, and whether its normals are computed (or it has
    /// none: `face_normals`) rather than the file's.
    fn serialized(&self, element: &Element, linear: DMat3) -> Result<(MeshData, bool), SceneError> {
        let file = property(element, "string", "filename")
            .ok_or_else(|| element.error("the property `filename` is missing"))?;
        let path = self.files.resolve(file.required("value")?);
        let index = super::values::integer(element, "shape_index")?.unwrap_or(0);
        let index = u32::try_from(index)
            .map_err(|_| element.error(format!("shape_index is {index}, but must be >= 0")))?;
        let face_normals = boolean(element, "face_normals")?.unwrap_or(false);
        let bytes = crate::input_file::read_bytes(&path)
            .map_err(|e| file.error(format!("cannot read '{}': {e}", path.display())))?;
        let mut mesh = crate::scene::formats::serialized::parse(&bytes, index, face_normals)
            .map_err(|problem| file.error(format!("'{}': {problem}", path.display())))?;
        // Mitsuba computes a smooth mesh's missing normals (after `to_world`), as for its OBJ
        // and PLY files.
        let computed = mesh.normals.is_none();
        if computed && !face_normals {
            let normals =
                VertexNormals::AngleWeighted.of_placed(&mesh.positions, &mesh.indices, linear);
            mesh.normals = Some(normals);
        }
        Ok((mesh, computed))
    }

    /// The objects of a `shapegroup`, in the group's own space.
    fn shape_group(&mut self, element: &Element) -> Result<Vec<ObjectDesc>, SceneError> {
        let before = self.objects.len();
        for child in &element.children {
            if child.tag != "shape" {
                return Err(
                    child.error(format!("a shapegroup holds shapes, not a <{}>", child.tag))
                );
            }
            if matches!(child.attr("type"), Some("shapegroup" | "instance")) {
                return Err(child.error("a shapegroup inside a shapegroup is not supported"));
            }
            if child.children.iter().any(|c| c.tag == "emitter") {
                return Err(child.error("a shape in a shapegroup cannot emit (as in Mitsuba)"));
            }
            self.shape(child)?;
        }
        Ok(self.objects.split_off(before))
    }

    /// Every object of the referenced shapegroup, placed by the instance's `to_world`.
    fn instance(&mut self, element: &Element) -> Result<(), SceneError> {
        let mut group = None;
        for child in &element.children {
            match (child.tag.as_str(), child.attr("name")) {
                ("ref", _) | ("shape", _) if group.is_none() => {
                    group = Some(self.ids.resolve(child)?.clone())
                }
                ("transform", Some("to_world")) => {}
                _ => return Err(child.error("an instance takes a shapegroup and a to_world")),
            }
        }
        let group =
            group.ok_or_else(|| element.error("an instance needs a <ref> to a shapegroup"))?;
        if group.attr("type") != Some("shapegroup") {
            return Err(element.error("an instance must refer to a shapegroup"));
        }
        let id = group.required("id")?.to_owned();
        if !self.groups.contains_key(&id) {
            let objects = self.shape_group(&group)?;
            self.groups.insert(id.clone(), objects);
        }
        let placement = match property(element, "transform", "to_world") {
            Some(t) => transform(t)?,
            None => DAffine3::IDENTITY,
        };
        let name = format!("{} (line {})", element.describe(), element.line);
        let placements = self.objects.len().saturating_add(self.groups[&id].len()) as u64;
        crate::scene::reading_budget::check_placements(&element.file, placements, || name.clone())?;
        self.objects.extend(self.groups[&id].iter().map(|o| ObjectDesc {
            name: format!("{name}: {}", o.name),
            world_from_object: placement * o.world_from_object,
            ..o.clone()
        }));
        Ok(())
    }

    /// The shape's material (its BSDF, with an area emitter's radiance), added to the list.
    fn shape_material(&mut self, element: &Element) -> Result<u32, SceneError> {
        let mut bsdfs = Vec::new();
        let mut emitters = Vec::new();
        for child in &element.children {
            if matches!(child.tag.as_str(), "bsdf" | "emitter" | "ref") {
                let found = self.ids.resolve(child)?;
                match found.tag.as_str() {
                    "bsdf" => bsdfs.push(found),
                    "emitter" => emitters.push(found),
                    other => return Err(child.error(format!("a shape does not take a <{other}>"))),
                }
            }
        }
        if let Some(second) = emitters.get(1) {
            // As Mitsuba: the last would win unseen.
            return Err(second.error(format!("{} takes one <emitter>", element.describe())));
        }
        let emitting = !emitters.is_empty();
        // Shapes that share a BSDF by id (and emit nothing) share one material.
        let shared_id = match bsdfs[..] {
            [one] if !emitting => one.attr("id").map(str::to_owned),
            _ => None,
        };
        if let Some(index) = shared_id.as_ref().and_then(|id| self.shared_materials.get(id)) {
            return Ok(*index);
        }
        // Mitsuba's default BSDF: diffuse 0.5, or black for an emitter.
        let albedo = glam::Vec3::splat(if emitting { 0.0 } else { 0.5 });
        let mut material = match bsdfs[..] {
            [] => MaterialDesc {
                name: "default".to_owned(),
                albedo,
                one_sided: true,
                ..Default::default()
            },
            [one] => bsdf(one, &self.ids, self.files)?,
            _ => return Err(element.error("a shape takes one <bsdf>")),
        };
        for emitter in emitters {
            if emitter.required("type")? != "area" {
                return Err(emitter.error("a shape's emitter must be of type area"));
            }
            (material.emission, material.emission_texture) =
                super::bsdfs::area_radiance(emitter, &self.ids, self.files)?;
        }
        self.materials.push(material);
        let index = (self.materials.len() - 1) as u32;
        if let Some(id) = shared_id {
            self.shared_materials.insert(id, index);
        }
        Ok(index)
    }
}

/// `mesh` with its faces turned over: winding reversed, normals negated.
fn flipped(mesh: &MeshData) -> MeshData {
    MeshData {
        indices: mesh.indices.iter().map(|&[a, b, c]| [a, c, b]).collect(),
        normals: mesh.normals.as_ref().map(|n| n.iter().map(|v| -*v).collect()),
        ..mesh.clone()
    }
}

/// Refuses a mesh file whose extension names another of Mitsuba's mesh plugins than `kind`:
/// Mitsuba's plugin would fail to parse it, where embray would read it by its extension.
fn mesh_type_matches(file: &Element, kind: &str) -> Result<(), SceneError> {
    let name = file.required("value")?;
    let extension = std::path::Path::new(name).extension().and_then(|e| e.to_str());
    let extension = extension.map(str::to_ascii_lowercase).unwrap_or_default();
    if ["obj", "ply", "serialized"].contains(&extension.as_str()) && extension != kind {
        return Err(file.error(format!(
            "a <shape type=\"{kind}\"> given a .{extension} file (use <shape \
             type=\"{extension}\">)"
        )));
    }
    Ok(())
}

/// `mesh` with Mitsuba's normals computed where `linear` places it, if it has none.
fn with_normals_placed(mesh: Arc<MeshData>, linear: DMat3) -> Arc<MeshData> {
    if mesh.normals.is_some() {
        return mesh;
    }
    let mut placed = MeshData::clone(&mesh);
    let normals = VertexNormals::AngleWeighted.of_placed(&mesh.positions, &mesh.indices, linear);
    placed.normals = Some(normals);
    Arc::new(placed)
}
