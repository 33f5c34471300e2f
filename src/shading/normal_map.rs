//! Normal maps (the course's `replace_normal`): the texture's colour c in [0, 1]³ is a
//! tangent-space normal 2c − 1, taken to render space by the frame (T, B, N): T and B the
//! unit directions in which the texture coordinates u and v grow on the surface (∂p/∂u,
//! ∂p/∂v), N the shading normal. The frame is computed only at hits whose material has a
//! normal map.

use crate::render_scene::{Geometry, Placement, RenderScene};
use crate::shading::surface::SurfaceInteraction;
use glam::{Mat3, Vec2, Vec3};

/// ∂p/∂u and ∂p/∂v of a triangle with corners `p` and texture coordinates `uv`; `None`
/// when the coordinates do not span the triangle.
fn triangle_derivatives(p: [Vec3; 3], uv: [Vec2; 3]) -> Option<(Vec3, Vec3)> {
    let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
    let (d1, d2) = (uv[1] - uv[0], uv[2] - uv[0]);
    let det = d1.x * d2.y - d2.x * d1.y;
    if det.abs() < 1e-12 || !det.is_finite() {
        return None;
    }
    Some(((d2.y * e1 - d1.y * e2) / det, (d1.x * e2 - d2.x * e1) / det))
}

/// ∂p/∂u and ∂p/∂v on a sphere of radius `r` at the point with unit normal `n` (the
/// sphere's own frame; see `tex_coords::sphere_uv`).
fn sphere_derivatives(n: Vec3, r: f32) -> (Vec3, Vec3) {
    use std::f32::consts::{PI, TAU};
    let sin_theta = (n.x * n.x + n.z * n.z).sqrt();
    let dpdu = TAU * r * Vec3::new(n.z, 0.0, -n.x);
    let (cos_phi, sin_phi) =
        if sin_theta > 0.0 { (n.x / sin_theta, n.z / sin_theta) } else { (1.0, 0.0) };
    let dpdv = PI * r * Vec3::new(n.y * cos_phi, -sin_theta, n.y * sin_phi);
    (dpdu, dpdv)
}

/// ∂p/∂u and ∂p/∂v at a hit, in render space, and the linear map to the object's own
/// space (the space its file describes it in, before its transformation).
#[derive(Clone, Copy, Debug)]
pub struct UvDerivatives {
    pub dpdu: Vec3,
    pub dpdv: Vec3,
    pub object_from_render: Mat3,
}

/// ∂p/∂u and ∂p/∂v at `si` (at `time`), if the surface has them.
pub fn uv_derivatives(
    scene: &RenderScene,
    si: &SurfaceInteraction,
    time: f32,
) -> Option<UvDerivatives> {
    let instance = &scene.instances[si.geom_id as usize];
    let geometry = &scene.prototypes[instance.prototype as usize].geometry;
    let placement = &instance.placement;
    // Derivatives in the prototype's space and the linear map that takes them to render space.
    let (dpdu, dpdv, render_from_object) = match geometry {
        Geometry::Triangles(mesh) => {
            let [i0, i1, i2] = mesh.indices[si.prim_id as usize].map(|i| i as usize);
            let uv = match &mesh.uvs {
                Some(t) => [t[i0], t[i1], t[i2]],
                None => [Vec2::ZERO, Vec2::X, Vec2::Y],
            };
            let (dpdu, dpdv) = triangle_derivatives(mesh.triangle(si.prim_id), uv)?;
            let linear = placement.render_from_object(time).map(|m| Mat3::from(m.matrix3));
            (dpdu, dpdv, linear)
        }
        // No texture coordinates, so nothing to differentiate.
        Geometry::SdfGrid(_) => return None,
        Geometry::Sphere(s) => match placement {
            Placement::Baked { object_from_render } => {
                let to_own = Mat3::from(object_from_render.matrix3);
                let n = ((si.surface.point - s.center) / s.radius).normalize_or_zero();
                let own = (to_own * n).normalize_or_zero();
                // The baked radius is in render space; the derivatives are taken in the
                // object's own space (a uniform scale: any axis measures it), whose radius
                // `to_own` scales it to: with the render radius, ∂p/∂u was scaled twice.
                let own_radius = s.radius * (to_own * Vec3::X).length();
                let (dpdu, dpdv) = sphere_derivatives(own, own_radius);
                (dpdu, dpdv, Some(to_own.inverse()))
            }
            _ => {
                let object_from_render = placement.object_from_render(time)?;
                let p = object_from_render.transform_point3(si.surface.point);
                let n = ((p - s.center) / s.radius).normalize_or_zero();
                let (dpdu, dpdv) = sphere_derivatives(n, s.radius);
                let linear = placement.render_from_object(time).map(|m| Mat3::from(m.matrix3));
                (dpdu, dpdv, linear)
            }
        },
    };
    let (dpdu, dpdv) = match render_from_object {
        Some(m) => (m * dpdu, m * dpdv),
        None => (dpdu, dpdv),
    };
    let object_from_render = Mat3::from(placement.texture_object_from_render(time).matrix3);
    (dpdu.is_finite() && dpdv.is_finite()).then_some(UvDerivatives {
        dpdu,
        dpdv,
        object_from_render,
    })
}

