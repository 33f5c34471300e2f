//! `[[objects]]` → placed objects: quads, spheres, boxes, meshes (each OBJ model an
//! object), with motion and `repeat` grids.

use super::builder::{Builder, dvec, mesh_ref};
use super::repeat::{Grid, Placement};
use super::transform_list::fmt_vec;
use crate::scene::desc::{MaterialDesc, ObjectDesc, ShapeDesc};
use crate::scene::error::SceneError;
use crate::scene::formats::obj;
use crate::scene::formats::toml::format::{ObjectKind, ObjectToml, RepeatToml};
use crate::scene::formats::toml::source_map::FieldPath;
use crate::scene::shapes::{box_mesh, quad_mesh};
use glam::DVec3;
use std::sync::Arc;

/// The most copies one `repeat` may make (each costs about `limits::BYTES_PER_OBJECT`).
pub const MAX_REPEAT_COPIES: u64 = 1_000_000;

/// Copies of a `repeat` grid up to this many are named `... copy (i,j,k)`; those of larger
/// grids are all named `... copy`.
const NAMED_COPIES: usize = 1_000_000;

impl Builder<'_> {
    /// Validates `repeat`: counts >= 1, at most `MAX_REPEAT_COPIES` in all, and the farthest
    /// copy still at a finite position.
    pub(super) fn grid(
        &self,
        path: &FieldPath,
        repeat: Option<&RepeatToml>,
        placement: &Placement,
    ) -> Result<Option<Grid>, SceneError> {
        let Some(repeat) = repeat else { return Ok(None) };
        let count_path = path.key("repeat").key("count");
        for (i, &n) in repeat.count.iter().enumerate() {
            self.ctx.require(n >= 1, &count_path.index(i), n, ">= 1")?;
        }
        // u128: three u32 factors cannot wrap it (their product wrapped u64 past the limit).
        let total: u128 = repeat.count.iter().map(|&n| u128::from(n)).product();
        let [nx, ny, nz] = repeat.count;
        self.ctx.require(
            total <= u128::from(MAX_REPEAT_COPIES),
            &count_path,
            format!("{nx} × {ny} × {nz} = {total} copies"),
            &format!("at most {MAX_REPEAT_COPIES} copies"),
        )?;
        let grid = Grid { count: repeat.count, spacing: dvec(repeat.spacing) };
        let farthest = (DVec3::new(nx as f64, ny as f64, nz as f64) - 1.0) * grid.spacing;
        let far = placement.shifted(farthest);
        if !farthest.is_finite()
            || !far.start.translation.is_finite()
            || far.end.is_some_and(|end| !end.translation.is_finite())
        {
            let field = path.key("repeat").key("spacing");
            return Err(SceneError::Transform {
                file: self.ctx.file.to_path_buf(),
                field: field.to_string(),
                problem: format!(
                    "the farthest copy's position overflows (spacing {} × count {})",
                    fmt_vec(&repeat.spacing),
                    fmt_vec(&repeat.count.map(f64::from))
                ),
                line: self.ctx.line(&field),
            });
        }
        Ok(Some(grid))
    }

    /// Refuses a material that looks up a mesh attribute `shape` does not have.
    fn check_attributes(
        &self,
        path: &FieldPath,
        shape: &ShapeDesc,
        material: u32,
    ) -> Result<(), SceneError> {
        let attributes = match shape {
            ShapeDesc::Mesh(mesh) => &mesh.attributes[..],
            ShapeDesc::Sphere { .. } | ShapeDesc::SdfGrid(_) => &[],
        };
        let material = &self.materials[material as usize];
        let Some(missing) = material
            .mesh_attributes()
            .into_iter()
            .find(|n| !attributes.iter().any(|a| a.name == *n))
        else {
            return Ok(());
        };
        let has: Vec<&str> = attributes.iter().map(|a| a.name.as_str()).collect();
        let has = if has.is_empty() { "none".to_owned() } else { has.join(", ") };
        Err(self.ctx.out_of_range(
            &path.key("material"),
            format!("'{}' (it looks up the mesh attribute `{missing}`)", material.name),
            &format!("a material that looks up only attributes the shape has (it has: {has})"),
        ))
    }

    /// Refuses `models` objects times the copies of `grid` when, with the objects made so
    /// far, they would need more memory than the process may use: before they are made.
    fn check_copies(
        &self,
        path: &FieldPath,
        grid: Option<Grid>,
        models: usize,
    ) -> Result<(), SceneError> {
        let Some(grid) = grid else { return Ok(()) };
        let copies = (grid.total() as u64).saturating_mul(models as u64);
        let placements = (self.objects.len() as u64).saturating_add(copies);
        let field = path.key("repeat");
        let at = || format!("{field}{}", self.ctx.line(&field));
        crate::scene::reading_budget::check_placements(self.ctx.file, placements, at)
    }

    /// Adds the object, or one per copy of `grid`, all sharing `shape`.
    pub(super) fn push(
        &mut self,
        name: String,
        shape: ShapeDesc,
        material: u32,
        placement: Placement,
        grid: Option<Grid>,
    ) {
        let object = |name: String, shape: ShapeDesc, placement: Placement| ObjectDesc {
            name,
            shape,
            material,
            world_from_object: placement.start,
            world_from_object_end: placement.end,
        };
        match grid {
            None => self.objects.push(object(name, shape, placement)),
            Some(grid) => {
                self.objects.reserve(grid.total());
                // Formatting a name per copy costs more than the rest of the copy; beyond
                // `NAMED_COPIES` the copies share one name.
                let named = grid.total() <= NAMED_COPIES;
                let shared_name = format!("{name} copy");
                for ([i, j, k], offset) in grid.offsets() {
                    let name = if named {
                        format!("{name} copy ({i},{j},{k})")
                    } else {
                        shared_name.clone()
                    };
                    self.objects.push(object(name, shape.clone(), placement.shifted(offset)));
                }
            }
        }
    }

    pub(super) fn object(&mut self, i: usize, o: &ObjectToml) -> Result<(), SceneError> {
        let path = FieldPath::root("objects").index(i);
        const PLACED: [&str; 4] = ["type", "transform", "transform_end", "repeat"];
        let (kind, own): (&str, &[&str]) = match o.kind {
            ObjectKind::Quad => ("quad", &["material", "corner", "u", "v"]),
            ObjectKind::Sphere => ("sphere", &["material", "center", "radius"]),
            ObjectKind::Box => ("box", &["material", "min", "max"]),
            ObjectKind::Mesh => ("mesh", &["material", "file", "smooth"]),
        };
        let allowed: Vec<&str> = PLACED.iter().chain(own).copied().collect();
        let item = format!("{path} ({kind})");
        let present = [
            ("corner", o.corner.is_some()),
            ("u", o.u.is_some()),
            ("v", o.v.is_some()),
            ("center", o.center.is_some()),
            ("radius", o.radius.is_some()),
            ("min", o.min.is_some()),
            ("max", o.max.is_some()),
            ("file", o.file.is_some()),
            ("smooth", o.smooth.is_some()),
        ];
        let ctx = self.ctx;
        ctx.check_fields(&path, &item, &present, &allowed)?;
        let placement = self.placement(&path, o)?;
        let grid = self.grid(&path, o.repeat.as_ref(), &placement)?;
        let material = o
            .material
            .as_deref()
            .map(|name| self.lookup_material(&path.key("material"), name))
            .transpose()?;
        let shape = match o.kind {
            ObjectKind::Mesh => {
                let file = ctx.required(&path, &item, "file", o.file.as_deref())?;
                return self.mesh_objects(&path, file, o.smooth, material, placement, grid);
            }
            ObjectKind::Quad => {
                let corner = ctx.required(&path, &item, "corner", o.corner)?;
                let u = ctx.required(&path, &item, "u", o.u)?;
                let v = ctx.required(&path, &item, "v", o.v)?;
                let mesh = quad_mesh(dvec(corner), dvec(u), dvec(v))
                    .map_err(|p| self.degenerate(&path, &item, p))?;
                ShapeDesc::Mesh(Arc::new(mesh))
            }
            ObjectKind::Sphere => {
                // Any non-singular transform is allowed: the renderer instances a unit sphere
                // for ellipsoids.
                let center = ctx.required(&path, &item, "center", o.center)?;
                let radius = ctx.required(&path, &item, "radius", o.radius)?;
                let radius = ctx.positive_radius(&path.key("radius"), radius)?;
                ShapeDesc::Sphere { center: dvec(center), radius }
            }
            ObjectKind::Box => {
                let min = ctx.required(&path, &item, "min", o.min)?;
                let max = ctx.required(&path, &item, "max", o.max)?;
                let mesh =
                    box_mesh(dvec(min), dvec(max)).map_err(|p| self.degenerate(&path, &item, p))?;
                ShapeDesc::Mesh(Arc::new(mesh))
            }
        };
        let material = ctx.required(&path, &item, "material", material)?;
        self.check_attributes(&path, &shape, material)?;
        self.check_copies(&path, grid, 1)?;
        self.push(item, shape, material, placement, grid);
        Ok(())
    }

    /// One object per model of the mesh file (an OBJ file has one per material), times the
    /// copies of `grid`. `material` overrides the MTL materials.
    pub(super) fn mesh_objects(
        &mut self,
        path: &FieldPath,
        file: &str,
        smooth: Option<bool>,
        material: Option<u32>,
        placement: Placement,
        grid: Option<Grid>,
    ) -> Result<(), SceneError> {
        let mesh_ref = mesh_ref(self.ctx, self.base_dir, path, file);
        let (key, models) = self.meshes.models(&mesh_ref, smooth, self.warnings)?;
        self.check_copies(path, grid, models.len())?;
        let mut notes = obj::MtlNotes::default();
        for model in models {
            let index = match (material, model.material) {
                (Some(index), _) => index,
                (None, Some((m, mtl))) => match self.mtl_materials.get(&(key.clone(), m)) {
                    Some(&index) => index,
                    None => {
                        let desc = obj::material_desc(&mtl, &mesh_ref, &mut notes)?;
                        let name = format!("{file}: {}", mtl.name);
                        let index = self.add_material(MaterialDesc { name, ..desc });
                        self.mtl_materials.insert((key.clone(), m), index);
                        index
                    }
                },
                (None, None) => self.default_material(),
            };
            let name = match &model.name {
                Some(model_name) => format!("{path} ({file}: {model_name})"),
                None => format!("{path} ({file})"),
            };
            let shape = ShapeDesc::Mesh(model.mesh);
            self.check_attributes(path, &shape, index)?;
            self.push(name, shape, index, placement, grid);
        }
        notes.flush(self.warnings);
        Ok(())
    }
}
