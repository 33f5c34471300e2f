//! What the integrator knows about a hit: the point with its error bound, normals facing the
//! incoming ray, material and texture coordinates. Computed from the backend's `Hit` the same
//! way for every backend.

use crate::float_error::{gamma, sphere_point, transform_point_with_error, triangle_hit_point};
use crate::ray::{Hit, Ray};
use crate::render_scene::{Geometry, Placement, RenderScene};
use crate::shading::spawn::SurfacePoint;
pub use crate::shading::tex_coords::TexCoords;
use glam::{Mat3, Vec2, Vec3};

#[derive(Clone, Copy, Debug)]
pub struct SurfaceInteraction {
    /// Point, error bound and unit geometric normal, facing against the incoming ray.
    pub surface: SurfacePoint,
    /// Unit shading normal, in the same hemisphere as the geometric normal.
    pub shading_normal: Vec3,
    pub uv: TexCoords,
    pub material: u32,
    pub geom_id: u32,
    pub prim_id: u32,
    /// The hit's barycentric coordinates on triangle `prim_id` (weights of its second and
    /// third vertex), for per-vertex mesh attributes.
    pub barycentric: Vec2,
    /// The ray arrived on the side the surface's own normal points to (outside, for closed
    /// meshes wound counter-clockwise and for spheres).
    pub front_face: bool,
}

/// The error (grid units) of a point on a signed distance grid beyond the rounding of
/// `origin + t dir`: the root is found in f64, far below this, but the spawned ray is
/// transformed back into grid units and re-enters the voxel; a ten-thousandth of a voxel
/// keeps it off the surface it leaves, and is far below what shading could show.
const SDF_POINT_ERROR: f32 = 1e-4;

struct LocalHit {
    point: Vec3,
    error: Vec3,
    geometric: Vec3,
    shading: Vec3,
    uv: TexCoords,
}

/// The hit in the space `origin` and `dir` are in. `uv_frame` turns a sphere's normal into
/// the frame its texture coordinates are measured in (a baked sphere's own frame).
fn local_hit(
    geometry: &Geometry,
    hit: &Hit,
    origin: Vec3,
    dir: Vec3,
    uv_frame: Option<Mat3>,
) -> LocalHit {
    match geometry {
        Geometry::Triangles(mesh) => {
            let tri = mesh.triangle(hit.prim_id);
            let plane = mesh.plane(hit.prim_id, &tri);
            let geometric = plane.normal;
            let (point, error) =
                triangle_hit_point(&tri, &plane, (hit.u, hit.v), (origin, dir, hit.t));
            let corners = mesh.indices[hit.prim_id as usize];
            let [i0, i1, i2] = corners.map(|i| i as usize);
            let b0 = 1.0 - hit.u - hit.v;
            let shading = match &mesh.normals {
                Some(normals) => interpolated_normal(normals, corners, hit),
                None => Vec3::ZERO,
            };
            let uv = TexCoords::Known(match &mesh.uvs {
                Some(t) => t[i0] * b0 + t[i1] * hit.u + t[i2] * hit.v,
                None => Vec2::new(hit.u, hit.v),
            });
            LocalHit { point, error, geometric, shading, uv }
        }
        Geometry::Sphere(s) => {
            let (point, error) = sphere_point(s.center, s.radius, origin, dir, hit.t);
            let n = ((point - s.center) / s.radius).normalize_or_zero();
            let uv = TexCoords::OnSphere(match uv_frame {
                Some(frame) => (frame * n).normalize_or_zero(),
                None => n,
            });
            LocalHit { point, error, geometric: n, shading: n, uv }
        }
        Geometry::SdfGrid(grid) => {
            let point = origin + dir * hit.t;
            let error =
                (origin.abs() + (dir * hit.t).abs()) * gamma(3) + Vec3::splat(SDF_POINT_ERROR);
            let geometric = grid.geometric_normal(hit.prim_id, point).normalize_or_zero();
            // A voxel flat along the ray (a zero gradient) faces the ray.
            let geometric = if geometric == Vec3::ZERO { -dir.normalize() } else { geometric };
            let shading = grid.shading_normal(hit.prim_id, point).normalize_or_zero();
            // As Mitsuba's sdfgrid: no texture coordinates.
            LocalHit { point, error, geometric, shading, uv: TexCoords::Known(Vec2::ZERO) }
        }
    }
}

