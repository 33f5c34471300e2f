//! `<VertexData>`, `<TexCoordData>` and `<Objects>` → `ObjectDesc`s.
//!
//! Indices are 1-based into the scene's vertex list (plus a `Faces` element's
//! `vertexOffset`). Each inline mesh keeps only the vertices it uses; `shadingMode="smooth"`
//! gives it area-weighted vertex normals over its own faces. A `plyFile` (relative to the
//! XML) is read by the crate's PLY loader. A `MeshInstance` shares its base mesh's
//! `Arc<MeshData>`, so the renderer instances it; with `resetTransform="true"` only its own
//! transformations apply, otherwise they apply on top of the base mesh's. `MotionBlur` is a
//! translation over the shutter: `world_from_object_end = translate(v) · world_from_object`.
//! `LightMesh` and `LightSphere` (hw6) are a mesh and a sphere that also emit `Radiance`:
//! each gets its own copy of its material with that emission, appended to the material
//! list, so the renderer samples it like any emitter (one-sided, where its normal points).
//! An object with `<Textures>` likewise gets its own copy of its material with the texture
//! maps attached; a mesh with an image texture must have texture coordinates for every
//! vertex (the course gives no meaning to a missing one), from `<TexCoordData>`
//! (`inline_mesh`) or its PLY file.

use super::inline_mesh::{InlineMesh, inline_mesh, vertex_index};
use super::materials::Materials;
use super::textures::TextureMaps;
use super::transforms::Transforms;
use super::xml::{Xml, describe, id_list, tokens};
use crate::scene::desc::{MaterialDesc, MeshData, ObjectDesc, ShapeDesc};
use crate::scene::error::SceneError;
use crate::scene::formats::obj::ObjRef;
use crate::scene::mesh_file::MeshCache;
use glam::{DAffine3, DVec3, Vec2};
use roxmltree::Node;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// Everything objects refer to.
pub(super) struct Refs<'a> {
    pub base_dir: &'a Path,
    pub materials: &'a Materials,
    pub transforms: &'a Transforms,
    pub vertices: &'a [DVec3],
    pub texcoords: &'a [Vec2],
    pub textures: &'a TextureMaps,
}

/// A mesh as a `MeshInstance` finds it.
struct BaseMesh {
    mesh: Arc<MeshData>,
    /// Why the mesh has no texture coordinates, where it has none.
    no_uvs: Option<String>,
    world_from_object: DAffine3,
    material: u32,
}

struct Builder<'a, 'x, 'i> {
    x: &'a Xml<'x, 'i>,
    refs: &'a Refs<'a>,
    cache: MeshCache,
    warnings: &'a mut Vec<String>,
    meshes: HashMap<String, BaseMesh>,
    objects: Vec<ObjectDesc>,
    /// Materials made for object lights and textured objects, numbered after the file's.
    extra_materials: Vec<MaterialDesc>,
}

/// The objects of a file and the materials its object lights added.
pub(super) struct Objects {
    pub objects: Vec<ObjectDesc>,
    pub extra_materials: Vec<MaterialDesc>,
}

pub(super) fn objects<'a, 'i: 'a>(
    x: &Xml,
    refs: &Refs,
    lists: impl Iterator<Item = Node<'a, 'i>> + Clone,
    warnings: &mut Vec<String>,
) -> Result<Objects, SceneError> {
    let mut b = Builder {
        x,
        refs,
        cache: MeshCache::default(),
        warnings,
        meshes: HashMap::new(),
        objects: Vec::new(),
        extra_materials: Vec::new(),
    };
    const KINDS: [&str; 6] =
        ["Mesh", "Triangle", "Sphere", "MeshInstance", "LightMesh", "LightSphere"];
    for list in lists.clone() {
        x.check_children(list, &KINDS)?;
        for node in list.children().filter(Node::is_element) {
            match node.tag_name().name() {
                "Mesh" => b.mesh(node, false)?,
                "LightMesh" => b.mesh(node, true)?,
                "Triangle" => b.triangle(node)?,
                "Sphere" => b.sphere(node, false)?,
                "LightSphere" => b.sphere(node, true)?,
                _ => {}
            }
        }
    }
    // Instances after every mesh, so that they may name a mesh defined later in the file.
    for list in lists {
        for node in list.children().filter(|n| n.has_tag_name("MeshInstance")) {
            b.instance(node)?;
        }
    }
    Ok(Objects { objects: b.objects, extra_materials: b.extra_materials })
}

