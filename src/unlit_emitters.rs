//! Emitters that can light nothing: a one-sided flat light with every other object behind
//! its plane renders nothing it could light (a quad emits only along u × v), and the
//! image comes out dark with no error. Found before rendering, from bounds alone.

use crate::render_scene::{RenderScene, transformed_bounds};
use glam::Vec3;

/// A sentence per emissive object whose every emitting face turns away from the bounds of
/// all other objects. Conservative: bounds are larger than what they hold, so an object
/// named here certainly lights nothing; scenes with moving objects are not judged.
pub fn emitters_facing_away(scene: &RenderScene) -> Vec<String> {
    if scene.instances.iter().any(|i| i.placement.is_moving()) {
        return Vec::new();
    }
    let bounds: Vec<(Vec3, Vec3)> = scene
        .instances
        .iter()
        .map(|instance| {
            let (lo, hi) = scene.prototypes[instance.prototype as usize].geometry.bounds();
            match instance.placement.render_from_object(0.0) {
                Some(m) => transformed_bounds(&m, lo, hi),
                None => (lo, hi),
            }
        })
        .collect();
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
        let others = bounds
            .iter()
            .enumerate()
            .filter(|(id, _)| *id != geom_id as usize)
            .map(|(_, b)| *b)
            .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)));
        let Some((lo, hi)) = others else { continue };
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
