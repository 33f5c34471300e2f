//! What embray accepts, in one place (the README's "Limits" lists the same numbers), and
//! the memory the machine has. The checks of a scene against them are
//! `scene::budget`'s.

/// The largest image width or height, in every scene format and in part files.
pub const MAX_RESOLUTION: u32 = 16384;
/// Samples per pixel (a million samples of one pixel is a convergence test).
pub const MAX_SPP: u32 = 1 << 20;
/// Camera samples of one render, pixels × spp: 2³⁶ ≈ 6.9·10¹⁰, about ten hours at the
/// 2-core machine's two million samples per second (4096² at 4096 spp).
pub const MAX_SAMPLES: u64 = 1 << 36;
/// Shadow rays per shading point.
pub const MAX_LIGHT_SAMPLES: u32 = 65_536;
/// Bounces (path tracer) or recursion depth (Whitted); the Whitted integrator keeps its
/// pending rays on the heap, so this bounds time, not stack.
pub const MAX_DEPTH: u32 = 100_000;
/// Worker threads.
pub const MAX_THREADS: usize = 1024;
/// Materials in one blend, counting itself, the blends inside it and each material as
/// often as it is named (a chain of blends that each name one material twice doubles at
/// every link: 2⁶⁰ descriptions from 60 lines).
pub const MAX_BLEND_MATERIALS: usize = 64;
/// Elements of a Mitsuba scene, its `<include>`d files' included (one file's own bound is
/// the XML reader's: each `<include>` may splice in as many again).
pub const MAX_XML_ELEMENTS: usize = 4_000_000;
/// `<include>`s read for one Mitsuba scene (a file that includes the next four times, 16
/// deep, would read 4¹⁶).
pub const MAX_XML_INCLUDES: usize = 10_000;
/// Bytes of a Mitsuba scene's files read, an include counted each time it is read: the
/// input-file cap, for the whole scene.
pub const MAX_XML_BYTES: u64 = 2 << 30;
/// How deep a Mitsuba scene's elements may nest, through includes too: each level is a
/// call of the reader (and of the plugins that read it, and of dropping it), so a file of
/// 200,000 nested tags would overflow the stack. Mitsuba's own scenes nest fewer than 10.
pub const MAX_XML_NESTING: usize = 100;
/// How deep BSDFs may nest inside one another, through `<ref>`s too (a `<ref>` that leads
/// back to its own BSDF would never end).
pub const MAX_BSDF_NESTING: usize = 64;
/// Bytes of one attribute value after its `$name`s are replaced (defaults made of defaults
/// double at each).
pub const MAX_XML_VALUE: usize = 1 << 20;
/// Repetitions of a measurement (`bench --runs`).
pub const MAX_RUNS: u32 = 1000;
/// The largest coordinate a scene may reach in render space (f32): measured from the
/// render-space origin, which is the camera in `cameraworld` and `camera`, the world origin
/// in `world`. Also the largest half-extent of one object. Beyond it an f32 ulp exceeds 8
/// units: the geometry itself loses its shape faster than the spawn bounds assume.
pub const MAX_COORDINATE: f64 = 1e8;
/// The largest world-space coordinate (geometry, camera, lights, after `--offset`). World
/// space is f64 and only ever subtracted from: at 1e12 its ulp is 1.2e-4 units, so a scene
/// far out renders in `cameraworld` as it does at the origin.
pub const MAX_WORLD_COORDINATE: f64 = 1e12;
/// The smallest `f_number`: a lens faster than f/0.01 is an infinite aperture in all but name.
pub const MIN_F_NUMBER: f64 = 0.01;

// The memory model: a render's peak resident memory is BASE_BYTES plus a cost per pixel,
// object placement, mesh triangle and texture texel, each measured by
// `scripts/memory_model.py` (peak RSS of `embray render` as one count grows, both backends,
// path tracer and Whitted alike) and checked by `tests/memory_model.rs` (the estimate
// covers the measured peak and stays within 1.5 times it).