/// The unit vertex normal of triangle `corners` at `hit`'s barycentrics (zero where they
/// cancel).
#[inline]
pub fn interpolated_normal(normals: &[Vec3], [i0, i1, i2]: [u32; 3], hit: &Hit) -> Vec3 {
    let b0 = 1.0 - hit.u - hit.v;
    let n = |i: u32| normals[i as usize];
    (n(i0) * b0 + n(i1) * hit.u + n(i2) * hit.v).normalize_or_zero()
}

/// The shading normal `shading` (zero: none) turned to the side of `geometric`, the
/// geometric normal already facing the ray; `geometric` where there is none.
#[inline]
pub fn shading_facing(shading: Vec3, geometric: Vec3) -> Vec3 {
    if shading == Vec3::ZERO {
        geometric
    } else if shading.dot(geometric) < 0.0 {
        -shading
    } else {
        shading
    }
}

/// Which side of a surface a ray travelling along `dir` meets (true: the front), and the
/// geometric and shading (zero: none) normals turned to that side. The geometric normal
/// decides, the shading normal then turned to its side; or, with `shading_sides`
/// (`Sides::Shading`, Mitsuba's way), the shading normal decides, and the geometric normal
/// may face away from the ray.
#[inline]
pub fn facing(
    geometric: Vec3,
    shading: Vec3,
    dir: Vec3,
    shading_sides: bool,
) -> (bool, Vec3, Vec3) {
    if shading_sides && shading != Vec3::ZERO {
        let front = shading.dot(dir) < 0.0;
        let side = if front { 1.0 } else { -1.0 };
        return (front, geometric * side, shading * side);
    }
    let front = geometric.dot(dir) < 0.0;
    let geometric = if front { geometric } else { -geometric };
    (front, geometric, shading_facing(shading, geometric))
}

pub fn interaction(scene: &RenderScene, ray: &Ray, hit: &Hit) -> SurfaceInteraction {
    let instance = &scene.instances[hit.geom_id as usize];
    let geometry = &scene.prototypes[instance.prototype as usize].geometry;
    let placement = &instance.placement;
    let transforms =
        placement.render_from_object(ray.time).zip(placement.object_from_render(ray.time));
    let local = match transforms {
        None => {
            // A sphere baked into render space (rotated and uniformly scaled) keeps its
            // own frame for texture coordinates, so that textures turn with it.
            let uv_frame = match (geometry, placement) {
                (Geometry::Sphere(_), Placement::Baked { object_from_render }) => {
                    Some(Mat3::from(object_from_render.matrix3))
                }
                _ => None,
            };
            local_hit(geometry, hit, ray.origin, ray.dir, uv_frame)
        }
        // The stored inverse (static instances), or the one the backends trace moving
        // instances with: the object-space ray is the one that found the hit.
        Some((render_from_object, object_from_render)) => {
            let origin = object_from_render.transform_point3(ray.origin);
            let dir = object_from_render.transform_vector3(ray.dir);
            let mut l = local_hit(geometry, hit, origin, dir, None);
            (l.point, l.error) = transform_point_with_error(&render_from_object, l.point, l.error);
            let normal_from_object = Mat3::from(object_from_render.matrix3).transpose();
            l.geometric = (normal_from_object * l.geometric).normalize_or_zero();
            l.shading = (normal_from_object * l.shading).normalize_or_zero();
            l
        }
    };
    let shading_sides = scene.sides == crate::scene::Sides::Shading;
    let (front_face, geometric, shading) =
        facing(local.geometric, local.shading, ray.dir, shading_sides);
    SurfaceInteraction {
        surface: SurfacePoint { point: local.point, error: local.error, normal: geometric },
        shading_normal: shading,
        uv: local.uv,
        material: instance.material,
        geom_id: hit.geom_id,
        prim_id: hit.prim_id,
        barycentric: Vec2::new(hit.u, hit.v),
        front_face,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Affine3A;

    #[test]
    fn transformed_error_bound_covers_the_rounding() {
        let m = Affine3A::from_scale_rotation_translation(
            Vec3::new(3.0, 0.5, 2.0),
            glam::Quat::from_rotation_y(0.7),
            Vec3::new(100.0, -50.0, 7.0),
        );
        let p = Vec3::new(1.234, -5.678, 9.1011);
        let (q, err) = transform_point_with_error(&m, p, Vec3::ZERO);
        let exact = glam::DAffine3::from_mat4(glam::Mat4::from(m).as_dmat4())
            .transform_point3(p.as_dvec3());
        let off = (q.as_dvec3() - exact).abs();
        assert!(off.x <= err.x as f64 && off.y <= err.y as f64 && off.z <= err.z as f64);
    }
}