/// The shading normal a normal map's `color` (in [0, 1]³) gives at a surface with shading
/// normal `n` and derivatives `dpdu`, `dpdv`.
pub fn mapped_normal(color: Vec3, n: Vec3, dpdu: Vec3, dpdv: Vec3) -> Vec3 {
    let tangent_space = color * 2.0 - Vec3::ONE;
    let t = dpdu.normalize_or_zero();
    let b = dpdv.normalize_or_zero();
    let mapped =
        (tangent_space.x * t + tangent_space.y * b + tangent_space.z * n).normalize_or_zero();
    if mapped == Vec3::ZERO { n } else { mapped }
}

/// The normal of the surface p + h·d displaced by a height field h(u, v) along `along`
/// (the surface normal, in whatever units `along` carries): with slopes (∂h/∂u, ∂h/∂v),
/// ∂q/∂u = ∂p/∂u + (∂h/∂u)·d (likewise v), and the new normal ∂q/∂u × ∂q/∂v is turned to
/// `n`'s side.
pub fn bumped_normal(slopes: Vec2, n: Vec3, dpdu: Vec3, dpdv: Vec3, along: Vec3) -> Vec3 {
    let qu = dpdu + slopes.x * along;
    let qv = dpdv + slopes.y * along;
    let bumped = qu.cross(qv).normalize_or_zero();
    if bumped == Vec3::ZERO || !bumped.is_finite() {
        return n;
    }
    if bumped.dot(n) < 0.0 { -bumped } else { bumped }
}

/// The CENG795 course's bump mapping (`BumpScale::CourseTexels`): the object is displaced
/// in its own space, by `rise` (the height's differences to the next texel in u and in v)
/// along its own unit normal, over its own ∂p/∂u and ∂p/∂v; the new normal is taken to
/// render space as normals are (by the transpose of `object_from_render`), on `n`'s side.
pub fn course_bumped_normal(rise: Vec2, n: Vec3, d: &UvDerivatives) -> Vec3 {
    let to_object = d.object_from_render;
    let normal_to_object = to_object.inverse().transpose();
    let n_object = (normal_to_object * n).normalize_or_zero();
    let bumped_object =
        bumped_normal(rise, n_object, to_object * d.dpdu, to_object * d.dpdv, n_object);
    let bumped = (to_object.transpose() * bumped_object).normalize_or_zero();
    if bumped == Vec3::ZERO || !bumped.is_finite() {
        return n;
    }
    if bumped.dot(n) < 0.0 { -bumped } else { bumped }
}

