//! The radiance of a textured emitter at a point sampled on it: the point's texture
//! coordinates found as a ray that hit it would find them (a triangle's barycentric
//! interpolation of its vertices' coordinates, a sphere's direction from its centre in its
//! own frame), then the texture looked up there.

use crate::shading::material::Texture;
use crate::shading::tex_coords::sphere_uv;
use glam::{Mat3, Vec2, Vec3};
use std::sync::Arc;

/// Where on a textured emitter each texture coordinate is.
#[derive(Clone, Debug)]
pub struct EmissionMap {
    pub texture: Arc<Texture>,
    /// The texture's mean over the unit square of coordinates (`mean_over_unit_square`).
    pub mean: Vec3,
    pub uvs: UvSource,
}

#[derive(Clone, Debug)]
pub enum UvSource {
    /// A triangle's vertices, in the order the emitter holds them, and their coordinates.
    Triangle { vertices: [Vec3; 3], uvs: [Vec2; 3] },
    /// A sphere (or a sphere under a linear map) about `center`: `object_from_render` takes
    /// a direction from the centre into the frame its coordinates are measured in.
    Sphere { center: Vec3, object_from_render: Mat3 },
}

impl EmissionMap {
    /// `emission` times the texture at `point`, a point on the emitter.
    pub fn radiance(&self, emission: Vec3, point: Vec3) -> Vec3 {
        emission * self.texture.eval(Vec3::ZERO, self.uv(point))
    }

    fn uv(&self, point: Vec3) -> Vec2 {
        match &self.uvs {
            UvSource::Triangle { vertices: [v0, v1, v2], uvs: [t0, t1, t2] } => {
                let [b1, b2] = barycentrics(*v0, *v1, *v2, point);
                *t0 * (1.0 - b1 - b2) + *t1 * b1 + *t2 * b2
            }
            UvSource::Sphere { center, object_from_render } => {
                sphere_uv((*object_from_render * (point - *center)).normalize_or_zero())
            }
        }
    }
}

/// The weights of `v1` and `v2` at `p` (a point on the triangle, within rounding), kept in
/// the triangle: the least-squares solution of p − v0 = b1·(v1 − v0) + b2·(v2 − v0).
fn barycentrics(v0: Vec3, v1: Vec3, v2: Vec3, p: Vec3) -> [f32; 2] {
    let (e1, e2, d) = ((v1 - v0).as_dvec3(), (v2 - v0).as_dvec3(), (p - v0).as_dvec3());
    let (d11, d12, d22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (d1, d2) = (d.dot(e1), d.dot(e2));
    let det = d11 * d22 - d12 * d12;
    if !(det > 0.0) {
        return [0.0, 0.0];
    }
    let b1 = ((d22 * d1 - d12 * d2) / det).clamp(0.0, 1.0);
    let b2 = ((d11 * d2 - d12 * d1) / det).clamp(0.0, 1.0 - b1);
    [b1 as f32, b2 as f32]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Pattern, TextureDesc, TextureMode};

    /// A texture whose colour is (u, v, 0): what a lookup returns is the coordinates.
    fn uv_texture() -> Arc<Texture> {
        let ramp = crate::scene::TextureImage {
            file: "uv".into(),
            width: 256,
            height: 256,
            texels: (0..256 * 256)
                .map(|i| {
                    Vec3::new(
                        ((i % 256) as f32 + 0.5) / 256.0,
                        ((i / 256) as f32 + 0.5) / 256.0,
                        0.0,
                    )
                })
                .collect(),
            srgb_decoded: false,
            hdr: true,
            rows_flipped: false,
        };
        let pattern = Pattern::Image {
            image: Arc::new(ramp),
            interpolation: crate::scene::Interpolation::BilinearCentered,
            normalizer: 1.0,
        };
        Arc::new(Texture::from_desc(&TextureDesc {
            pattern,
            mode: TextureMode::Replace,
            texture_from_object: glam::DAffine3::IDENTITY,
        }))
    }

    #[test]
    fn a_triangle_point_gets_its_interpolated_coordinates() {
        let vertices =
            [Vec3::new(1.0, 0.0, 2.0), Vec3::new(3.0, 0.5, 2.0), Vec3::new(1.5, 2.0, 1.0)];
        let uvs = [Vec2::new(0.1, 0.2), Vec2::new(0.9, 0.3), Vec2::new(0.4, 0.8)];
        let map = EmissionMap {
            texture: uv_texture(),
            mean: Vec3::ONE,
            uvs: UvSource::Triangle { vertices, uvs },
        };
        for (b1, b2) in [(0.2, 0.3), (0.6, 0.1), (0.05, 0.9)] {
            let p = vertices[0] * (1.0 - b1 - b2) + vertices[1] * b1 + vertices[2] * b2;
            let expected = uvs[0] * (1.0 - b1 - b2) + uvs[1] * b1 + uvs[2] * b2;
            let got = map.radiance(Vec3::splat(2.0), p);
            assert!(
                (got.truncate() - 2.0 * expected).abs().max_element() < 1e-3,
                "{got} vs {expected}"
            );
        }
    }

    #[test]
    fn a_sphere_point_gets_the_coordinates_a_hit_there_gets() {
        let frame = Mat3::from_rotation_z(0.7) * Mat3::from_rotation_x(-0.3);
        let center = Vec3::new(0.5, -1.0, 4.0);
        let map = EmissionMap {
            texture: uv_texture(),
            mean: Vec3::ONE,
            uvs: UvSource::Sphere { center, object_from_render: frame },
        };
        for dir in [Vec3::new(0.3, 0.4, -0.5), Vec3::new(-0.8, 0.1, 0.2)] {
            let n = dir.normalize();
            let expected = sphere_uv((frame * n).normalize());
            let got = map.radiance(Vec3::ONE, center + 2.5 * n).truncate();
            assert!((got - expected).abs().max_element() < 1e-3, "{got} vs {expected}");
        }
    }
}
