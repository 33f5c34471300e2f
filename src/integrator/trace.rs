//! What both integrators do with rays: closest hits and shadow rays against the scene's
//! backend, counted per ray kind; rays leave surfaces by the render's spawn mode.

use crate::accel::Accel;
use crate::ray::{Hit, Ray};
use crate::ray_columns::RayColumns;
use crate::render_scene::RenderScene;
use crate::scene::BumpScale;
use crate::shading::material::Material;
use crate::shading::normal_map::{
    bumped_normal, course_bumped_normal, mapped_normal, solid_bumped_normal, uv_derivatives,
};
use crate::shading::spawn::SpawnMode;
use crate::shading::surface::SurfaceInteraction;
use crate::shading::tex_coords::TexCoords;
use crate::shading::texture::Texture;
use crate::stats::RenderStats;
use glam::{Vec2, Vec3};

/// A scene, the backend built over it, and how rays leave surfaces.
pub(crate) struct SceneTracer<'a> {
    pub scene: &'a RenderScene,
    pub accel: &'a dyn Accel,
    pub spawn: SpawnMode,
    /// Whether camera hits record their albedo (`PathSample::albedo`).
    pub first_hit_albedo: bool,
}

impl SceneTracer<'_> {
    /// Traces a shadow ray and counts it; an invalid ray (which must never reach Embree)
    /// counts as blocked.
    pub fn occluded(&self, ray: &Ray, stats: &mut RenderStats) -> bool {
        if !ray.is_valid() {
            return true;
        }
        stats.shadow.rays += 1;
        let blocked = self.accel.occluded(ray, &mut stats.traversal);
        stats.shadow.hits += blocked as u64;
        blocked
    }

    /// `blocked[i]` becomes `occluded(&rays.ray(i), stats)` for valid rays (the caller
    /// leaves invalid ones out), traced as one batch (`Accel::occluded_columns`) and counted
    /// as `occluded` counts them.
    pub fn occluded_batch(&self, rays: &RayColumns, blocked: &mut [bool], stats: &mut RenderStats) {
        debug_assert!(rays.iter().all(|r| r.is_valid()), "invalid shadow rays are never traced");
        self.accel.occluded_columns(rays, blocked, &mut stats.traversal);
        stats.shadow.rays += rays.len() as u64;
        stats.shadow.hits += blocked.iter().filter(|&&b| b).count() as u64;
    }

    /// The closest hit of a valid `ray`, counted as a camera or an indirect ray.
    pub fn closest_hit(&self, ray: &Ray, camera_ray: bool, stats: &mut RenderStats) -> Option<Hit> {
        let hit = self.accel.intersect(ray, &mut stats.traversal);
        Self::count_closest_hits(std::slice::from_ref(&hit), camera_ray, stats);
        hit
    }

    /// Counts `hits`, the closest hits found for camera rays or for indirect rays: one
    /// (`closest_hit`'s) or a batch's.
    #[inline]
    pub fn count_closest_hits(hits: &[Option<Hit>], camera_rays: bool, stats: &mut RenderStats) {
        let counts = if camera_rays { &mut stats.camera } else { &mut stats.indirect };
        counts.rays += hits.len() as u64;
        counts.hits += hits.iter().filter(|hit| hit.is_some()).count() as u64;
    }

    /// Radiance arriving along a ray that leaves the scene in direction `dir`: the
    /// environment light's, or the background colour.
    pub fn escaped(&self, dir: Vec3) -> Vec3 {
        match &self.scene.lights.environment {
            Some(environment) => environment.radiance(dir),
            None => self.scene.background,
        }
    }

    /// The diffuse reflectance of `material` at `si` (its texture applied).
    pub fn surface_albedo(&self, material: &Material, si: &SurfaceInteraction, time: f32) -> Vec3 {
        match &material.texture {
            None => material.albedo,
            Some(texture) => {
                texture.apply_to_albedo(material.albedo, self.texture_color(texture, si, time))
            }
        }
    }

    /// The value of the hit mesh's attribute `name` at `si` (black on spheres and on meshes
    /// without it, as Mitsuba's lookup of a missing attribute gives 0).
    fn mesh_attribute(&self, name: &str, si: &SurfaceInteraction) -> Vec3 {
        let instance = &self.scene.instances[si.geom_id as usize];
        match &self.scene.prototypes[instance.prototype as usize].geometry {
            crate::render_scene::Geometry::Triangles(mesh) => {
                mesh.attribute(name, si.prim_id, si.barycentric).unwrap_or(Vec3::ZERO)
            }
            crate::render_scene::Geometry::Sphere(_)
            | crate::render_scene::Geometry::SdfGrid(_) => Vec3::ZERO,
        }
    }

    /// `texture`'s colour at `si` (solid patterns in the hit object's own space at `time`).
    pub fn texture_color(&self, texture: &Texture, si: &SurfaceInteraction, time: f32) -> Vec3 {
        if let Some((name, scale)) = texture.mesh_attribute() {
            return self.mesh_attribute(name, si) * scale;
        }
        let p_object = if texture.needs_object_point() {
            let placement = &self.scene.instances[si.geom_id as usize].placement;
            placement.texture_object_from_render(time).transform_point3(si.surface.point)
        } else {
            Vec3::ZERO
        };
        texture.eval(p_object, si.uv.get())
    }

    /// `si` with its shading normal replaced by `material`'s normal map, if it has one.
    #[inline]
    pub fn with_normal_map(
        &self,
        mut si: SurfaceInteraction,
        material: &Material,
        time: f32,
    ) -> SurfaceInteraction {
        self.map_normal(&mut si, material, time);
        si
    }

    /// Replaces the shading normal of `si` by `material`'s normal map, if it has one, in
    /// place. Inlined for the common case (no map: `si` untouched, not copied).
    #[inline]
    pub fn map_normal(&self, si: &mut SurfaceInteraction, material: &Material, time: f32) {
        if material.normal_map.is_some() || material.bump_map.is_some() {
            *si = self.apply_normal_map(*si, material, time);
        }
    }

    #[inline(never)]
    fn apply_normal_map(
        &self,
        si: SurfaceInteraction,
        material: &Material,
        time: f32,
    ) -> SurfaceInteraction {
        if let (None, Some((map, factor, _))) = (&material.normal_map, &material.bump_map) {
            if map.needs_object_point() {
                // A solid height field: its gradient in render space, through the chain
                // rule from the object point.
                let placement = &self.scene.instances[si.geom_id as usize].placement;
                let object_from_render = placement.texture_object_from_render(time);
                let p_object = object_from_render.transform_point3(si.surface.point);
                let in_object = glam::Vec3A::from(map.solid_gradient(p_object));
                let gradient = Vec3::from(object_from_render.matrix3.transpose() * in_object);
                // Heights rise along the outward normal, whichever side the ray is on.
                let side = if si.front_face { 1.0 } else { -1.0 };
                let outward = side * si.shading_normal;
                let bumped = side * solid_bumped_normal(*factor * gradient, outward);
                return Self::facing_the_ray(si, bumped);
            }
        }
        let Some(derivatives) = uv_derivatives(self.scene, &si, time) else { return si };
        let (dpdu, dpdv) = (derivatives.dpdu, derivatives.dpdv);
        let n = si.shading_normal;
        let mapped = match (&material.normal_map, &material.bump_map) {
            (Some(map), _) if material.bump_shadowing => {
                // Mitsuba's tangent frame: ∂p/∂u made orthogonal to the outward normal, and
                // that normal × it, whichever side the ray is on (built on the normal facing
                // the ray, the bitangent turned round and the map seen mirrored from behind).
                let side = if si.front_face { 1.0 } else { -1.0 };
                let outward = side * n;
                let tangent = (dpdu - outward.dot(dpdu) * outward).normalize_or_zero();
                let bitangent = outward.cross(tangent);
                let color = self.texture_color(map, &si, time);
                if material.is_dielectric() {
                    // From inside a glass: the normal it has from outside, reversed.
                    side * mapped_normal(color, outward, tangent, bitangent)
                } else {
                    // From behind a two-sided surface, which Mitsuba's `twosided` shades as
                    // its front seen in a mirror: the mapped normal mirrored in the surface.
                    mapped_normal(color, n, tangent, bitangent)
                }
            }
            (Some(map), _) => mapped_normal(self.texture_color(map, &si, time), n, dpdu, dpdv),
            (None, Some((map, factor, scale))) => {
                let height = |uv: Vec2| {
                    let at = SurfaceInteraction { uv: TexCoords::Known(uv), ..si };
                    self.texture_color(map, &at, time).element_sum() / 3.0
                };
                let step = map.uv_step();
                let uv = si.uv.get();
                let rise = || {
                    let h = height(uv);
                    let next = |offset| height(uv + offset) - h;
                    Vec2::new(next(Vec2::new(step.x, 0.0)), next(Vec2::new(0.0, step.y)))
                };
                match scale {
                    BumpScale::Scene => {
                        // Mitsuba's image slopes are exact in the cell the point is in; one
                        // texel's difference reaches into the next cell (a slope half a
                        // texel off, smoothed).
                        let mean = |slope: Vec3| slope.element_sum() / 3.0;
                        let slopes = match map.uv_slopes(uv) {
                            Some([along_u, along_v]) => Vec2::new(mean(along_u), mean(along_v)),
                            None => rise() / step,
                        };
                        // As Mitsuba: ∂p/∂u and ∂p/∂v in the shading normal's tangent plane
                        // first, so that a flat height field gives back the shading normal
                        // (a smooth mesh's interpolated one, not its triangle's).
                        let tangent = |d: Vec3| d - n.dot(d) * n;
                        bumped_normal(slopes * *factor, n, tangent(dpdu), tangent(dpdv), n)
                    }
                    // Texel differences in the image's 0–255 units.
                    BumpScale::CourseTexels => {
                        course_bumped_normal(rise() * map.value_scale() * *factor, n, &derivatives)
                    }
                }
            }
            (None, None) => return si,
        };
        Self::facing_the_ray(si, mapped)
    }

    /// `si` with the shading normal `mapped`, kept on the side the ray arrived from, as
    /// every shading normal is.
    fn facing_the_ray(mut si: SurfaceInteraction, mapped: Vec3) -> SurfaceInteraction {
        si.shading_normal = if mapped.dot(si.surface.normal) < 0.0 {
            (mapped - 2.0 * mapped.dot(si.surface.normal) * si.surface.normal).normalize()
        } else {
            mapped
        };
        si
    }
}
