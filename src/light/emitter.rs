//! One emitting primitive, and how a point on it is sampled from a shading point: uniformly
//! by solid angle where that is numerically stable (spherical triangles and rectangles, the
//! cone a sphere subtends), else uniformly by area. Far-away lights gain nothing from solid
//! angle sampling and lose accuracy to it; near ones gain the most, since area sampling
//! wastes samples on the parts seen at grazing angles. Densities are per unit solid angle at
//! the shading point, so both strategies enter MIS alike.

use super::ellipsoid::Ellipsoid;
use super::shape_sample::{ShapeSample, by_solid_angle, solid_angle_density};
use super::sphere_shape::SphereShape;
use crate::float_error::{TrianglePlane, triangle_point};
use crate::sampling::spherical_rectangle::{RectangleFrame, SphericalRectangle};
use crate::sampling::{spherical_triangle, uniform_triangle};
use glam::{Vec2, Vec3};

/// Solid-angle sampling costs several trigonometric functions per sample and gains little
/// beyond a few bounding radii from the light, where the density over it is nearly uniform
/// anyway. Chosen by time to equal error (MSE over three seeds × median render time, 64 spp,
/// against the peers' Mitsuba reference and 4096-spp renders): on the two Cornell boxes 3
/// radii beat 4 by 3.6 % and 5.7 % (4 radii lowered the MSE by 2.3–2.4 % more, for 6–9 % more
/// time) and on the glass scene by 8.8 % (the same MSE within 0.2 %, 9 % less time); 2 radii
/// lost by 1.5 % and 1.7 % on the boxes (no point of them is that near), and nothing changed
/// on the glossy plates, whose lights are far from everything.
const NEAR_RADII: f32 = 3.0;

/// One emitting primitive, in render space.
#[derive(Clone, Debug)]
pub enum EmitterShape {
    Triangle {
        vertices: [Vec3; 3],
        plane: TrianglePlane,
        /// Kept: the density of area sampling (every far light sample) divides by it.
        area: f32,
        near: NearSphere,
    },
    /// A parallelogram made of two triangles, (v0, v1, v3) and (v2, v3, v1), with v2
    /// opposite v0: the point with parameters (s, t) is v0 + s·(v1 − v0) + t·(v3 − v0), and
    /// it is computed on the mesh triangle that holds it. One emitter for both keeps the
    /// sampler's stratification over the whole quad.
    Quad {
        vertices: [Vec3; 4],
        planes: [TrianglePlane; 2],
        /// A rectangle's frame (sampled by solid angle from near points); `None` for other
        /// parallelograms. Boxed: it is larger than the rest of an emitter, and every
        /// triangle of an emissive mesh is an emitter of the same size.
        rectangle: Option<Box<RectangleFrame>>,
        area: f32,
        near: NearSphere,
    },
    Sphere(SphereShape),
    /// A sphere under an affine map (see `Ellipsoid`).
    Ellipsoid(Box<Ellipsoid>),
}

impl EmitterShape {
    pub fn triangle(vertices: [Vec3; 3]) -> Self {
        let [v0, v1, v2] = vertices;
        let area = 0.5 * (v1 - v0).cross(v2 - v0).length();
        let center = (v0 + v1 + v2) / 3.0;
        let radius2 = vertices.map(|v| (v - center).length_squared());
        let near = NearSphere::around(center, radius2[0].max(radius2[1]).max(radius2[2]));
        EmitterShape::Triangle { vertices, plane: TrianglePlane::new(&vertices), area, near }
    }

