//! `<shape>` → objects: obj, ply, rectangle, cube and sphere, each with its BSDF (nested or
//! by reference; Mitsuba's default is a diffuse 0.5) and an `area` emitter's radiance.

use super::Builder;
use super::bsdfs::bsdf;
use super::transform::transform;
use super::tree::Element;
use super::values::{ColorUse, color, vec3};
use super::values::{boolean, float, property};
use crate::scene::desc::{MaterialDesc, MeshData, ObjectDesc, ShapeDesc};
use crate::scene::error::{Line, SceneError};
use crate::scene::formats::obj::ObjRef;
use crate::scene::shapes::{box_mesh, quad_mesh};
use glam::{DAffine3, DVec3};
use std::sync::Arc;

impl Builder<'_> {
    pub(super) fn shape(&mut self, element: &Element) -> Result<(), SceneError> {
        let kind = element.required("type")?;
        let known: &[&str] = match kind {
            "obj" => &["filename", "face_normals", "flip_normals", "flip_tex_coords", "to_world"],
            "ply" => &["filename", "face_normals", "flip_normals", "to_world"],
            "sphere" => &["center", "radius", "flip_normals", "to_world"],
            _ => &["flip_normals", "to_world"],
        };
        for child in &element.children {
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
        if boolean(element, "flip_normals")? == Some(true) {
            return Err(element.error("flip_normals is not supported yet"));
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
                };
                let (_, models) =
                    self.meshes.models(&mesh_ref, Some(!face_normals), self.warnings)?;
                // Mitsuba turns an OBJ's v upside down (flip_tex_coords, on by default), so
                // that v = 0 is the image's top row as for every other texture lookup.
                let flip = kind == "obj" && boolean(element, "flip_tex_coords")?.unwrap_or(true);
                models
                    .into_iter()
                    .map(|m| {
                        if !flip || m.mesh.uvs.is_none() {
                            return ShapeDesc::Mesh(m.mesh);
                        }
                        let mut mesh = MeshData::clone(&m.mesh);
                        for uv in mesh.uvs.iter_mut().flatten() {
                            uv.y = 1.0 - uv.y;
                        }
                        ShapeDesc::Mesh(Arc::new(mesh))
                    })
                    .collect()
            }
            "rectangle" => {
                let mesh = quad_mesh(DVec3::new(-1.0, -1.0, 0.0), 2.0 * DVec3::X, 2.0 * DVec3::Y)
                    .map_err(|p| element.error(p))?;
                vec![ShapeDesc::Mesh(Arc::new(mesh))]
            }
            "cube" => {
                let mesh =
                    box_mesh(DVec3::splat(-1.0), DVec3::ONE).map_err(|p| element.error(p))?;
                vec![ShapeDesc::Mesh(Arc::new(mesh))]
            }
            "sphere" => {
                let center = property(element, "point", "center")
                    .map_or(Ok(DVec3::ZERO), |c| vec3(c, false))?;
                let radius = float(element, "radius")?.unwrap_or(1.0);
                if !(radius > 0.0) {
                    return Err(element.error(format!("radius is {radius}, but must be > 0")));
                }
                vec![ShapeDesc::Sphere { center, radius }]
            }
            other => {
                return Err(element.error(format!(
                    "the shape '{other}' is not supported yet (obj, ply, rectangle, cube, sphere are)"
                )));
            }
        };
        for shape in shapes {
            self.objects.push(ObjectDesc {
                name: name.clone(),
                shape,
                material,
                world_from_object,
                world_from_object_end: None,
            });
        }
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
            [] => MaterialDesc { name: "default".to_owned(), albedo, ..Default::default() },
            [one] => bsdf(one, &self.ids, self.files)?,
            _ => return Err(element.error("a shape takes one <bsdf>")),
        };
        for emitter in emitters {
            if emitter.required("type")? != "area" {
                return Err(emitter.error("a shape's emitter must be of type area"));
            }
            let radiance = property(emitter, "rgb", "radiance")
                .or_else(|| property(emitter, "spectrum", "radiance"));
            let radiance = radiance.map_or(Ok(DVec3::ONE), |r| color(r, ColorUse::Emission))?;
            if !radiance.cmpge(DVec3::ZERO).all() {
                return Err(emitter.error("radiance must be >= 0"));
            }
            material.emission = radiance.as_vec3();
        }
        self.materials.push(material);
        let index = (self.materials.len() - 1) as u32;
        if let Some(id) = shared_id {
            self.shared_materials.insert(id, index);
        }
        Ok(index)
    }
}
