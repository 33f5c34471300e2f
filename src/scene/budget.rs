//! A scene against the limits (`crate::limits`), before a render allocates anything: the
//! coordinate range and the memory the render will need against the memory the machine has.

use crate::limits::{
    BASE_BYTES, BYTES_PER_ATTRIBUTE_VALUE, BYTES_PER_EMITTER, BYTES_PER_GRID_VALUE,
    BYTES_PER_GRID_VOXEL, BYTES_PER_HDR_TEXEL, BYTES_PER_LIGHT, BYTES_PER_MATERIAL,
    BYTES_PER_OBJECT, BYTES_PER_PIXEL, BYTES_PER_SAMPLED_TEXEL, BYTES_PER_TEXEL, BYTES_PER_THREAD,
    BYTES_PER_VERTEX, BYTES_PER_VERTEX_NORMAL, BYTES_PER_VERTEX_UV, MAX_COORDINATE,
    MAX_WORLD_COORDINATE, memory_available,
};
use crate::render_space::RenderSpace;
use crate::scene::{ObjectDesc, SceneDesc, ShapeDesc};
use crate::texels::TextureImage;
use glam::DVec3;
use std::collections::HashSet;
use std::sync::Arc;

#[derive(Debug, thiserror::Error)]
pub enum LimitError {
    #[error(
        "{}: rendering it needs about {} of memory ({}), but only {} are \
         available; lower camera.resolution (or the CENG795 ImageResolution), the number of \
         objects and repeat copies, the size of the textures or signed distance grids, or \
         --threads",
        .file.display(), size(.estimate.bytes), .estimate, size(*.available)
    )]
    /// (The estimate boxed: every render error would otherwise carry its size.)
    Memory { file: std::path::PathBuf, estimate: Box<MemoryEstimate>, available: u64 },
    #[error(
        "{}: {what} reaches the coordinate {value:e}, beyond the supported range ±{limit:e} \
         ({frame}, after --offset); {advice}",
        .file.display()
    )]
    Coordinate {
        file: std::path::PathBuf,
        what: String,
        value: f64,
        limit: f64,
        frame: &'static str,
        advice: &'static str,
    },
}

/// A memory size in GiB, in MiB below one GiB, in KiB below 0.1 MiB and in bytes below
/// 0.1 KiB (a budget of a few bytes read as "0.0 MiB" on both sides of a refusal).
pub fn size(bytes: u64) -> String {
    let unit = |shift: u32| bytes as f64 / (1u64 << shift) as f64;
    match bytes {
        _ if bytes >= 1 << 30 => format!("{:.1} GiB", unit(30)),
        _ if unit(20) >= 0.1 => format!("{:.1} MiB", unit(20)),
        _ if unit(10) >= 0.1 => format!("{:.1} KiB", unit(10)),
        1 => "1 byte".to_owned(),
        _ => format!("{bytes} bytes"),
    }
}

/// The memory a render needs, in bytes, and the counts it is estimated from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemoryEstimate {
    pub bytes: u64,
    pub width: u32,
    pub height: u32,
    pub pixels: u64,
    pub objects: u64,
    pub materials: u64,
    pub lights: u64,
    pub triangles: u64,
    /// Values of meshes' attributes (PLY vertex and face properties), each f32.
    pub attribute_values: u64,
    /// Emitting primitives, counted once a placement (each samples its own).
    pub emitters: u64,
    /// Values of signed distance grids, and their voxels (each counted as a primitive).
    pub grid_values: u64,
    pub grid_voxels: u64,
    pub texels: u64,
    /// Of those, texels of EXR images (dearer to load).
    pub hdr_texels: u64,
    /// Texels of images that also get a sampling table (environment maps).
    pub sampled_texels: u64,
    /// Worker threads.
    pub threads: u64,
}

impl std::fmt::Display for MemoryEstimate {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}x{} pixels, {} object placements, {} materials, {} lights, {} mesh triangles, \
             {}{} emitting primitives, {} grid values, {} texture texels, {} thread{}",
            self.width,
            self.height,
            self.objects,
            self.materials,
            self.lights,
            self.triangles,
            match self.attribute_values {
                0 => String::new(),
                n => format!("{n} mesh attribute values, "),
            },
            self.emitters,
            self.grid_values,
            self.texels,
            self.threads,
            if self.threads == 1 { "" } else { "s" }
        )
    }
}