    /// The quad v0 v1 v2 v3 (in order around it); `None` unless it is a parallelogram
    /// (within rounding of its coordinates).
    pub fn quad(vertices: [Vec3; 4]) -> Option<Self> {
        let [v0, v1, v2, v3] = vertices;
        let scale = vertices.iter().map(|v| v.abs().max_element()).fold(0.0, f32::max);
        if (v0 + v2 - v1 - v3).abs().max_element() > 1e-5 * scale {
            return None;
        }
        let planes = [TrianglePlane::new(&[v0, v1, v3]), TrianglePlane::new(&[v2, v3, v1])];
        let (edge_u, edge_v) = (v1 - v0, v3 - v0);
        if planes[0].normal == Vec3::ZERO || planes[0].normal.dot(planes[1].normal) < 0.999_999 {
            return None;
        }
        let rectangle = (edge_u.dot(edge_v).abs() <= 1e-5 * edge_u.length() * edge_v.length())
            .then(|| RectangleFrame::new(v0, edge_u, edge_v).map(Box::new))
            .flatten();
        let area = edge_u.cross(edge_v).length();
        let radius2 = (v0 - v2).length_squared().max((v1 - v3).length_squared()) * 0.25;
        let near = NearSphere::around((v0 + v2) * 0.5, radius2);
        Some(EmitterShape::Quad { vertices, planes, rectangle, area, near })
    }

    /// Whether `reference` lies on the side a flat shape's normal points to (always, for a
    /// sphere).
    pub fn faces(&self, reference: Vec3) -> bool {
        match self {
            EmitterShape::Triangle { vertices: [v0, ..], plane, .. } => {
                (reference - *v0).dot(plane.normal) > 0.0
            }
            EmitterShape::Quad { vertices: [v0, ..], planes, .. } => {
                (reference - *v0).dot(planes[0].normal) > 0.0
            }
            EmitterShape::Sphere(_) | EmitterShape::Ellipsoid(_) => true,
        }
    }

    /// Whether `reference` is behind the shape as an emitter that is `two_sided` or not:
    /// where it sends no light (the back of a one-sided flat emitter).
    #[inline]
    pub fn is_behind(&self, two_sided: bool, reference: Vec3) -> bool {
        !two_sided && !self.faces(reference)
    }

    pub fn area(&self) -> f32 {
        match self {
            EmitterShape::Triangle { area, .. } | EmitterShape::Quad { area, .. } => *area,
            EmitterShape::Sphere(sphere) => sphere.area(),
            EmitterShape::Ellipsoid(e) => e.area(),
        }
    }
}

/// Where solid-angle sampling of a flat shape pays: within `NEAR_RADII` bounding radii of
/// its centre (kept, since every light sample asks).
#[derive(Clone, Copy, Debug)]
pub struct NearSphere {
    center: Vec3,
    /// The square of `NEAR_RADII` bounding radii.
    radius2: f32,
}

impl NearSphere {
    fn around(center: Vec3, bounding_radius2: f32) -> Self {
        NearSphere { center, radius2: NEAR_RADII * NEAR_RADII * bounding_radius2 }
    }

    /// Whether `reference` is inside.
    #[inline(always)]
    pub fn contains(&self, reference: Vec3) -> bool {
        (self.center - reference).length_squared() < self.radius2
    }
}

/// How a shape is sampled by solid angle from one shading point.
#[derive(Clone, Copy, Debug)]
enum Spherical {
    Triangle { solid_angle: f64 },
    Rectangle(SphericalRectangle),
}

impl Spherical {
    fn pdf(&self) -> f32 {
        match self {
            Spherical::Triangle { solid_angle } => (1.0 / solid_angle) as f32,
            Spherical::Rectangle(r) => (1.0 / r.solid_angle()) as f32,
        }
    }
}

impl EmitterShape {
    /// The solid-angle strategy for shading point `reference`, or `None` where sampling by
    /// area is the stable choice (tiny or huge solid angles, non-rectangular quads, inside a
    /// sphere). Sampling and density both ask here, so they always agree.
    fn spherical(&self, reference: Vec3) -> Option<Spherical> {
        if !self.is_near(reference) {
            return None;
        }
        match self {
            EmitterShape::Triangle { vertices, .. } => {
                let solid_angle = spherical_triangle::solid_angle(vertices, reference);
                by_solid_angle(solid_angle).then_some(Spherical::Triangle { solid_angle })
            }
            EmitterShape::Quad { rectangle: Some(frame), .. } => frame
                .seen_from(reference)
                .filter(|r| by_solid_angle(r.solid_angle()))
                .map(Spherical::Rectangle),
            EmitterShape::Quad { .. } | EmitterShape::Sphere(_) | EmitterShape::Ellipsoid(_) => {
                None
            }
        }
    }