/// Bytes per pixel: the exact fixed-point sums of every pixel (colour, depth, normal,
/// albedo, squares for the variance), the film resolved from them, and the EXR channels and
/// PNG pixels while encoding (measured: 280, with every AOV written or none).
pub const BYTES_PER_PIXEL: u64 = 300;
/// Bytes per pixel that `--denoise` adds: Open Image Denoise's network activations at full
/// resolution, its copies of the colour, albedo and normal, and the denoised film (measured:
/// 477, peak RSS of the Cornell box at 1024² and 2048² with and without `--denoise`).
pub const DENOISE_BYTES_PER_PIXEL: u64 = 500;
/// Bytes every render holds whatever its size: the binary, the runtime, Embree's library
/// and the bundled scenes (measured: 10–14 MiB beyond the pixels; 24 leaves room for
/// another machine's Embree kernels).
pub const BASE_BYTES: u64 = 24 << 20;
/// Bytes per object placement: the scene description, its render-space instance and its
/// share of the top-level BVH (measured: 1047 on Embree, 957 on obvhs).
pub const BYTES_PER_OBJECT: u64 = 1100;
/// Bytes per emitting primitive of each placement (every triangle of an emissive mesh,
/// every emissive sphere, once per object: each placement samples its own): the light
/// sampler's `Emitter` and its index, and a textured one's map (`light::tests` holds the
/// types to it).
pub const BYTES_PER_EMITTER: u64 = 352;
/// Bytes per worker thread beyond the first: its stack as touched, its batch of paths and
/// their queues (`Wavefront`), and the thread pool's own. Measured as peak RSS over 1 to 256
/// threads: 296 KiB a thread on the Cornell box of `../shared/peers` (an area light, 256²,
/// a tile per thread), 150-200 KiB on `scripts/memory_model.py`'s floor under a point light
/// and 40-60 KiB for its Whitted renders; the largest, with a margin.
pub const BYTES_PER_THREAD: u64 = 320 << 10;
/// Bytes per mesh triangle on Embree: f64 positions and indices, the render-space copy,
/// Embree's BVH and its build (measured: 161).
pub const BYTES_PER_TRIANGLE_EMBREE: u64 = 175;
/// Bytes per mesh triangle on obvhs: as on Embree, with obvhs's BVH and the memory its
/// build holds at its peak (measured: 330).
pub const BYTES_PER_TRIANGLE_OBVHS: u64 = 345;
/// Bytes per texel of a PNG, JPEG or BMP image: the texels (12 bytes) and, while loading,
/// the image as decoded (measured: 18, 8-bit RGB noise).
pub const BYTES_PER_TEXEL: u64 = 20;
/// Bytes per texel of an EXR image: the texels and, while loading, its channels as
/// decoded (measured: 25 for a map with R, G, B, Z and normals, as embray writes them).
pub const BYTES_PER_HDR_TEXEL: u64 = 30;
/// Bytes per byte of an OBJ file while it is read, checked before it is read: its text, the
/// parser's (tobj's) arrays and the mesh made of them (measured, peak RSS of `embray info`:
/// 4.0 for a triangle soup with normals and texture coordinates, 3.4 for an indexed grid
/// with them, 2.9 for unreferenced vertices).
pub const BYTES_PER_OBJ_BYTE: u64 = 4;
/// Bytes per mesh vertex beyond half a mesh's triangles (which their cost covers): its f64
/// position and the render-space copy's f32 one.
pub const BYTES_PER_VERTEX: u64 = 36;
/// Bytes per vertex normal: f64 in the description, f32 in the render-space copy.
pub const BYTES_PER_VERTEX_NORMAL: u64 = 36;
/// Bytes per vertex texture coordinate: f32 in the description and in the render-space copy.
pub const BYTES_PER_VERTEX_UV: u64 = 16;
/// Bytes per value of a mesh attribute (a PLY's other vertex and face properties): the f32
/// of the scene's mesh and of its render-space copy.
pub const BYTES_PER_ATTRIBUTE_VALUE: u64 = 8;
/// Bytes per value of a signed distance grid: the f32 it is held as.
pub const BYTES_PER_GRID_VALUE: u64 = 4;
/// Bytes per voxel of a signed distance grid, beyond its share of the BVH (counted as a
/// triangle's, `BYTES_PER_TRIANGLE_*`): its corner (12) and box (24) if it is a primitive.
/// Counted from the types, not measured; every voxel is counted as a primitive, which
/// bounds a grid whose voxels are not yet built.
pub const BYTES_PER_GRID_VOXEL: u64 = 36;
/// Bytes per texel of an environment map's sampling table, beyond the texel itself
/// (measured: 22).
pub const BYTES_PER_SAMPLED_TEXEL: u64 = 24;