/// The memory a render of `desc` needs on a backend whose BVH and build take
/// `bytes_per_triangle` (`BackendKind::bytes_per_triangle`) with `threads` workers: the
/// counts of what the render holds, each at its measured cost (`crate::limits`). Shared
/// meshes and images count once.
pub fn memory_needed(desc: &SceneDesc, bytes_per_triangle: u64, threads: usize) -> MemoryEstimate {
    let pixels = u64::from(desc.camera.width) * u64::from(desc.camera.height);
    let mut meshes = HashSet::new();
    let mut grids = HashSet::new();
    let (mut triangles, mut grid_values, mut grid_voxels) = (0u64, 0u64, 0u64);
    let mut attribute_values = 0u64;
    let mut vertex_bytes = 0u64;
    let mut emitters = 0u64;
    for object in &desc.objects {
        // Each placement of an emissive shape samples its own emitters, shared mesh or not.
        let emissive = desc
            .materials
            .get(object.material as usize)
            .is_some_and(|m| m.emission.max_element() > 0.0);
        if emissive {
            emitters += match &object.shape {
                ShapeDesc::Mesh(mesh) => mesh.indices.len() as u64,
                _ => 1,
            };
        }
        if let ShapeDesc::Mesh(mesh) = &object.shape {
            if meshes.insert(Arc::as_ptr(mesh)) {
                triangles += mesh.indices.len() as u64;
                vertex_bytes = vertex_bytes.saturating_add(vertices_beyond_triangles(mesh));
                attribute_values +=
                    mesh.attributes.iter().map(|a| a.values.len() as u64).sum::<u64>();
            }
        }
        // Counted here, before placement builds a grid's voxels: its values, and each voxel
        // that will be a primitive (its corner and box, and a triangle's share of the BVH).
        if let ShapeDesc::SdfGrid(grid) = &object.shape {
            if grids.insert(Arc::as_ptr(grid)) {
                grid_values += grid.values.len() as u64;
                grid_voxels += grid.surface_voxels();
            }
        }
    }
    let mut images = HashSet::new();
    let (mut texels, mut hdr_texels, mut sampled_texels) = (0u64, 0u64, 0u64);
    let mut count = |image: &Arc<TextureImage>, sampled: bool| {
        let n = u64::from(image.width) * u64::from(image.height);
        if images.insert(Arc::as_ptr(image)) {
            texels += n;
            hdr_texels += if image.hdr { n } else { 0 };
        }
        if sampled {
            sampled_texels += n;
        }
    };
    desc.materials.iter().flat_map(|m| m.images()).for_each(|i| count(i, false));
    let background = desc.settings.background_texture.as_ref().and_then(|t| t.image());
    background.into_iter().for_each(|i| count(i, false));
    desc.lights.iter().filter_map(|l| l.image()).for_each(|(i, sampled)| count(i, sampled));
    let objects = desc.objects.len() as u64;
    let materials = desc.materials.len() as u64;
    let lights = desc.lights.len() as u64;
    // A render has one thread at least.
    let threads = threads.max(1) as u64;
    // Saturating: counts from a file may be absurd, and an estimate that wrapped would pass.
    let bytes = [
        (pixels, BYTES_PER_PIXEL),
        (objects, BYTES_PER_OBJECT),
        (materials, BYTES_PER_MATERIAL),
        (lights, BYTES_PER_LIGHT),
        (desc.reading_bytes, 1),
        (vertex_bytes, 1),
        (emitters, BYTES_PER_EMITTER),
        (triangles, bytes_per_triangle),
        (attribute_values, BYTES_PER_ATTRIBUTE_VALUE),
        (grid_values, BYTES_PER_GRID_VALUE),
        (grid_voxels, bytes_per_triangle.saturating_add(BYTES_PER_GRID_VOXEL)),
        (texels - hdr_texels, BYTES_PER_TEXEL),
        (hdr_texels, BYTES_PER_HDR_TEXEL),
        (sampled_texels, BYTES_PER_SAMPLED_TEXEL),
        (threads - 1, BYTES_PER_THREAD),
    ]
    .iter()
    .fold(BASE_BYTES, |sum, (count, each)| sum.saturating_add(count.saturating_mul(*each)));
    let (width, height) = (desc.camera.width, desc.camera.height);
    MemoryEstimate {
        bytes,
        width,
        height,
        pixels,
        objects,
        materials,
        lights,
        triangles,
        attribute_values,
        emitters,
        grid_values,
        grid_voxels,
        texels,
        hdr_texels,
        sampled_texels,
        threads,
    }
}

