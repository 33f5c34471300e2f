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
//! maps attached. Texture coordinates are per vertex: `<TexCoordData>` entry `i +
//! textureOffset` for vertex index `i` of a `Faces` list.

use super::materials::Materials;
use super::textures::TextureMaps;
use super::transforms::Transforms;
use super::xml::{Xml, describe, id_list, tokens};
use crate::scene::desc::{MaterialDesc, MeshData, ObjectDesc, ShapeDesc};
use crate::scene::error::SceneError;
use crate::scene::formats::obj::ObjRef;
use crate::scene::mesh_file::{MeshCache, area_weighted_normals};
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

    /// The 0-based scene vertex of the 1-based `token` (plus `offset`) at `pos` in `node`.
    fn vertex_index(
        &self,
        node: Node,
        token: &str,
        pos: usize,
        offset: i64,
    ) -> Result<usize, SceneError> {
        let count = self.refs.vertices.len();
        let bad = |problem: String| self.x.token_error(node, pos, problem);
        let id: i64 = token
            .parse()
            .map_err(|_| bad(format!("vertex index '{token}' is not a whole number")))?;
        let index = id.saturating_add(offset);
        if index < 1 || index as u64 > count as u64 {
            let shown = if offset == 0 {
                format!("vertex index {id}")
            } else {
                format!("vertex index {id} + vertexOffset {offset} = {index}")
            };
            return Err(bad(format!(
                "{shown} is out of range: the scene has {count} vertices (indices 1 to {count})"
            )));
        }
        Ok(index as usize - 1)
    }

    /// A mesh of the listed scene vertices (triples of indices in `node`'s text), keeping
    /// only the vertices it uses.
    fn inline_mesh(
        &self,
        node: Node,
        offset: i64,
        texture_offset: i64,
        smooth: bool,
    ) -> Result<MeshData, SceneError> {
        let mut local: HashMap<usize, u32> = HashMap::new();
        let mut positions = Vec::new();
        let mut used = Vec::new();
        let mut corners = Vec::new();
        for (token, pos) in tokens(node) {
            let global = self.vertex_index(node, token, pos, offset)?;
            let index = *local.entry(global).or_insert_with(|| {
                positions.push(self.refs.vertices[global]);
                used.push(global);
                (positions.len() - 1) as u32
            });
            corners.push(index);
        }
        if corners.is_empty() {
            return Err(self.x.error(node, "the mesh has no faces"));
        }
        if corners.len() % 3 != 0 {
            return Err(self.x.error(
                node,
                format!("{} vertex indices is not a whole number of triangles", corners.len()),
            ));
        }
        let indices: Vec<[u32; 3]> = corners.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        // Vertex `g` (0-based, vertexOffset included) has the coordinates of entry
        // `g - vertexOffset + textureOffset`; a mesh any of whose vertices has none gets none.
        let texcoords = self.refs.texcoords;
        let uvs = used
            .iter()
            .map(|&g| {
                let i = (g as i64).checked_sub(offset)?.checked_add(texture_offset)?;
                usize::try_from(i).ok().and_then(|i| texcoords.get(i).copied())
            })
            .collect::<Option<Vec<Vec2>>>();
        let normals = smooth.then(|| area_weighted_normals(&positions, &indices));
        Ok(MeshData { positions, indices, normals, uvs, attributes: Vec::new() })
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
        let mesh = match faces.attribute("plyFile") {
            Some(file) => {
                let mesh_ref = ObjRef {
                    obj: self.refs.base_dir.join(file.trim()),
                    scene: x.file,
                    item: describe(node),
                    line: x.line(faces),
                };
                let (_, models) = self.cache.models(&mesh_ref, Some(smooth), self.warnings)?;
                let mut models = models.into_iter();
                match (models.next(), models.next()) {
                    (Some(model), None) => model.mesh,
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
                let (vertex_offset, texture_offset) =
                    (offset("vertexOffset")?, offset("textureOffset")?);
                Arc::new(self.inline_mesh(faces, vertex_offset, texture_offset, smooth)?)
            }
        };
        let place = self.placement(node, DAffine3::IDENTITY)?;
        // Light meshes number their ids apart from meshes, and no MeshInstance names them.
        if !id.is_empty() && !light {
            let base = BaseMesh { mesh: Arc::clone(&mesh), world_from_object: place.0, material };
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
        let mesh = self.inline_mesh(indices, 0, 0, false)?;
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
        let center = self.refs.vertices[self.vertex_index(center_node, token, pos, 0)?];
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
        let material = match x.child(node, "Material")? {
            Some(m) => self.refs.materials.lookup(x, m)?,
            None => base_material,
        };
        let material = self.with_textures(node, material)?;
        let base = if reset { DAffine3::IDENTITY } else { base_transform };
        let place = self.placement(node, base)?;
        self.push(node, ShapeDesc::Mesh(mesh), material, place);
        Ok(())
    }
}
