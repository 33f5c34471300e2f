//! What the integrator knows about a hit: the point with its error bound, normals facing the
//! incoming ray, material and texture coordinates. Computed from the backend's `Hit` the same
//! way for every backend.

use crate::accel::{Hit, Ray};
use crate::render_scene::{Geometry, RenderScene};
use crate::spawn::{SurfacePoint, sphere_point, triangle_point};
use glam::{Vec2, Vec3};

#[derive(Clone, Copy, Debug)]
pub struct SurfaceInteraction {
    /// Point, error bound and unit geometric normal, facing against the incoming ray.
    pub surface: SurfacePoint,
    /// Unit shading normal, in the same hemisphere as the geometric normal.
    pub shading_normal: Vec3,
    pub uv: Vec2,
    pub material: u32,
    pub geom_id: u32,
}

pub fn interaction(scene: &RenderScene, ray: &Ray, hit: &Hit) -> SurfaceInteraction {
    let shape = &scene.shapes[hit.geom_id as usize];
    let (point, error, geometric, shading, uv) = match &shape.geometry {
        Geometry::Triangles(mesh) => {
            let tri = mesh.triangle(hit.prim_id);
            let (point, error) = triangle_point(&tri, hit.u, hit.v);
            let geometric = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize_or_zero();
            let [i0, i1, i2] = mesh.indices[hit.prim_id as usize].map(|i| i as usize);
            let b0 = 1.0 - hit.u - hit.v;
            let shading = match &mesh.normals {
                Some(n) => (n[i0] * b0 + n[i1] * hit.u + n[i2] * hit.v).normalize_or_zero(),
                None => geometric,
            };
            let uv = match &mesh.uvs {
                Some(t) => t[i0] * b0 + t[i1] * hit.u + t[i2] * hit.v,
                None => Vec2::new(hit.u, hit.v),
            };
            (point, error, geometric, shading, uv)
        }
        Geometry::Sphere(s) => {
            let (point, error) = sphere_point(s.center, s.radius, ray.origin, ray.dir, hit.t);
            let n = ((point - s.center) / s.radius).normalize_or_zero();
            let uv = Vec2::new(
                0.5 + n.z.atan2(n.x) / std::f32::consts::TAU,
                n.y.clamp(-1.0, 1.0).acos() / std::f32::consts::PI,
            );
            (point, error, n, n, uv)
        }
    };
    let geometric = if geometric.dot(ray.dir) > 0.0 { -geometric } else { geometric };
    let shading = if shading == Vec3::ZERO {
        geometric
    } else if shading.dot(geometric) < 0.0 {
        -shading
    } else {
        shading
    };
    SurfaceInteraction {
        surface: SurfacePoint { point, error, normal: geometric },
        shading_normal: shading,
        uv,
        material: shape.material,
        geom_id: hit.geom_id,
    }
}