impl Builder<'_, '_, '_> {
    fn material(&mut self, node: Node) -> Result<u32, SceneError> {
        let material = self.refs.materials.lookup(self.x, self.x.required(node, "Material")?)?;
        self.with_textures(node, material)
    }

    /// The material at `index` (of the file's, or one made here), in full.
    fn material_desc(&self, index: u32) -> &MaterialDesc {
        let file = &self.refs.materials.list;
        file.get(index as usize)
            .unwrap_or_else(|| &self.extra_materials[index as usize - file.len()])
    }

    /// `material`, or a copy of it with the texture maps `node` lists.
    fn with_textures(&mut self, node: Node, material: u32) -> Result<u32, SceneError> {
        let base = self.material_desc(material);
        match self.refs.textures.textured(self.x, node, base)? {
            None => Ok(material),
            Some(textured) => Ok(self.add_material(textured)),
        }
    }

    fn add_material(&mut self, material: MaterialDesc) -> u32 {
        let index = self.refs.materials.list.len() + self.extra_materials.len();
        self.extra_materials.push(material);
        index as u32
    }

    /// An image texture needs texture coordinates at every vertex; without them it would
    /// show one texel, or whatever a renderer defaults to, without a word.
    fn require_uvs(
        &self,
        node: Node,
        material: u32,
        no_uvs: Option<&str>,
    ) -> Result<(), SceneError> {
        let m = self.material_desc(material);
        let bump = m.bump_map.as_ref().map(|b| &b.texture);
        let textures = [&m.texture, &m.specular_texture, &m.normal_map];
        let image = textures.into_iter().flatten().chain(bump).any(|t| t.image().is_some());
        match no_uvs {
            Some(why) if image => Err(self.x.error(
                node,
                format!("the object has an image texture but no texture coordinates: {why}"),
            )),
            _ => Ok(()),
        }
    }

    /// `<Transformations>` and `<MotionBlur>` of `node`, on top of `base`.
    fn placement(
        &self,
        node: Node,
        base: DAffine3,
    ) -> Result<(DAffine3, Option<DAffine3>), SceneError> {
        let own = self.refs.transforms.compose(self.x, self.x.child(node, "Transformations")?)?;
        let start = own * base;
        let det = start.matrix3.determinant();
        if !start.is_finite() || !det.is_finite() || det == 0.0 {
            return Err(self.x.error(node, "the composed transformation is singular or overflows"));
        }
        let end = match self.x.child(node, "MotionBlur")? {
            Some(m) => Some(DAffine3::from_translation(self.x.vec3(m)?) * start),
            None => None,
        };
        Ok((start, end))
    }

    fn push(
        &mut self,
        node: Node,
        shape: ShapeDesc,
        material: u32,
        place: (DAffine3, Option<DAffine3>),
    ) {
        self.objects.push(ObjectDesc {
            name: describe(node),
            shape,
            material,
            world_from_object: place.0,
            world_from_object_end: place.1,
        });
    }

    /// The material of `node`; for an object light, a copy of it emitting `<Radiance>`.
    fn material_of(&mut self, node: Node, light: bool) -> Result<u32, SceneError> {
        let material = self.material(node)?;
        if !light {
            return Ok(material);
        }
        let x = self.x;
        let radiance_node = x.required(node, "Radiance")?;
        let radiance = x.color(radiance_node)?;
        let mut emissive = self.material_desc(material).clone();
        emissive.emission = radiance;
        emissive.name = format!("{} emitting ({})", emissive.name, describe(node));
        Ok(self.add_material(emissive))
    }

    fn mesh(&mut self, node: Node, light: bool) -> Result<(), SceneError> {
        let x = self.x;
        let allowed: &[&str] = if light {
            &["Material", "Faces", "Radiance", "Transformations", "MotionBlur", "Textures"]
        } else {
            &["Material", "Faces", "Transformations", "MotionBlur", "Textures"]
        };
        x.check_children(node, allowed)?;
        let id = node.attribute("id").map(str::trim).unwrap_or("").to_owned();
        let smooth = match node.attribute("shadingMode").map(str::trim) {
            None | Some("flat") => false,
            Some("smooth") => true,
            Some(other) => {
                return Err(x.error(
                    node,
                    format!("unsupported shadingMode \"{other}\" (supported: smooth, flat)"),
                ));
            }
        };
        let material = self.material_of(node, light)?;
        let faces = x.required(node, "Faces")?;
        let (mesh, no_uvs) = match faces.attribute("plyFile") {
            Some(file) => {
                // What is given beside a plyFile would be ignored without a word.
                let inline =
                    ["vertexOffset", "textureOffset"].into_iter().find(|a| faces.has_attribute(*a));
                if let Some(attribute) = inline {
                    return Err(x.error(
                        faces,
                        format!(
                            "{attribute} is given with a plyFile, whose mesh has its own indices"
                        ),
                    ));
                }
                if let Some((_, pos)) = tokens(faces).next() {
                    let problem = "vertex indices are given with a plyFile, whose mesh has its own";
                    return Err(x.token_error(faces, pos, problem));
                }
                let mesh_ref = ObjRef {
                    obj: self.refs.base_dir.join(file.trim()),
                    scene: x.file,
                    item: describe(node),
                    line: x.line(faces),
                    read_mtl: true,
                };
                let (_, models) = self.cache.models(&mesh_ref, Some(smooth), self.warnings)?;
                let mut models = models.into_iter();
                match (models.next(), models.next()) {
                    (Some(model), None) => {
                        let why = format!("{} gives none", file.trim());
                        let no_uvs = model.mesh.uvs.is_none().then_some(why);
                        (model.mesh, no_uvs)
                    }
                    _ => return Err(x.error(faces, "the mesh file must hold exactly one mesh")),
                }
            }
            None => {
                let offset = |name: &str| match faces.attribute(name) {
                    Some(text) => text.trim().parse::<i64>().map_err(|_| {
                        x.error(faces, format!("{name} \"{text}\" is not a whole number"))
                    }),
                    None => Ok(0),
                };
                let offsets = (offset("vertexOffset")?, offset("textureOffset")?);
                let data = (self.refs.vertices, self.refs.texcoords);
                let InlineMesh { mesh, no_uvs } = inline_mesh(x, data, faces, offsets, smooth)?;
                (Arc::new(mesh), no_uvs)
            }
        };
        self.require_uvs(node, material, no_uvs.as_deref())?;
        let place = self.placement(node, DAffine3::IDENTITY)?;
        // Light meshes number their ids apart from meshes, and no MeshInstance names them.
        if !id.is_empty() && !light {
            let mesh = Arc::clone(&mesh);
            let base = BaseMesh { mesh, no_uvs, world_from_object: place.0, material };
            if self.meshes.insert(id.clone(), base).is_some() {
                return Err(x.error(node, format!("mesh id \"{id}\" is defined twice")));
            }
        }
        self.push(node, ShapeDesc::Mesh(mesh), material, place);
        Ok(())
    }

    fn triangle(&mut self, node: Node) -> Result<(), SceneError> {
        let x = self.x;
        x.check_children(
            node,
            &["Material", "Indices", "Transformations", "MotionBlur", "Textures"],
        )?;
        let material = self.material(node)?;
        let indices = x.required(node, "Indices")?;
        if tokens(indices).count() != 3 {
            return Err(x.error(indices, "a triangle takes exactly 3 vertex indices"));
        }
        let data = (self.refs.vertices, self.refs.texcoords);
        let InlineMesh { mesh, no_uvs } = inline_mesh(x, data, indices, (0, 0), false)?;
        self.require_uvs(node, material, no_uvs.as_deref())?;
        let place = self.placement(node, DAffine3::IDENTITY)?;
        self.push(node, ShapeDesc::Mesh(Arc::new(mesh)), material, place);
        Ok(())
    }

    fn sphere(&mut self, node: Node, light: bool) -> Result<(), SceneError> {
        let x = self.x;
        let allowed: &[&str] = if light {
            &[
                "Material",
                "Center",
                "Radius",
                "Radiance",
                "Transformations",
                "MotionBlur",
                "Textures",
            ]
        } else {
            &["Material", "Center", "Radius", "Transformations", "MotionBlur", "Textures"]
        };
        x.check_children(node, allowed)?;
        let material = self.material_of(node, light)?;
        let center_node = x.required(node, "Center")?;
        let mut all = tokens(center_node);
        let (Some((token, pos)), None) = (all.next(), all.next()) else {
            return Err(x.error(center_node, "expected one vertex index"));
        };
        let center =
            self.refs.vertices[vertex_index(x, self.refs.vertices, center_node, token, pos, 0)?];
        let radius_node = x.required(node, "Radius")?;
        let radius = x.scalar(radius_node)?;
        if !(radius > 0.0) {
            return Err(x.out_of_range(radius_node, radius, "> 0"));
        }
        let place = self.placement(node, DAffine3::IDENTITY)?;
        self.push(node, ShapeDesc::Sphere { center, radius }, material, place);
        Ok(())
    }

    fn instance(&mut self, node: Node) -> Result<(), SceneError> {
        let x = self.x;
        x.check_children(node, &["Material", "Transformations", "MotionBlur", "Textures"])?;
        let base_id = node
            .attribute("baseMeshId")
            .map(str::trim)
            .ok_or_else(|| x.error(node, "the instance has no baseMeshId attribute"))?;
        let Some(base) = self.meshes.get(base_id) else {
            let defined = id_list(self.meshes.keys());
            return Err(x.error(
                node,
                format!("baseMeshId \"{base_id}\" is not a mesh id; meshes: {defined}"),
            ));
        };
        let reset = x.flag(node, "resetTransform")?;
        let (mesh, base_transform, base_material) =
            (Arc::clone(&base.mesh), base.world_from_object, base.material);
        let no_uvs = base.no_uvs.as_ref().map(|why| format!("its base mesh's {why}"));
        let material = match x.child(node, "Material")? {
            Some(m) => self.refs.materials.lookup(x, m)?,
            None => base_material,
        };
        let material = self.with_textures(node, material)?;
        self.require_uvs(node, material, no_uvs.as_deref())?;
        let base = if reset { DAffine3::IDENTITY } else { base_transform };
        let place = self.placement(node, base)?;
        self.push(node, ShapeDesc::Mesh(mesh), material, place);
        Ok(())
    }
}
