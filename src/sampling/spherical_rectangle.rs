//! Directions uniform in the solid angle a rectangle subtends (Ureña, Fajardo & King 2013,
//! "An area-preserving parametrization for spherical rectangles"). In f64, for the same
//! reason as the spherical triangle: the solid angle is a sum of angles minus 2π.

use glam::{DVec3, Vec2, Vec3};
use std::f64::consts::TAU;

/// The frame of a rectangle `corner + s·edge_u + t·edge_v` (s, t in [0, 1], edges
/// perpendicular), fixed for the rectangle: an emitter keeps it, so each shading point only
/// projects itself into it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RectangleFrame {
    corner: DVec3,
    /// Unit vectors along the edges, and their cross product.
    x: DVec3,
    y: DVec3,
    z: DVec3,
    edge_u_length: f64,
    edge_v_length: f64,
}

impl RectangleFrame {
    /// `None` when an edge is empty.
    pub fn new(corner: Vec3, edge_u: Vec3, edge_v: Vec3) -> Option<Self> {
        let (edge_u, edge_v) = (edge_u.as_dvec3(), edge_v.as_dvec3());
        let x = edge_u.try_normalize()?;
        let y = edge_v.try_normalize()?;
        let z = x.cross(y);
        (z.length_squared() > 0.0).then_some(RectangleFrame {
            corner: corner.as_dvec3(),
            x,
            y,
            z,
            edge_u_length: edge_u.length(),
            edge_v_length: edge_v.length(),
        })
    }

    /// The rectangle as seen from `reference`; `None` when `reference` lies in its plane.
    pub fn seen_from(&self, reference: Vec3) -> Option<SphericalRectangle> {
        let d = self.corner - reference.as_dvec3();
        // The side the point is on does not matter: the plane is put below it (z0 < 0).
        let height = d.dot(self.z).abs();
        if !(height > 0.0) {
            return None;
        }
        let (x0, y0) = (d.dot(self.x), d.dot(self.y));
        let (x1, y1) = (x0 + self.edge_u_length, y0 + self.edge_v_length);
        let z0 = -height;
        let h2 = height * height;
        // The interior angles g0..g3 between the planes through the origin and consecutive
        // edges, as arguments of (cos, sin) pairs with the common positive factors dropped:
        // the planes' normals have closed forms in this frame (as in pbrt-v4), and
        // cos g = −n_a·n_b, sin g = |n_a × n_b| reduce to a corner's coordinates and its
        // distance. Pairs of angles are summed by multiplying the pairs as complex numbers:
        // two `atan2` instead of four `acos`, and no precision lost near 0 and π.
        let distance = |cx: f64, cy: f64| (cx * cx + cy * cy + h2).sqrt();
        let g0 = (x1 * y0, height * distance(x1, y0));
        let g1 = (-x1 * y1, height * distance(x1, y1));
        let g2 = (x0 * y1, height * distance(x0, y1));
        let g3 = (-x0 * y0, height * distance(x0, y0));
        let g01 = angle_sum(g0, g1);
        let g23 = angle_sum(g2, g3);
        let k = TAU - g23;
        let solid_angle = g01 - k;
        Some(SphericalRectangle {
            x0,
            x1,
            y0,
            y1,
            z0,
            edge_u_length: self.edge_u_length,
            edge_v_length: self.edge_v_length,
            // The z components of the unit normals of the planes through the first and the
            // third edge.
            b0: -y0 / (y0 * y0 + h2).sqrt(),
            b1: y1 / (y1 * y1 + h2).sqrt(),
            k,
            solid_angle,
        })
    }
}

/// The sum, in [0, 2π), of two angles in [0, π] given as (cos, sin) up to positive factors.
fn angle_sum((c0, s0): (f64, f64), (c1, s1): (f64, f64)) -> f64 {
    let angle = (c0 * s1 + s0 * c1).atan2(c0 * c1 - s0 * s1);
    if angle < 0.0 { angle + TAU } else { angle }
}

/// A rectangle as seen from a reference point, in the rectangle's own frame with the
/// reference point at the origin.
#[derive(Clone, Copy, Debug)]
pub struct SphericalRectangle {
    /// Extent of the rectangle along its edges, relative to the reference point.
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    /// Signed distance of the rectangle's plane (negative by construction).
    z0: f64,
    edge_u_length: f64,
    edge_v_length: f64,
    b0: f64,
    b1: f64,
    k: f64,
    solid_angle: f64,
}

impl SphericalRectangle {
    /// The rectangle `corner + s·edge_u + t·edge_v` seen from `reference`; `None` when
    /// `reference` lies in the rectangle's plane or an edge is empty.
    pub fn new(reference: Vec3, corner: Vec3, edge_u: Vec3, edge_v: Vec3) -> Option<Self> {
        RectangleFrame::new(corner, edge_u, edge_v)?.seen_from(reference)
    }

    pub fn solid_angle(&self) -> f64 {
        self.solid_angle
    }