/// The bytes of `mesh`'s vertices that its triangles' cost (`BYTES_PER_TRIANGLE_*`, measured
/// on closed meshes, which have half as many vertices as triangles) does not cover: its
/// positions beyond half its triangles (a soup has three a triangle), its normals and its
/// texture coordinates, each in the description and its render-space copy.
fn vertices_beyond_triangles(mesh: &crate::scene::MeshData) -> u64 {
    let vertices = mesh.positions.len() as u64;
    let beyond = vertices.saturating_sub(mesh.indices.len() as u64 / 2);
    let normals = if mesh.normals.is_some() { vertices } else { 0 };
    let uvs = if mesh.uvs.is_some() { vertices } else { 0 };
    beyond * BYTES_PER_VERTEX + normals * BYTES_PER_VERTEX_NORMAL + uvs * BYTES_PER_VERTEX_UV
}

/// Refuses a render whose estimated memory exceeds what the machine has.
pub fn check_memory(
    desc: &SceneDesc,
    bytes_per_triangle: u64,
    threads: usize,
) -> Result<(), LimitError> {
    let estimate = memory_needed(desc, bytes_per_triangle, threads);
    match memory_available() {
        Some(available) if estimate.bytes > available => {
            let estimate = Box::new(estimate);
            Err(LimitError::Memory { file: desc.source.clone(), estimate, available })
        }
        _ => Ok(()),
    }
}

/// Object-space bounds of the meshes seen so far, by `Arc` identity (the scene holds the
/// `Arc`s, so an address is not reused while the map lives).
#[derive(Default)]
pub struct MeshBounds(std::collections::HashMap<*const crate::scene::MeshData, (DVec3, DVec3)>);

/// The largest world-space coordinate `object` reaches: its bounds' corners at both
/// shutter ends (NaN or inf if they overflow).
/// `bounds` keeps each shared mesh's object-space bounds, so a mesh placed a million times
/// is scanned once.
pub fn object_reach(object: &ObjectDesc, bounds: &mut MeshBounds) -> f64 {
    object_reach_from(object, bounds, DVec3::ZERO)
}

/// As [`object_reach`], measured from `origin` (the render-space origin).
pub fn object_reach_from(object: &ObjectDesc, bounds: &mut MeshBounds, origin: DVec3) -> f64 {
    let mut reach = 0.0f64;
    for (lo, hi) in world_bounds(object, bounds) {
        let far = (lo - origin).abs().max_element().max((hi - origin).abs().max_element());
        if !(far <= reach) || lo.is_nan() || hi.is_nan() {
            reach = if far.is_nan() || lo.is_nan() || hi.is_nan() { f64::NAN } else { far };
        }
    }
    reach
}

