//! Textures as the integrators evaluate them: a scene `Pattern` with the f32 transform from
//! the attached object's space to the pattern's space.

mod image;
pub mod perlin;

use crate::scene::{NoiseConversion, Pattern, TextureMode, UvMapped, Wrap};
use glam::{Affine3A, Vec2, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    pub pattern: Pattern,
    pub mode: TextureMode,
    /// From the attached object's space to the pattern's space.
    pub texture_from_object: Affine3A,
}

impl Texture {
    pub fn from_desc(desc: &crate::scene::TextureDesc) -> Self {
        Texture {
            pattern: desc.pattern.clone(),
            mode: desc.mode,
            texture_from_object: Affine3A::from_mat4(
                glam::DMat4::from(desc.texture_from_object).as_mat4(),
            ),
        }
    }

    /// The colour at object-space point `p_object` with texture coordinates `uv`.
    pub fn eval(&self, p_object: Vec3, uv: Vec2) -> Vec3 {
        let p = match self.pattern {
            Pattern::Checker2d { .. } | Pattern::Image { .. } | Pattern::UvMapped(_) => Vec3::ZERO,
            _ => self.texture_from_object.transform_point3(p_object),
        };
        self.eval_at(p, uv)
    }

    /// The colour at pattern-space point `p` with texture coordinates `uv`.
    fn eval_at(&self, p: Vec3, uv: Vec2) -> Vec3 {
        pattern_at(&self.pattern, p, uv)
    }

    /// The gradient of this solid pattern's mean channel at `p_object`, with respect to
    /// the object-space point (central differences a thousandth of the pattern's period
    /// apart).
    pub fn solid_gradient(&self, p_object: Vec3) -> Vec3 {
        let period = match &self.pattern {
            Pattern::Perlin { scale, .. } => 1.0 / scale,
            Pattern::Checker3d { scale, .. } | Pattern::CourseChecker { scale, .. } => 1.0 / scale,
            _ => 1.0,
        };
        let h = 1e-3 * period;
        let linear = self.texture_from_object.matrix3;
        let p = self.texture_from_object.transform_point3(p_object);
        let height = |q: Vec3| self.eval_at(q, Vec2::ZERO).element_sum() / 3.0;
        let along = |axis: Vec3| (height(p + h * axis) - height(p - h * axis)) / (2.0 * h);
        let in_pattern = Vec3::new(along(Vec3::X), along(Vec3::Y), along(Vec3::Z));
        // Heights are a function of the pattern point, which is linear in the object point.
        Vec3::from(linear.transpose() * glam::Vec3A::from(in_pattern))
    }

    /// The step in texture coordinates over which a height field's slope is taken: one
    /// texel of an image, else a small fraction of the unit square.
    pub fn uv_step(&self) -> Vec2 {
        let pattern = match &self.pattern {
            Pattern::UvMapped(mapped) => &mapped.inner,
            pattern => pattern,
        };
        match pattern {
            Pattern::Image { image, .. } => {
                Vec2::new(1.0 / image.width as f32, 1.0 / image.height as f32)
            }
            _ => Vec2::splat(1e-3),
        }
    }

    /// The exact derivatives of the value along u and along v at `uv`, for an image looked
    /// up as Mitsuba does (centred bilinear, maybe through a `to_uv`, whose linear part the
    /// chain rule takes); `None` for other patterns (a caller takes differences).
    pub fn uv_slopes(&self, uv: Vec2) -> Option<[Vec3; 2]> {
        let centred = |pattern: &Pattern, at: Vec2| match pattern {
            Pattern::Image { image, interpolation, normalizer }
                if *interpolation == crate::scene::Interpolation::BilinearCentered =>
            {
                Some(image.centred_bilinear_slopes(at).map(|s| s / *normalizer))
            }
            _ => None,
        };
        match &self.pattern {
            Pattern::UvMapped(mapped) => {
                let [along_u, along_v] = centred(&mapped.inner, mapped_uv(mapped, uv))?;
                let m = mapped.uv_from_surface.matrix2;
                Some([
                    along_u * m.x_axis.x + along_v * m.x_axis.y,
                    along_u * m.y_axis.x + along_v * m.y_axis.y,
                ])
            }
            pattern => centred(pattern, uv),
        }
    }

    /// What one unit of this texture's value is in the image's own units (its
    /// normalizer, 255 for 8-bit images by default); 1 for patterns.
    pub fn value_scale(&self) -> f32 {
        match &self.pattern {
            Pattern::Image { normalizer, .. } => *normalizer,
            Pattern::UvMapped(mapped) => match &mapped.inner {
                Pattern::Image { normalizer, .. } => *normalizer,
                _ => 1.0,
            },
            _ => 1.0,
        }
    }

