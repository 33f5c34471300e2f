//! An emitting ellipsoid: a sphere under an affine map (the course's scaled `LightSphere`).
//! It has no closed-form uniform sampling, so a point is sampled on the sphere in the
//! object's own space (the cone it subtends from the shading point taken there, as for any
//! sphere) and carried over by the map; the density follows through the map's area Jacobian.
//! An affine map keeps tangency, so the object-space visible cap is exactly the visible part
//! of the ellipsoid.

use super::shape_sample::{ShapeSample, solid_angle_density};
use super::sphere_shape::SphereShape;
use crate::float_error::transform_point_with_error;
use glam::{Affine3A, Mat3, Vec2, Vec3};
use std::f32::consts::PI;

#[derive(Clone, Debug)]
pub struct Ellipsoid {
    /// The sphere in object space.
    center: Vec3,
    radius: f32,
    render_from_object: Affine3A,
    object_from_render: Affine3A,
    /// Inverse transpose of the linear part: object normals to render normals.
    normal_from_object: Mat3,
    /// |det| of the linear part.
    volume_scale: f32,
    /// Surface area (`surface_area`, a quadrature), computed once.
    area: f32,
}

impl Ellipsoid {
    /// `None` for a singular map.
    pub fn new(center: Vec3, radius: f32, render_from_object: Affine3A) -> Option<Self> {
        let linear = Mat3::from(render_from_object.matrix3);
        let det = linear.determinant();
        if !(det.abs() > 0.0) || !det.is_finite() || !(radius > 0.0) {
            return None;
        }
        let object_from_render = render_from_object.inverse();
        let mut ellipsoid = Ellipsoid {
            center,
            radius,
            render_from_object,
            object_from_render,
            normal_from_object: linear.inverse().transpose(),
            volume_scale: det.abs(),
            area: 0.0,
        };
        ellipsoid.area = ellipsoid.surface_area();
        Some(ellipsoid)
    }

    fn sphere(&self) -> SphereShape {
        SphereShape { center: self.center, radius: self.radius }
    }

    /// Render-space area per object-space area at the point with unit object normal `n`.
    fn area_scale(&self, n: Vec3) -> f32 {
        self.volume_scale * (self.normal_from_object * n).length()
    }

    /// Surface area, by midpoint quadrature of the area scale over the sphere. It only
    /// weighs the emitter's selection by power; the integrand is smooth, so a 32 × 64 grid is
    /// within 2e-3 even for a 20:1 ellipsoid, and is cheap for many instanced lights.
    fn surface_area(&self) -> f32 {
        let (rows, cols) = (32, 64);
        let columns: Vec<(f32, f32)> =
            (0..cols).map(|j| (2.0 * PI * (j as f32 + 0.5) / cols as f32).sin_cos()).collect();
        let mut sum = 0.0f64;
        for i in 0..rows {
            let z = 1.0 - 2.0 * (i as f32 + 0.5) / rows as f32;
            let r = (1.0 - z * z).max(0.0).sqrt();
            for (sin_phi, cos_phi) in &columns {
                sum += self.area_scale(Vec3::new(r * cos_phi, r * sin_phi, z)) as f64;
            }
        }
        // Each cell has object-space area 4πr² / (rows · cols) (equal-area rows in z).
        (sum * (4.0 * PI * self.radius * self.radius) as f64 / (rows * cols) as f64) as f32
    }

    pub fn area(&self) -> f32 {
        self.area
    }

    /// Converts the object-space solid-angle density `pdf_object` of `p_object` (unit normal
    /// `n_object`) seen from `reference_object` into the render-space one of `point`
    /// (normal `normal`) seen from `reference`.
    #[allow(clippy::too_many_arguments)]
    fn render_density(
        &self,
        pdf_object: f32,
        reference_object: Vec3,
        p_object: Vec3,
        n_object: Vec3,
        reference: Vec3,
        point: Vec3,
        normal: Vec3,
    ) -> f32 {
        // Solid angle → area density in object space: divide by the density one unit of
        // area density makes per solid angle.
        let per_unit_area = solid_angle_density(1.0, reference_object, p_object, n_object);
        if !(per_unit_area > 0.0) {
            return 0.0;
        }
        let pdf_object_area = pdf_object / per_unit_area;
        solid_angle_density(pdf_object_area / self.area_scale(n_object), reference, point, normal)
    }

    pub fn sample_from(&self, reference: Vec3, u: Vec2) -> Option<ShapeSample> {
        let reference_object = self.object_from_render.transform_point3(reference);
        let local = self.sphere().sample_from(reference_object, u)?;
        let (point, error) =
            transform_point_with_error(&self.render_from_object, local.point, local.error);
        let normal = (self.normal_from_object * local.normal).normalize_or_zero();
        let pdf = self.render_density(
            local.pdf,
            reference_object,
            local.point,
            local.normal,
            reference,
            point,
            normal,
        );
        (pdf > 0.0 && pdf.is_finite()).then_some(ShapeSample { point, error, normal, pdf })
    }

