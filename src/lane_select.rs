//! Selects for code that runs over many lanes at once (the Lambertian lanes, the lone
//! emitter's area samples): an `if` over two values already computed, written so that a
//! loop over lanes compiles to a blend rather than a branch.

use glam::Vec3;

/// `a` where `condition`, else `b`.
#[inline(always)]
pub fn select(condition: bool, a: f32, b: f32) -> f32 {
    if condition { a } else { b }
}

/// `a` where `condition`, else `b`, component by component.
#[inline(always)]
pub fn select3(condition: bool, a: Vec3, b: Vec3) -> Vec3 {
    Vec3::new(select(condition, a.x, b.x), select(condition, a.y, b.y), select(condition, a.z, b.z))
}
