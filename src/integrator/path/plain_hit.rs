//! The short way from a hit to its Lambertian lane, for the commonest surface: a triangle
//! mesh already in render space, whose material is plain Lambertian with a constant
//! reflectance and no emission or normal perturbation. Such a hit needs only its point, its
//! error bound, its plane's normal and (with vertex normals) its interpolated normal: not
//! the texture coordinates, the material's lookups or the general `SurfaceInteraction` that
//! `scatter` builds for every other hit. The lane it gives is the one `scatter` would give,
//! bit for bit (the same functions on the same numbers), which `tests/path_batching.rs`
//! checks against the reference paths, which never take this way.

use super::PathTracer;
use super::bounce::{PathState, Scattered};
use super::lambert::LaneSink;
use super::lane_light::{OnTriangle, TriangleHit};
use crate::ray::Hit;
use crate::render_scene::{Geometry, Placement, RenderScene, TriangleMesh};
use crate::sampling::SampleStream;
use crate::shading::bsdf::Energy;
use crate::shading::surface::{facing, interpolated_normal};
use crate::stats::RenderStats;
use glam::Vec3;

/// What a plain instance's hits need.
#[derive(Clone, Copy, Debug)]
pub(super) struct PlainSurface<'a> {
    mesh: &'a TriangleMesh,
    /// The reflectance after the energy model.
    diffuse: Vec3,
    /// Whether its back faces are black (then they take the general way).
    one_sided: bool,
}

/// The plain instances of a scene, by instance index (`Hit::geom_id`).
#[derive(Clone, Debug, Default)]
pub(super) struct PlainSurfaces<'a> {
    by_instance: Vec<Option<PlainSurface<'a>>>,
    /// Whether any is.
    any: bool,
}

impl<'a> PlainSurfaces<'a> {
    /// The plain instances of `scene` (see the module's comment).
    pub fn new(scene: &'a RenderScene, energy: Energy) -> Self {
        let plain = |instance: &crate::render_scene::Instance| {
            let material = scene.materials.get(instance.material as usize)?;
            let prototype = scene.prototypes.get(instance.prototype as usize)?;
            let mesh = match &prototype.geometry {
                Geometry::Triangles(mesh) => mesh,
                _ => return None,
            };
            let in_render_space = matches!(instance.placement, Placement::Baked { .. });
            let plain_material = material.is_plain_lambertian()
                && !material.is_emissive()
                && material.texture.is_none()
                && material.normal_map.is_none()
                && material.bump_map.is_none();
            (in_render_space && plain_material).then_some(PlainSurface {
                mesh,
                diffuse: energy.lambertian(material.albedo),
                one_sided: material.one_sided,
            })
        };
        let by_instance: Vec<_> = scene.instances.iter().map(plain).collect();
        let any = by_instance.iter().any(Option::is_some);
        PlainSurfaces { by_instance, any }
    }

    /// Whether any instance is plain.
    pub fn any(&self) -> bool {
        self.any
    }

    /// The plain surface instance `instance` has, if it is one.
    #[inline]
    pub fn get(&self, instance: u32) -> Option<&PlainSurface<'a>> {
        self.by_instance.get(instance as usize)?.as_ref()
    }
}

impl PathTracer<'_> {
    /// `scatter` for `hit` on the plain surface `plain`; `None` (nothing done) where it
    /// must take the general way: a one-sided material's back face.
    #[inline]
    pub(super) fn plain_hit(
        &self,
        state: &mut PathState,
        (hit, plain): (&Hit, &PlainSurface),
        stream: &mut SampleStream,
        stats: &mut RenderStats,
        lane: &mut impl LaneSink,
    ) -> Option<Scattered> {
        let (ray, mesh) = (&state.ray, plain.mesh);
        let tri = mesh.triangle(hit.prim_id);
        let plane = mesh.plane(hit.prim_id, &tri);
        // As `interaction` shades it.
        let interpolated = match &mesh.normals {
            Some(normals) => interpolated_normal(normals, mesh.indices[hit.prim_id as usize], hit),
            None => Vec3::ZERO,
        };
        let (front_face, normal, shading) =
            facing(plane.normal, interpolated, ray.dir, self.spaces.shading_sides);
        if plain.one_sided && !front_face {
            return None;
        }
        let at = TriangleHit::new(tri, &plane, ray.origin, hit);
        if state.depth == 0 {
            self.record_first_hit(&mut state.result, hit.t, shading);
        }
        if self.ends_at(state.depth) {
            return Some(Scattered::End);
        }
        stats.bounces.lanes += 1;
        let at = OnTriangle { hit: at, normal, front_face };
        self.lambert_lane(state, plain.diffuse, (at, shading), stream, lane);
        Some(Scattered::Lambert)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::{RenderOptions, prepare_scene};

    /// Only the constant, unlit Lambertian meshes in render space are plain; their
    /// reflectance is the energy model's.
    #[test]
    fn plain_surfaces_are_the_constant_lambertian_meshes() {
        let mut text = String::from(
            r#"
            [camera]
            lookfrom = [0.0, 1.0, -5.0]
            lookat = [0.0, 0.0, 0.0]
            vfov = 40.0
            resolution = [8, 8]
            [materials.plain]
            albedo = [0.9, 0.5, 0.25]
            [materials.checker]
            texture = { type = "checker2d", scale = 4.0, even = [0.8, 0.8, 0.8], odd = [0.1, 0.1, 0.1] }
            [materials.lamp]
            albedo = [0.5, 0.5, 0.5]
            emission = [4.0, 4.0, 4.0]
            [materials.glass]
            type = "dielectric"
            ior = 1.5
            [[objects]]
            type = "box"
            material = "plain"
            min = [-0.5, 0.0, -0.5]
            max = [0.5, 1.0, 0.5]
            transform = [{ rotate = { axis = [0.0, 1.0, 0.0], degrees = 30.0 } }]
            [[objects]]
            type = "sphere"
            material = "plain"
            center = [0.0, 5.0, 0.0]
            radius = 0.5
        "#,
        );
        for (y, material) in ["plain", "checker", "lamp", "glass"].iter().enumerate() {
            text += &format!(
                "[[objects]]\ntype = \"quad\"\nmaterial = \"{material}\"\n\
                 corner = [-1.0, {y}.0, -1.0]\nu = [0.0, 0.0, 2.0]\nv = [2.0, 0.0, 0.0]\n"
            );
        }
        let source = std::path::Path::new("plain.toml");
        let (desc, _) = crate::scene::load_str_with_warnings(&text, source).expect("scene parses");
        let scene = prepare_scene(&desc, &RenderOptions::for_scene(&desc)).expect("converts");
        assert_eq!(scene.instances.len(), 6, "one instance per object");
        for energy in [Energy::Conserving, Energy::Additive] {
            let plain = PlainSurfaces::new(&scene, energy);
            let found: Vec<bool> = (0..6).map(|i| plain.get(i).is_some()).collect();
            // The box, the sphere, then the plain, textured, emitting and glass quads.
            assert_eq!(found, [true, false, true, false, false, false], "{energy:?}");
            let diffuse = plain.get(0).map(|p| p.diffuse);
            assert_eq!(diffuse, Some(energy.lambertian(Vec3::new(0.9, 0.5, 0.25))));
            assert!(plain.get(6).is_none(), "past the last instance");
            assert!(plain.any());
        }
    }
}
