//! The memory a benchmark's own scenes and ray arrays need, held against what the process
//! may use before they are made (`bench speed --large 4294967296` asked for 51 GB and
//! aborted; `bench queries --resolution 16384x16384` for 4.8 GB of rays).

use crate::limits::{BASE_BYTES, BYTES_PER_PIXEL, BYTES_PER_TRIANGLE_OBVHS, memory_available};
use crate::ray::Ray;
use crate::scene::SceneDesc;
use crate::scene::budget::{memory_needed, size};

/// Refuses `--large triangles`: the procedural scene of that many triangles
/// (`procedural::displaced_sphere_scene`, half a vertex a triangle) on either backend.
pub fn check_large(triangles: usize) -> Result<(), String> {
    let per_triangle = (triangles as u64).saturating_mul(BYTES_PER_TRIANGLE_OBVHS);
    check(&format!("--large {triangles}"), BASE_BYTES.saturating_add(per_triangle))
}

/// Refuses the query benchmark of `scene` (at its resolution) on either backend: a camera
/// ray and a bounce ray a pixel and the hits they are measured into, without the film's
/// cost, which it does not make.
pub fn check_queries(scene: &SceneDesc) -> Result<(), String> {
    let pixels = u64::from(scene.camera.width) * u64::from(scene.camera.height);
    let per_pixel = 2 * std::mem::size_of::<Ray>() as u64 + 32;
    let estimate = memory_needed(scene, BYTES_PER_TRIANGLE_OBVHS, 1).bytes;
    let needed =
        estimate.saturating_sub(pixels * BYTES_PER_PIXEL).saturating_add(pixels * per_pixel);
    let (width, height) = (scene.camera.width, scene.camera.height);
    check(&format!("the query benchmark at {width}x{height}"), needed)
}

/// Refuses `needed` bytes when the process may not use them; `what` names the option.
fn check(what: &str, needed: u64) -> Result<(), String> {
    match memory_available() {
        Some(available) if needed > available => Err(format!(
            "{what} needs about {} of memory, but only {} are available",
            size(needed),
            size(available)
        )),
        _ => Ok(()),
    }
}