    /// The rectangle's parameters (s, t) in [0, 1]² of the direction that `u` picks,
    /// uniformly by solid angle.
    pub fn sample(&self, u: Vec2) -> Vec2 {
        let (x0, x1, y0, y1, z0) = (self.x0, self.x1, self.y0, self.y1, self.z0);
        // The x at which the sub-rectangle [x0, x] subtends u.x of the solid angle.
        let au = u.x as f64 * self.solid_angle + self.k;
        let (sin_au, cos_au) = au.sin_cos();
        let fu = (cos_au * self.b0 - self.b1) / sin_au;
        let cu = if fu.is_finite() {
            (fu.signum() / (fu * fu + self.b0 * self.b0).sqrt()).clamp(-1.0, 1.0)
        } else {
            // sin(au) = 0 only at the ends of the range.
            if u.x < 0.5 { -1.0 } else { 1.0 }
        };
        let xu = (-(cu * z0) / (1.0 - cu * cu).max(0.0).sqrt()).clamp(x0, x1);
        let xu = if xu.is_nan() { x0 } else { xu };
        // Then y along that line, uniform in the projected sine.
        let d = (xu * xu + z0 * z0).sqrt();
        let h0 = y0 / (d * d + y0 * y0).sqrt();
        let h1 = y1 / (d * d + y1 * y1).sqrt();
        let hv = h0 + u.y as f64 * (h1 - h0);
        let hv2 = hv * hv;
        let yv = if hv2 < 1.0 - 1e-12 { (hv * d) / (1.0 - hv2).sqrt() } else { y1 };
        let s = (xu - x0) / self.edge_u_length;
        let t = (yv.clamp(y0, y1) - y0) / self.edge_v_length;
        Vec2::new(s.clamp(0.0, 1.0) as f32, t.clamp(0.0, 1.0) as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_straight_above_has_the_known_solid_angle() {
        // A square of half-side a = 1 centred at height h = 1 above the point:
        // Ω = 4 atan(a² / (h √(2a² + h²))) = 4 atan(1/√3).
        let r = SphericalRectangle::new(
            Vec3::ZERO,
            Vec3::new(-1.0, -1.0, 1.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
        )
        .unwrap();
        let expected = 4.0 * (1.0f64 / 3.0f64.sqrt()).atan();
        assert!((r.solid_angle() - expected).abs() < 1e-12, "{}", r.solid_angle());
    }

    /// The solid angle the textbook way: the angles between the planes through the
    /// reference point and consecutive edges, each from generic cross products and `acos`.
    fn solid_angle_from_planes(reference: Vec3, corner: Vec3, u: Vec3, v: Vec3) -> f64 {
        let c = corner.as_dvec3() - reference.as_dvec3();
        let (u, v) = (u.as_dvec3(), v.as_dvec3());
        let corners = [c, c + u, c + u + v, c + v];
        let normal = |i: usize| corners[i].cross(corners[(i + 1) % 4]).normalize();
        let angle = |i: usize| (-normal(i).dot(normal((i + 1) % 4))).clamp(-1.0, 1.0).acos();
        (0..4).map(angle).sum::<f64>() - TAU
    }

    #[test]
    fn solid_angles_agree_with_the_planes_construction() {
        let mut rng = crate::splitmix::SplitMix64(11);
        for _ in 0..2000 {
            let corner = rng.vec3(-2.0, 2.0);
            // Exactly perpendicular edges (as the construction assumes), in any orientation.
            let [a, b, c] = rng.vec3(-2.0, 2.0).to_array();
            let axes = [[0, 1, 2], [1, 2, 0], [2, 0, 1], [0, 2, 1]][(rng.unit() * 3.99) as usize];
            let permute = |w: [f32; 3]| Vec3::new(w[axes[0]], w[axes[1]], w[axes[2]]);
            let (u, v) = (permute([a, b, c]), permute([-b, a, 0.0]));
            let reference = rng.vec3(-1.5, 1.5);
            let Some(r) = SphericalRectangle::new(reference, corner, u, v) else { continue };
            let expected = solid_angle_from_planes(reference, corner, u, v);
            assert!(
                (r.solid_angle() - expected).abs() <= 1e-9 * expected.max(1e-3),
                "{reference} {corner} {u} {v}: {} vs {expected}",
                r.solid_angle()
            );
            // Either side of the plane sees the same solid angle (away from the plane, where
            // the f32 mirror point's rounding barely moves it).
            let normal = u.cross(v).normalize();
            let height = (corner - reference).dot(normal);
            if height.abs() > 0.05 {
                let m = SphericalRectangle::new(reference + 2.0 * height * normal, corner, u, v)
                    .expect("off the plane");
                assert!(
                    (m.solid_angle() - expected).abs() < 1e-4 * expected,
                    "mirror of {reference}: {} vs {expected}",
                    m.solid_angle()
                );
            }
        }
    }

    #[test]
    fn the_unit_square_maps_onto_the_whole_rectangle() {
        let r = SphericalRectangle::new(
            Vec3::new(0.3, -0.2, 0.0),
            Vec3::new(-1.0, -1.0, 1.0),
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
        )
        .unwrap();
        for (u, st) in
            [([0.0, 0.0], [0.0, 0.0]), ([1.0, 1.0], [1.0, 1.0]), ([0.0, 1.0], [0.0, 1.0])]
        {
            let got = r.sample(Vec2::from_array(u));
            assert!((got - Vec2::from_array(st)).length() < 1e-5, "{u:?} -> {got}");
        }
    }
}