    /// The mean colour over the unit square of texture coordinates, from a 128 × 128 grid of
    /// lookups at cell centres: what a textured emitter emits on average (its share of the
    /// light samples; any positive share keeps them unbiased).
    pub fn mean_over_unit_square(&self) -> Vec3 {
        const CELLS: u32 = 128;
        let at = |i: u32| (i as f32 + 0.5) / CELLS as f32;
        let sum: glam::DVec3 = (0..CELLS * CELLS)
            .map(|i| self.eval(Vec3::ZERO, Vec2::new(at(i % CELLS), at(i / CELLS))).as_dvec3())
            .sum();
        (sum / f64::from(CELLS * CELLS)).as_vec3()
    }

    /// The mesh attribute this texture shows and its scale, if it is a `mesh_attribute`
    /// texture.
    pub fn mesh_attribute(&self) -> Option<(&str, f32)> {
        match &self.pattern {
            Pattern::MeshAttribute { name, scale } => Some((name, *scale)),
            _ => None,
        }
    }

    pub fn needs_object_point(&self) -> bool {
        matches!(
            self.pattern,
            Pattern::Checker3d { .. } | Pattern::CourseChecker { .. } | Pattern::Perlin { .. }
        )
    }

    /// The diffuse reflectance at a point whose material's own is `albedo`, with this
    /// texture's colour `color` there.
    pub fn apply_to_albedo(&self, albedo: Vec3, color: Vec3) -> Vec3 {
        match self.mode {
            TextureMode::Replace | TextureMode::ReplaceAll => color,
            TextureMode::Blend => (albedo + color) * 0.5,
        }
    }
}

/// The colour of `pattern` at pattern-space point `p` with texture coordinates `uv`.
fn pattern_at(pattern: &Pattern, p: Vec3, uv: Vec2) -> Vec3 {
    let parity = |cells: &[f32]| cells.iter().map(|c| c.floor() as i64).sum::<i64>() & 1;
    match pattern {
        Pattern::Checker2d { scale, even, odd } => {
            if parity(&[uv.x * scale, uv.y * scale]) == 0 {
                *even
            } else {
                *odd
            }
        }
        Pattern::Checker3d { scale, even, odd } => {
            let p = p * *scale;
            if parity(&[p.x, p.y, p.z]) == 0 { *even } else { *odd }
        }
        Pattern::CourseChecker { scale, offset, black, white } => {
            let odd = |c: f32| ((c + offset) * scale) as i64 % 2 != 0;
            if (odd(p.x) != odd(p.y)) != odd(p.z) { *black } else { *white }
        }
        Pattern::Perlin { scale, conversion } => {
            let n = perlin::noise(p * *scale);
            Vec3::splat(match conversion {
                NoiseConversion::Absolute => n.abs(),
                NoiseConversion::Linear => (n + 1.0) * 0.5,
            })
        }
        Pattern::Image { image, interpolation, normalizer } => {
            image::lookup(image, *interpolation, uv) / *normalizer
        }
        Pattern::Constant(value) => *value,
        // Only the hit knows its mesh: `mesh_attribute` is where the tracer looks them up.
        Pattern::MeshAttribute { .. } => Vec3::ZERO,
        Pattern::UvMapped(mapped) => pattern_at(&mapped.inner, p, mapped_uv(mapped, uv)),
    }
}

