//! Emitters that can light nothing: a one-sided flat light with every other object behind
//! its plane renders nothing it could light (a quad emits only along u × v), and the
//! image comes out dark with no error. Found before rendering, from bounds alone.

use crate::render_scene::{RenderScene, transformed_bounds};
use glam::Vec3;

/// An axis-aligned box as (min, max).
type Bounds = (Vec3, Vec3);

/// A sentence per emissive object whose every emitting face turns away from the bounds of
/// all other objects. Conservative: bounds are larger than what they hold, so an object
/// named here certainly lights nothing; scenes with moving objects are not judged.
pub fn emitters_facing_away(scene: &RenderScene) -> Vec<String> {
    let one_sided = scene.lights.emitters.iter().any(|e| !e.two_sided);
    if !one_sided || scene.instances.iter().any(|i| i.placement.is_moving()) {
        return Vec::new();
    }
    // Each prototype's bounds once (a mesh instanced a thousand times is read once), then
    // each instance's, and the union of all but one from prefix and suffix unions.
    let prototype_bounds: Vec<Bounds> =
        scene.prototypes.iter().map(|p| p.geometry.bounds()).collect();
    let bounds: Vec<Bounds> = scene
        .instances
        .iter()
        .map(|instance| {
            let (lo, hi) = prototype_bounds[instance.prototype as usize];
            match instance.placement.render_from_object(0.0) {
                Some(m) => transformed_bounds(&m, lo, hi),
                None => (lo, hi),
            }
        })
        .collect();
    let union = |a: Bounds, b: &Bounds| (a.0.min(b.0), a.1.max(b.1));
    let empty = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    let before: Vec<Bounds> = bounds
        .iter()
        .scan(empty, |acc, b| {
            let previous = *acc;
            *acc = union(*acc, b);
            Some(previous)
        })
        .collect();
    let mut after = vec![empty; bounds.len()];
    for i in (0..bounds.len().saturating_sub(1)).rev() {
        after[i] = union(after[i + 1], &bounds[i + 1]);
    }
    let mut warnings = Vec::new();
    let emitters = &scene.lights.emitters;
    let mut start = 0;
    while start < emitters.len() {
        let geom_id = emitters[start].geom_id;
        let end = start + emitters[start..].iter().take_while(|e| e.geom_id == geom_id).count();
        let group = &emitters[start..end];
        start = end;
        let Some(instance) = scene.instances.get(geom_id as usize) else { continue };
        if group.iter().any(|e| e.two_sided) {
            continue;
        }
        let (lo, hi) = union(before[geom_id as usize], &after[geom_id as usize]);
        if !(lo.cmple(hi).all()) {
            continue; // nothing else in the scene
        }
        let corners = (0..8).map(|k| {
            let pick =
                |bit: usize, axis: usize| if k >> bit & 1 == 0 { lo[axis] } else { hi[axis] };
            Vec3::new(pick(0, 0), pick(1, 1), pick(2, 2))
        });
        let corners: Vec<Vec3> = corners.collect();
        if !group.iter().any(|e| corners.iter().any(|&c| e.shape.faces(c))) {
            warnings.push(format!(
                "{} emits only on its front side, and every other object is behind it: it \
                 lights nothing (flip it: swap u and v of a quad, or set two_sided = true)",
                instance.name
            ));
        }
    }
    warnings
}
