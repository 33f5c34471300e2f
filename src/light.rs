//! Lights in render space: point lights (one shadow ray each) and emissive shapes, which are
//! sampled by area in proportion to their emitted power.

use crate::material::Material;
use crate::render_scene::{Geometry, Shape};
use crate::sampling::uniform_triangle;
use crate::spawn::{gamma, triangle_point};
use glam::{Vec2, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub struct PointLight {
    pub position: Vec3,
    /// Radiant intensity (W/sr) per channel.
    pub intensity: Vec3,
}

/// One emitting primitive.
#[derive(Clone, Debug, PartialEq)]
pub enum EmitterShape {
    Triangle([Vec3; 3]),
    Sphere { center: Vec3, radius: f32 },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Emitter {
    pub geom_id: u32,
    pub shape: EmitterShape,
    pub emission: Vec3,
    pub area: f32,
}

/// A point sampled on an emitter.
#[derive(Clone, Copy, Debug)]
pub struct EmitterSample {
    pub point: Vec3,
    /// Rounding-error bound of `point`, so shadow rays can stop safely short of it.
    pub error: Vec3,
    /// Unit surface normal at `point`.
    pub normal: Vec3,
    pub emission: Vec3,
    /// Probability density of choosing this point, per unit area (includes the choice of
    /// emitter).
    pub pdf_area: f32,
    pub geom_id: u32,
}

#[derive(Clone, Debug, Default)]
pub struct LightSet {
    pub points: Vec<PointLight>,
    pub emitters: Vec<Emitter>,
    /// Cumulative emitted power of `emitters`, normalised so the last entry is 1.
    emitter_cdf: Vec<f32>,
}

fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

impl LightSet {
    /// Collects the emissive primitives of `shapes`.
    pub fn new(points: Vec<PointLight>, shapes: &[Shape], materials: &[Material]) -> Self {
        let mut emitters = Vec::new();
        for (geom_id, shape) in shapes.iter().enumerate() {
            let material = &materials[shape.material as usize];
            if !material.is_emissive() {
                continue;
            }
            let geom_id = geom_id as u32;
            match &shape.geometry {
                Geometry::Triangles(mesh) => {
                    for prim in 0..mesh.indices.len() as u32 {
                        let tri = mesh.triangle(prim);
                        let area = 0.5 * (tri[1] - tri[0]).cross(tri[2] - tri[0]).length();
                        if area > 0.0 && area.is_finite() {
                            emitters.push(Emitter {
                                geom_id,
                                shape: EmitterShape::Triangle(tri),
                                emission: material.emission,
                                area,
                            });
                        }
                    }
                }
                Geometry::Sphere(s) => emitters.push(Emitter {
                    geom_id,
                    shape: EmitterShape::Sphere { center: s.center, radius: s.radius },
                    emission: material.emission,
                    area: 4.0 * std::f32::consts::PI * s.radius * s.radius,
                }),
            }
        }
        let mut total = 0.0f64;
        let mut emitter_cdf: Vec<f32> = emitters
            .iter()
            .map(|e| {
                total += (e.area * luminance(e.emission)).max(0.0) as f64;
                total as f32
            })
            .collect();
        if total > 0.0 {
            for c in &mut emitter_cdf {
                *c = (*c as f64 / total) as f32;
            }
            if let Some(last) = emitter_cdf.last_mut() {
                *last = 1.0;
            }
        } else {
            emitters.clear();
            emitter_cdf.clear();
        }
        LightSet { points, emitters, emitter_cdf }
    }

    pub fn has_emitters(&self) -> bool {
        !self.emitters.is_empty()
    }

    fn emitter_probability(&self, index: usize) -> f32 {
        let below = if index == 0 { 0.0 } else { self.emitter_cdf[index - 1] };
        self.emitter_cdf[index] - below
    }

    /// Picks an emitter in proportion to its power (with `pick`) and a point on it uniformly
    /// by area (with `on_surface`).
    pub fn sample_emitter(&self, pick: f32, on_surface: Vec2) -> Option<EmitterSample> {
        if self.emitters.is_empty() {
            return None;
        }
        let index = self.emitter_cdf.partition_point(|&c| c <= pick).min(self.emitters.len() - 1);
        let emitter = &self.emitters[index];
        let probability = self.emitter_probability(index);
        if probability <= 0.0 {
            return None;
        }
        let (point, error, normal) = match emitter.shape {
            EmitterShape::Triangle(tri) => {
                let b = uniform_triangle(on_surface);
                let (point, error) = triangle_point(&tri, b.x, b.y);
                (point, error, (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize())
            }
            EmitterShape::Sphere { center, radius } => {
                let z = 1.0 - 2.0 * on_surface.x;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = 2.0 * std::f32::consts::PI * on_surface.y;
                let n = Vec3::new(r * phi.cos(), r * phi.sin(), z);
                let local = radius * n;
                let error = local.abs() * gamma(5) + (center.abs() + local.abs()) * gamma(1);
                (center + local, error, n)
            }
        };
        Some(EmitterSample {
            point,
            error,
            normal,
            emission: emitter.emission,
            pdf_area: probability / emitter.area,
            geom_id: emitter.geom_id,
        })
    }
}