    /// Whether `reference` is close enough for solid-angle sampling to pay for itself.
    pub(super) fn is_near(&self, reference: Vec3) -> bool {
        match self {
            EmitterShape::Triangle { near, .. } | EmitterShape::Quad { near, .. } => {
                near.contains(reference)
            }
            EmitterShape::Sphere(_) | EmitterShape::Ellipsoid(_) => true,
        }
    }

    /// A point sampled from `reference` with `u`; `None` where nothing can be sampled (a
    /// degenerate shape, or one seen exactly edge-on).
    pub fn sample_from(&self, reference: Vec3, u: Vec2) -> Option<ShapeSample> {
        match self {
            EmitterShape::Sphere(sphere) => return sphere.sample_from(reference, u),
            EmitterShape::Ellipsoid(e) => return e.sample_from(reference, u),
            _ => {}
        }
        let Some(spherical) = self.spherical(reference) else {
            return self.sample_by_area(reference, u);
        };
        let pdf = spherical.pdf();
        match (self, spherical) {
            (EmitterShape::Triangle { vertices, plane, .. }, Spherical::Triangle { .. }) => {
                let b = spherical_triangle::sample(vertices, reference, u)?;
                let (point, error) = triangle_point(vertices, plane, b.x, b.y);
                Some(ShapeSample { point, error, normal: plane.normal, pdf })
            }
            (EmitterShape::Quad { .. }, Spherical::Rectangle(r)) => {
                let (point, error, normal) = self.quad_point(r.sample(u));
                Some(ShapeSample { point, error, normal, pdf })
            }
            _ => unreachable!("`spherical` matches the shape"),
        }
    }

    /// A point sampled uniformly by area with `u` (its density still per unit solid angle
    /// at `reference`).
    pub(super) fn sample_by_area(&self, reference: Vec3, u: Vec2) -> Option<ShapeSample> {
        let (point, error, normal) = match self {
            EmitterShape::Triangle { vertices, plane, .. } => {
                let b = uniform_triangle(u);
                let (point, error) = triangle_point(vertices, plane, b.x, b.y);
                (point, error, plane.normal)
            }
            EmitterShape::Quad { .. } => self.quad_point(u),
            EmitterShape::Sphere(sphere) => return sphere.sample_by_area(reference, u),
            // Not uniform by area: the sphere's uniform points carried over by the map.
            EmitterShape::Ellipsoid(e) => return e.sample_from(reference, u),
        };
        let pdf = solid_angle_density(1.0 / self.area(), reference, point, normal);
        (pdf > 0.0).then_some(ShapeSample { point, error, normal, pdf })
    }

    /// The point of a quad at parameters `st`, computed on the mesh triangle that holds it.
    fn quad_point(&self, st: Vec2) -> (Vec3, Vec3, Vec3) {
        let EmitterShape::Quad { vertices: [v0, v1, v2, v3], planes, .. } = self else {
            unreachable!("only quads have quad points")
        };
        let (point, error) = if st.x + st.y <= 1.0 {
            triangle_point(&[*v0, *v1, *v3], &planes[0], st.x, st.y)
        } else {
            triangle_point(&[*v2, *v3, *v1], &planes[1], 1.0 - st.x, 1.0 - st.y)
        };
        (point, error, planes[0].normal)
    }

    /// The density per unit solid angle with which `sample_from(reference, ..)` picks
    /// `point` (normal `normal`), a point on this shape.
    pub fn pdf_from(&self, reference: Vec3, point: Vec3, normal: Vec3) -> f32 {
        match self {
            EmitterShape::Sphere(sphere) => return sphere.pdf_from(reference, point, normal),
            EmitterShape::Ellipsoid(e) => return e.pdf_from(reference, point, normal),
            _ => {}
        }
        match self.spherical(reference) {
            Some(spherical) => spherical.pdf(),
            None => solid_angle_density(1.0 / self.area(), reference, point, normal),
        }
    }
}