/// `uv` mapped and wrapped as `mapped` says, for its inner pattern.
fn mapped_uv(mapped: &UvMapped, uv: Vec2) -> Vec2 {
    let uv = mapped.uv_from_surface.transform_point2(uv);
    let mirror = |t: f32| {
        let t = t.rem_euclid(2.0);
        if t > 1.0 { 2.0 - t } else { t }
    };
    let inside = match mapped.wrap {
        Wrap::Repeat => return uv,
        Wrap::Mirror => Vec2::new(mirror(uv.x), mirror(uv.y)),
        Wrap::Clamp => uv.clamp(Vec2::ZERO, Vec2::ONE),
    };
    // An image's lookup repeats across its edges: kept off them, it shows the edge texels.
    let Pattern::Image { image, interpolation, .. } = &mapped.inner else { return inside };
    let size = Vec2::new(image.width as f32, image.height as f32);
    let (low, high) = match interpolation {
        crate::scene::Interpolation::BilinearCentered => (0.5 / size, 1.0 - 0.5 / size),
        _ => (Vec2::ZERO, Vec2::splat(1.0 - f32::EPSILON / 2.0)),
    };
    inside.clamp(low, high)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::TextureDesc;

    fn perlin(texture_from_object: glam::DAffine3) -> Texture {
        Texture::from_desc(&TextureDesc {
            pattern: Pattern::Perlin { scale: 3.0, conversion: NoiseConversion::Linear },
            mode: TextureMode::Replace,
            texture_from_object,
        })
    }

    #[test]
    fn solid_gradients_are_directional_derivatives_in_object_space() {
        let scaled = glam::DAffine3::from_scale(glam::DVec3::new(2.0, 1.0, 0.5))
            * glam::DAffine3::from_rotation_z(0.4);
        for texture in [perlin(glam::DAffine3::IDENTITY), perlin(scaled)] {
            let height = |p: Vec3| texture.eval(p, Vec2::ZERO).x;
            for p in [Vec3::new(0.13, 0.71, -0.4), Vec3::new(-1.2, 0.05, 0.33)] {
                let g = texture.solid_gradient(p);
                for dir in [Vec3::X, Vec3::new(0.3, -0.8, 0.5).normalize()] {
                    // A wider central difference of the same field, in object space.
                    let h = 2e-3;
                    let slope = (height(p + h * dir) - height(p - h * dir)) / (2.0 * h);
                    let along = g.dot(dir);
                    assert!(
                        (along - slope).abs() < 0.02 * g.length().max(0.1),
                        "{p}: gradient gives {along}, differences {slope}"
                    );
                }
            }
        }
    }

    /// Mitsuba's `to_uv` and wrap modes on a 4 × 1 ramp (texels 0, 1, 2, 3) looked up
    /// between texel centres: 1.2 repeats to 0.2, mirrors to 0.8, clamps to the last texel.
    #[test]
    fn mapped_coordinates_repeat_mirror_and_clamp() {
        let ramp = crate::scene::TextureImage {
            file: "ramp".into(),
            width: 4,
            height: 1,
            texels: (0..4).map(|i| Vec3::splat(i as f32)).collect(),
            srgb_decoded: false,
            hdr: false,
            rows_flipped: false,
        };
        let image = Pattern::Image {
            image: std::sync::Arc::new(ramp),
            interpolation: crate::scene::Interpolation::BilinearCentered,
            normalizer: 1.0,
        };
        let at = |uv_from_surface, wrap, u: f32| {
            let mapped = UvMapped { uv_from_surface, wrap, inner: image.clone() };
            pattern_at(&Pattern::UvMapped(Box::new(mapped)), Vec3::ZERO, Vec2::new(u, 0.5)).x
        };
        let same = glam::Affine2::IDENTITY;
        let close = |a: f32, b: f32| assert!((a - b).abs() < 1e-5, "{a} vs {b}");
        close(at(same, Wrap::Repeat, 1.2), 0.3);
        close(at(same, Wrap::Mirror, 1.2), 2.7);
        close(at(same, Wrap::Clamp, 1.2), 3.0);
        close(at(same, Wrap::Clamp, -0.4), 0.0);
        // Shifted by half the image and scaled by 2: u = 0.1 looks up 0.7.
        let shifted =
            glam::Affine2::from_scale_angle_translation(Vec2::splat(2.0), 0.0, Vec2::new(0.5, 0.0));
        close(at(shifted, Wrap::Repeat, 0.1), 2.3);
        // The ramp rises 4 a unit of u between texel centres; through the map, twice that.
        let texture = |uv_from_surface| Texture {
            pattern: Pattern::UvMapped(Box::new(UvMapped {
                uv_from_surface,
                wrap: Wrap::Repeat,
                inner: image.clone(),
            })),
            mode: TextureMode::Replace,
            texture_from_object: glam::Affine3A::IDENTITY,
        };
        let slopes = |t: &Texture| t.uv_slopes(Vec2::new(0.4, 0.5)).unwrap().map(|s| s.x);
        assert_eq!(slopes(&texture(same)), [4.0, 0.0]);
        assert_eq!(slopes(&texture(shifted)), [8.0, 0.0]);
        // A quarter turn: u of the surface runs along the image's v, where nothing changes.
        let turned = glam::Affine2::from_angle(std::f32::consts::FRAC_PI_2);
        let [along_u, along_v] = slopes(&texture(turned));
        assert!(along_u.abs() < 1e-5 && (along_v + 4.0).abs() < 1e-5, "{along_u} {along_v}");
    }
}