/// The normal of a surface with normal `n` displaced along it by a solid height field
/// whose gradient there is `gradient` (render space): the gradient's part along the
/// surface tilts the normal away from rising height.
pub fn solid_bumped_normal(gradient: Vec3, n: Vec3) -> Vec3 {
    let along_surface = gradient - gradient.dot(n) * n;
    let bumped = (n - along_surface).normalize_or_zero();
    if bumped == Vec3::ZERO || !bumped.is_finite() { n } else { bumped }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_solid_slope_tilts_the_normal_downhill() {
        let n = Vec3::Z;
        // Height rising along +x with slope 1: the surface is tilted 45° towards −x.
        let tilted = solid_bumped_normal(Vec3::new(1.0, 0.0, 0.3), n);
        let expected = Vec3::new(-1.0, 0.0, 1.0).normalize();
        assert!((tilted - expected).length() < 1e-6, "{tilted}");
        assert_eq!(solid_bumped_normal(Vec3::new(0.0, 0.0, 5.0), n), n);
    }

    #[test]
    fn triangle_derivatives_recover_a_planar_mapping() {
        // p = (2u, 3v, 0) on a triangle with arbitrary texture coordinates.
        let uv = [Vec2::new(0.1, 0.2), Vec2::new(0.7, 0.3), Vec2::new(0.4, 0.9)];
        let p = uv.map(|t| Vec3::new(2.0 * t.x, 3.0 * t.y, 0.0));
        let (dpdu, dpdv) = triangle_derivatives(p, uv).unwrap();
        assert!((dpdu - Vec3::new(2.0, 0.0, 0.0)).length() < 1e-5, "{dpdu}");
        assert!((dpdv - Vec3::new(0.0, 3.0, 0.0)).length() < 1e-5, "{dpdv}");
        assert!(triangle_derivatives(p, [Vec2::ZERO; 3]).is_none());
    }

    #[test]
    fn sphere_derivatives_match_finite_differences_of_the_mapping() {
        // Invert sphere_uv: θ = πv, φ = π(1 − 2u).
        let point = |u: f32, v: f32| {
            let (theta, phi) = (std::f32::consts::PI * v, std::f32::consts::PI * (1.0 - 2.0 * u));
            Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin()) * 2.0
        };
        let (u, v, h) = (0.3f32, 0.4f32, 1e-3f32);
        let n = point(u, v) / 2.0;
        let (dpdu, dpdv) = sphere_derivatives(n, 2.0);
        let fd_u = (point(u + h, v) - point(u - h, v)) / (2.0 * h);
        let fd_v = (point(u, v + h) - point(u, v - h)) / (2.0 * h);
        assert!((dpdu - fd_u).length() < 1e-2 * fd_u.length(), "{dpdu} vs {fd_u}");
        assert!((dpdv - fd_v).length() < 1e-2 * fd_v.length(), "{dpdv} vs {fd_v}");
    }

    #[test]
    fn a_uv_slope_tilts_the_normal_downhill() {
        // p = (2u, 3v, 0); h rising by 2 per unit of u: ∂q/∂u = (2, 0, 2), a 45° tilt.
        let n = Vec3::Z;
        let tilted = bumped_normal(Vec2::new(2.0, 0.0), n, 2.0 * Vec3::X, 3.0 * Vec3::Y, n);
        assert!((tilted - Vec3::new(-1.0, 0.0, 1.0).normalize()).length() < 1e-6, "{tilted}");
        assert_eq!(bumped_normal(Vec2::ZERO, n, Vec3::X, Vec3::Y, n), n);
    }

    #[test]
    fn a_flat_normal_map_keeps_the_normal() {
        let n = Vec3::Z;
        let flat = Vec3::new(0.5, 0.5, 1.0);
        assert!((mapped_normal(flat, n, Vec3::X, Vec3::Y) - n).length() < 1e-6);
        let tilted = mapped_normal(Vec3::new(1.0, 0.5, 0.5), n, Vec3::X, Vec3::Y);
        assert!((tilted - Vec3::X).length() < 1e-6, "{tilted}");
    }
}