/// `object`'s world-space bounding box at each shutter end (NaN if a corner is NaN).
fn world_bounds(object: &ObjectDesc, bounds: &mut MeshBounds) -> Vec<(DVec3, DVec3)> {
    let (lo, hi) = match &object.shape {
        ShapeDesc::Sphere { center, radius } => (*center - *radius, *center + *radius),
        ShapeDesc::SdfGrid(_) => (DVec3::ZERO, DVec3::ONE),
        ShapeDesc::Mesh(mesh) => {
            *bounds.0.entry(std::sync::Arc::as_ptr(mesh)).or_insert_with(|| {
                mesh.positions.iter().fold(
                    (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
                    |(lo, hi), p| (lo.min(*p), hi.max(*p)),
                )
            })
        }
    };
    let placements = std::iter::once(object.world_from_object).chain(object.world_from_object_end);
    placements
        .map(|placement| {
            let mut box_lo = DVec3::splat(f64::INFINITY);
            let mut box_hi = DVec3::splat(f64::NEG_INFINITY);
            for corner in 0..8 {
                let pick = |bit: usize, lo: f64, hi: f64| if corner & bit != 0 { hi } else { lo };
                let local =
                    DVec3::new(pick(1, lo.x, hi.x), pick(2, lo.y, hi.y), pick(4, lo.z, hi.z));
                let world = placement.transform_point3(local);
                if world.is_nan() {
                    return (DVec3::NAN, DVec3::NAN);
                }
                (box_lo, box_hi) = (box_lo.min(world), box_hi.max(world));
            }
            (box_lo, box_hi)
        })
        .collect()
}

/// Refuses a scene (already moved by any offset) that reaches beyond `MAX_WORLD_COORDINATE`
/// in world space, or beyond `MAX_COORDINATE` from the origin of `space`: the camera, the
/// lights, and each object's bounds at both shutter ends.
pub fn check_coordinates(desc: &SceneDesc, space: RenderSpace) -> Result<(), LimitError> {
    let render_origin = match space {
        RenderSpace::World => DVec3::ZERO,
        RenderSpace::Cameraworld | RenderSpace::Camera => desc.camera.lookfrom,
    };
    let frames = [
        (DVec3::ZERO, MAX_WORLD_COORDINATE, "world space", "move the scene nearer the origin"),
        (render_origin, MAX_COORDINATE, space.frame(), space.advice()),
    ];
    for (origin, limit, frame, advice) in frames {
        let refuse = |what: String, value: f64| LimitError::Coordinate {
            file: desc.source.clone(),
            what,
            value,
            limit,
            frame,
            advice,
        };
        let far = |p: DVec3| if p.is_nan() { f64::NAN } else { (p - origin).abs().max_element() };
        for (what, p) in
            [("camera.lookfrom", desc.camera.lookfrom), ("camera.lookat", desc.camera.lookat)]
        {
            if !(far(p) <= limit) {
                return Err(refuse(what.to_owned(), far(p)));
            }
        }
        for (i, light) in desc.lights.iter().enumerate() {
            let reach = light.reach(origin);
            if !(reach <= limit) {
                return Err(refuse(format!("lights[{i}]"), reach));
            }
        }
        let mut bounds = MeshBounds::default();
        for object in &desc.objects {
            let reach = object_reach_from(object, &mut bounds, origin);
            if !(reach <= limit) {
                return Err(refuse(object.name.clone(), reach));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_keep_a_digit_that_is_not_zero() {
        let sizes = [1, 44, 103, 45_000, 104_858, 1000 << 20, 3 << 30].map(size);
        let expected =
            ["1 byte", "44 bytes", "0.1 KiB", "43.9 KiB", "0.1 MiB", "1000.0 MiB", "3.0 GiB"];
        assert_eq!(sizes, expected);
    }

    #[test]
    fn the_bundled_scene_fits_and_far_scenes_do_not() {
        let mut scene = crate::scene::load(&crate::bundled::default_scene()).unwrap();
        for space in [RenderSpace::World, RenderSpace::Cameraworld, RenderSpace::Camera] {
            check_coordinates(&scene, space).unwrap();
        }
        check_memory(&scene, crate::limits::BYTES_PER_TRIANGLE_OBVHS, 2).unwrap();
        scene.translate(DVec3::new(1e9, 0.0, 0.0));
        // Far out, the camera-relative spaces still hold it; f32 world space cannot.
        check_coordinates(&scene, RenderSpace::Cameraworld).unwrap();
        check_coordinates(&scene, RenderSpace::Camera).unwrap();
        let err = check_coordinates(&scene, RenderSpace::World).unwrap_err().to_string();
        assert!(err.contains("cornell.toml") && err.contains("±1e8 (world render space"), "{err}");
        // Past 1e12 not even f64 world space keeps the scene's detail.
        scene.translate(DVec3::new(2e12, 0.0, 0.0));
        let err = check_coordinates(&scene, RenderSpace::Cameraworld).unwrap_err().to_string();
        assert!(err.contains("±1e12 (world space"), "{err}");
    }

    #[test]
    fn the_largest_resolution_needs_more_than_this_machine_has() {
        let mut scene = crate::scene::load(&crate::bundled::default_scene()).unwrap();
        (scene.camera.width, scene.camera.height) = (16384, 16384);
        let needed = memory_needed(&scene, crate::limits::BYTES_PER_TRIANGLE_EMBREE, 2).bytes;
        assert!(needed > 24 << 30, "{needed}");
    }

    #[test]
    fn each_thread_past_the_first_adds_its_cost() {
        let scene = crate::scene::load(&crate::bundled::default_scene()).unwrap();
        let needed = |threads| memory_needed(&scene, 0, threads).bytes;
        assert_eq!(needed(0), needed(1), "the render has one thread at least");
        let all_but_one = (crate::limits::MAX_THREADS as u64 - 1) * crate::limits::BYTES_PER_THREAD;
        assert_eq!(needed(crate::limits::MAX_THREADS), needed(1) + all_but_one);
    }
}