/// Bytes per byte of a TOML scene file while it is read, checked before it is parsed: the
/// parse's tokens and events, its syntax tree with spans (kept for the lines of messages)
/// and the copy serde reads into the file's structs (measured: 46–72 as allocated, and as
/// peak RSS of `embray info` 48 for files of many objects, 110 for a long array's unknown
/// field, whose message reads the text again).
pub const BYTES_PER_TOML_BYTE: u64 = 128;
/// Bytes per byte of a TOML scene's text that a render holds at its peak: the reading's
/// memory that the allocator keeps (measured: 16–35, peak RSS of renders of TOML files of
/// many materials, objects or lights, beside their other costs).
pub const BYTES_PER_TEXT_BYTE: u64 = 40;
/// Bytes per byte of an XML scene's files (Mitsuba's, its includes' and spectrum files',
/// CENG795's) while they are read and after: the document tree and what the reader makes
/// of it (measured: 20 for Mitsuba point emitters, 27 for unused BSDFs, 9 for CENG795
/// vertex data, 7.5 for a spectrum file; peak RSS of renders, beside their other costs).
pub const BYTES_PER_XML_BYTE: u64 = 32;
/// Bytes per material: its TOML table as read, its description and its compiled shading
/// (measured: 3.65 KB a material, peak RSS of renders of 50,000 to 200,000 materials, net
/// of their text's cost).
pub const BYTES_PER_MATERIAL: u64 = 4096;
/// Bytes per light of the scene's `lights` (a point, spot, directional or environment
/// light; an emissive shape's cost is its emitters'): its parameters with their fields and
/// lines as read, its description and what the light sampler holds for it (measured: 0.3
/// KB for TOML point lights, 0.2 KB for Mitsuba's, net of their text's cost; peak RSS of
/// renders of 8,000 to 200,000).
pub const BYTES_PER_LIGHT: u64 = 1024;

/// The memory this process may still use: the smallest of the kernel's MemAvailable, the
/// cgroup's limit (in a container), what `ulimit -v` leaves of the address space and
/// `EMBRAY_MAX_MEMORY` (bytes: a budget for a shared machine), or `None` when none is known.
/// (The estimates it is held against count resident memory; threads reserve more address
/// space than that, so under `ulimit -v` the check is a bound on the estimate only.)
pub fn memory_available() -> Option<u64> {
    // The command line refuses an unusable value before any work (`memory_budget`), so
    // it is never silently dropped there.
    let budget = memory_budget().ok().flatten();
    [memory_at_start(), budget].into_iter().flatten().min()
}

/// What the machine had for this process when it was first asked (`note_memory_at_start`,
/// at the start of `main`): the estimates count all a render holds, images and meshes
/// already read included, so they are held against what there was before any of it (asked
/// again after reading, the images would count twice, and a larger `ulimit -v` could
/// fail where a smaller one passed).
fn memory_at_start() -> Option<u64> {
    static AT_START: std::sync::OnceLock<Option<u64>> = std::sync::OnceLock::new();
    *AT_START.get_or_init(detected_memory)
}

/// Notes what memory the machine has now, before anything is read (`memory_available`).
pub fn note_memory_at_start() {
    memory_at_start();
}

/// An environment variable embray reads, set to a value it cannot use.
#[derive(Debug, thiserror::Error)]
#[error("the environment variable {name} is '{value}', but must be {expected}")]
pub struct EnvError {
    pub name: &'static str,
    pub value: String,
    pub expected: &'static str,
}

/// The environment variable `name`, trimmed; `None` when unset or empty (how a variable is
/// cleared in a job script).
pub(crate) fn env_text(name: &'static str) -> Option<String> {
    let value = std::env::var_os(name)?;
    let text = value.to_string_lossy().trim().to_owned();
    (!text.is_empty()).then_some(text)
}

/// `EMBRAY_MAX_MEMORY`, the budget of a shared machine in bytes, if set. A value such as
/// `1e9` or `8GiB` is an error rather than no budget: a cap that silently does nothing is
/// the one outcome its user did not ask for.
pub fn memory_budget() -> Result<Option<u64>, EnvError> {
    let name = "EMBRAY_MAX_MEMORY";
    let Some(text) = env_text(name) else { return Ok(None) };
    text.parse::<u64>().map(Some).map_err(|_| EnvError {
        name,
        value: crate::excerpt::excerpt(&text),
        expected: "a whole number of bytes (8 GiB is 8589934592)",
    })
}

fn detected_memory() -> Option<u64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok().and_then(|text| {
        let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
        let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
        Some(kib * 1024)
    });
    let cgroup = std::fs::read_to_string("/sys/fs/cgroup/memory.max")
        .ok()
        .and_then(|t| t.trim().parse::<u64>().ok());
    [meminfo, cgroup, address_space_left()].into_iter().flatten().min()
}

/// What `ulimit -v` (the soft RLIMIT_AS) leaves of the address space beyond what the
/// process maps already, if it sets one: past it an allocation fails, and Rust aborts.
fn address_space_left() -> Option<u64> {
    let limits = std::fs::read_to_string("/proc/self/limits").ok()?;
    let line = limits.lines().find(|l| l.starts_with("Max address space"))?;
    let limit: u64 =
        line.trim_start_matches("Max address space").split_whitespace().next()?.parse().ok()?;
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let size = status.lines().find(|l| l.starts_with("VmSize:"))?;
    let kib: u64 = size.split_whitespace().nth(1)?.parse().ok()?;
    Some(limit.saturating_sub(kib * 1024))
}
