//! Directions uniform in the solid angle a rectangle subtends (Ureña, Fajardo & King 2013,
//! "An area-preserving parametrization for spherical rectangles"). In f64, for the same
//! reason as the spherical triangle: the solid angle is a sum of angles minus 2π.

use glam::{DVec3, Vec2, Vec3};
use std::f64::consts::TAU;

/// A rectangle `corner + s·edge_u + t·edge_v` (s, t in [0, 1], edges perpendicular) as
/// seen from a reference point, in the rectangle's own frame with the reference point at
/// the origin.
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
    /// `None` when the reference point lies in the rectangle's plane or an edge is empty.
    pub fn new(reference: Vec3, corner: Vec3, edge_u: Vec3, edge_v: Vec3) -> Option<Self> {
        let (edge_u, edge_v) = (edge_u.as_dvec3(), edge_v.as_dvec3());
        let (edge_u_length, edge_v_length) = (edge_u.length(), edge_v.length());
        let x = edge_u.try_normalize()?;
        let y = edge_v.try_normalize()?;
        let mut z = x.cross(y);
        let d = corner.as_dvec3() - reference.as_dvec3();
        let mut z0 = d.dot(z);
        if z0 > 0.0 {
            z = -z;
            z0 = -z0;
        }
        if !(z0 < 0.0) || z.length_squared() == 0.0 {
            return None;
        }
        let (x0, y0) = (d.dot(x), d.dot(y));
        let (x1, y1) = (x0 + edge_u_length, y0 + edge_v_length);
        let corner_at = |cx: f64, cy: f64| DVec3::new(cx, cy, z0);
        let (v00, v01, v10, v11) =
            (corner_at(x0, y0), corner_at(x0, y1), corner_at(x1, y0), corner_at(x1, y1));
        // Normals of the planes through the origin and each edge.
        let n0 = v00.cross(v10).try_normalize()?;
        let n1 = v10.cross(v11).try_normalize()?;
        let n2 = v11.cross(v01).try_normalize()?;
        let n3 = v01.cross(v00).try_normalize()?;
        let interior = |a: DVec3, b: DVec3| (-a.dot(b)).clamp(-1.0, 1.0).acos();
        let (g0, g1, g2, g3) =
            (interior(n0, n1), interior(n1, n2), interior(n2, n3), interior(n3, n0));
        let k = TAU - g2 - g3;
        let solid_angle = g0 + g1 - k;
        Some(SphericalRectangle {
            x0,
            x1,
            y0,
            y1,
            z0,
            edge_u_length,
            edge_v_length,
            b0: n0.z,
            b1: n2.z,
            k,
            solid_angle,
        })
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