    pub fn pdf_from(&self, reference: Vec3, point: Vec3, normal: Vec3) -> f32 {
        let reference_object = self.object_from_render.transform_point3(reference);
        let p_object = self.object_from_render.transform_point3(point);
        let n_object = ((p_object - self.center) / self.radius).normalize_or_zero();
        let pdf_object = self.sphere().pdf_from(reference_object, p_object, n_object);
        self.render_density(
            pdf_object,
            reference_object,
            p_object,
            n_object,
            reference,
            point,
            normal,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::splitmix::SplitMix64;
    use glam::Quat;

    /// The hw6 shape (a sphere stretched 5×) turned and moved off the axes.
    fn stretched() -> Ellipsoid {
        let m = Affine3A::from_scale_rotation_translation(
            Vec3::new(5.0, 1.0, 0.6),
            Quat::from_rotation_z(0.4) * Quat::from_rotation_x(0.3),
            Vec3::new(0.5, 0.2, 3.0),
        );
        Ellipsoid::new(Vec3::new(0.1, -0.2, 0.0), 0.2, m).unwrap()
    }

    /// Mean and standard error of `value` over `n` draws.
    fn mean_and_error(n: usize, mut value: impl FnMut() -> f64) -> (f64, f64) {
        let (mut sum, mut sum2) = (0.0, 0.0);
        for _ in 0..n {
            let v = value();
            (sum, sum2) = (sum + v, sum2 + v * v);
        }
        let mean = sum / n as f64;
        (mean, ((sum2 / n as f64 - mean * mean).max(0.0) / n as f64).sqrt())
    }

    /// Whether the ray from `origin` along `dir` (render space) hits the ellipsoid: the
    /// sphere test in object space, independent of the sampling code.
    fn hits(e: &Ellipsoid, origin: Vec3, dir: Vec3) -> bool {
        let o = e.object_from_render.transform_point3(origin) - e.center;
        let d = e.object_from_render.transform_vector3(dir);
        let (a, b, c) = (d.dot(d), o.dot(d), o.dot(o) - e.radius * e.radius);
        let disc = b * b - a * c;
        disc >= 0.0 && (-b + disc.sqrt()) > 0.0
    }

    /// The solid angle the ellipsoid subtends, two ways: E[1 / pdf] over sampled points,
    /// and 4π × the fraction of uniform directions whose rays hit it.
    #[test]
    fn sampling_density_integrates_to_the_brute_force_solid_angle() {
        let e = stretched();
        for reference in [Vec3::new(0.4, 0.3, 2.2), Vec3::new(-1.0, 2.0, 3.5), Vec3::ZERO] {
            let mut rng = SplitMix64(11);
            let (sampled, sampled_error) = mean_and_error(200_000, || {
                let u = Vec2::new(rng.unit(), rng.unit());
                e.sample_from(reference, u).map_or(0.0, |s| 1.0 / s.pdf as f64)
            });
            let (fraction, fraction_error) = mean_and_error(4_000_000, || {
                let z = 1.0 - 2.0 * rng.unit();
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = 2.0 * PI * rng.unit();
                let dir = Vec3::new(r * phi.cos(), r * phi.sin(), z);
                hits(&e, reference, dir) as u8 as f64
            });
            let (brute, brute_error) =
                (4.0 * PI as f64 * fraction, 4.0 * PI as f64 * fraction_error);
            let combined = (sampled_error.powi(2) + brute_error.powi(2)).sqrt();
            println!(
                "from {reference}: sampled {sampled:.5} ± {sampled_error:.5} sr, brute force \
                 {brute:.5} ± {brute_error:.5} sr"
            );
            assert!(combined < 0.02 * brute, "too noisy to compare: {combined} of {brute}");
            assert!((sampled - brute).abs() < 4.0 * combined, "{sampled} vs {brute}");
        }
    }

    #[test]
    fn density_of_a_sampled_point_is_the_one_pdf_from_reports() {
        let e = stretched();
        let mut rng = SplitMix64(3);
        let reference = Vec3::new(0.4, 0.3, 2.2);
        for _ in 0..1000 {
            let s = e.sample_from(reference, Vec2::new(rng.unit(), rng.unit())).unwrap();
            let pdf = e.pdf_from(reference, s.point, s.normal);
            assert!((pdf - s.pdf).abs() <= 2e-3 * s.pdf, "{pdf} vs {}", s.pdf);
            // The normal is the ellipsoid's: it faces the reference on the visible side.
            assert!(s.normal.dot(reference - s.point) > 0.0);
        }
    }

    /// A prolate spheroid's area in closed form: 2πa²(1 + c/(a e) asin e), e² = 1 − a²/c².
    #[test]
    fn area_matches_the_closed_form_of_a_spheroid() {
        let (radius, stretch) = (0.5f32, 3.0f32);
        let m = Affine3A::from_scale(Vec3::new(1.0, 1.0, stretch));
        let e = Ellipsoid::new(Vec3::ZERO, radius, m).unwrap();
        let (a, c) = (radius as f64, (radius * stretch) as f64);
        let ecc = (1.0 - a * a / (c * c)).sqrt();
        let exact = 2.0 * std::f64::consts::PI * a * a * (1.0 + c / (a * ecc) * ecc.asin());
        let area = e.area() as f64;
        assert!((area - exact).abs() < 1e-3 * exact, "{area} vs {exact}");
        assert!(
            Ellipsoid::new(Vec3::ZERO, 1.0, Affine3A::from_scale(Vec3::new(1.0, 0.0, 1.0)))
                .is_none()
        );
    }
}
