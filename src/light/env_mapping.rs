//! How an environment image covers the sphere of directions (world space, y up), and the
//! solid angle per unit of image area at each point (the Jacobian that turns densities over
//! the image into densities over directions).
//!
//! * Latitude-longitude (hw5.tex): u = (1 + atan2(x, −z)/π)/2, v = acos(y)/π; the image's
//!   centre looks along −z, its top row straight up. dω = 2π² sin θ du dv.
//! * Light probe (Debevec's angular map): the disc inscribed in the image; its centre looks
//!   along −z, its rim straight back (+z), and the distance from the centre is proportional
//!   to the angle from −z: with (a, b) = (2u − 1, 1 − 2v) and ρ = |(a, b)| ≤ 1, the direction
//!   is θ = πρ from −z towards (a, b). dω = 4π sin(πρ)/ρ du dv. Texels outside the disc are
//!   never seen.

use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// How an environment image covers the sphere of directions.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EnvironmentMapping {
    /// Latitude-longitude (equirectangular), hw5.tex's mapping.
    #[default]
    LatLong,
    /// Debevec's light probe (angular map).
    Probe,
}

crate::choice::named_choices!(EnvironmentMapping, "environment mapping", {
    LatLong => "latlong",
    Probe => "probe",
});

/// Image coordinates in [0, 1]² of the unit world direction `d`, and the solid angle per
/// unit image area there (0 where the mapping is singular: the poles of a lat-long map).
pub fn uv_of(mapping: EnvironmentMapping, d: Vec3) -> (Vec2, f32) {
    match mapping {
        EnvironmentMapping::LatLong => {
            let u = 0.5 * (1.0 + d.x.atan2(-d.z) / PI);
            // sin θ from the horizontal components stays accurate near the poles, where
            // 1 − cos² θ cancels.
            let sin_theta = d.x.hypot(d.z);
            let v = sin_theta.atan2(d.y) / PI;
            (Vec2::new(u, v), 2.0 * PI * PI * sin_theta)
        }
        EnvironmentMapping::Probe => {
            let sideways = d.x.hypot(d.y);
            let theta = sideways.atan2(-d.z);
            let rho = theta / PI;
            let (a, b) = if sideways > 0.0 {
                (rho * d.x / sideways, rho * d.y / sideways)
            } else if d.z <= 0.0 {
                (0.0, 0.0)
            } else {
                (1.0, 0.0) // straight back: any point of the rim
            };
            (Vec2::new(0.5 * (1.0 + a), 0.5 * (1.0 - b)), probe_jacobian(rho))
        }
    }
}

/// The unit world direction at image coordinates `uv` and the solid angle per unit image
/// area there; `None` outside a probe's disc.
pub fn direction_of(mapping: EnvironmentMapping, uv: Vec2) -> Option<(Vec3, f32)> {
    match mapping {
        EnvironmentMapping::LatLong => {
            let (sin_theta, cos_theta) = (uv.y * PI).sin_cos();
            let (sin_phi, cos_phi) = ((2.0 * uv.x - 1.0) * PI).sin_cos();
            let d = Vec3::new(sin_theta * sin_phi, cos_theta, -sin_theta * cos_phi);
            Some((d, 2.0 * PI * PI * sin_theta))
        }
        EnvironmentMapping::Probe => {
            let (a, b) = (2.0 * uv.x - 1.0, 1.0 - 2.0 * uv.y);
            let rho = a.hypot(b);
            if rho > 1.0 {
                return None;
            }
            let (sin_theta, cos_theta) = (PI * rho).sin_cos();
            let (ca, cb) = if rho > 0.0 { (a / rho, b / rho) } else { (0.0, 0.0) };
            let d = Vec3::new(sin_theta * ca, sin_theta * cb, -cos_theta);
            Some((d, probe_jacobian(rho)))
        }
    }
}

/// The solid angle per unit image area of the cell centred at `uv` with half-extents
/// `half`, for weighting the sampling distribution: at its centre, or for a cell that a
/// probe's rim cuts, at its point nearest the disc's centre; 0 only for cells wholly
/// outside the disc. (Every direction must keep a positive density: a direction never
/// sampled would be missing from direct light.)
pub fn cell_solid_angle(mapping: EnvironmentMapping, uv: Vec2, half: Vec2) -> f32 {
    if let Some((_, jacobian)) = direction_of(mapping, uv) {
        if jacobian > 0.0 {
            return jacobian;
        }
    }
    let nearest = Vec2::splat(0.5).clamp(uv - half, uv + half);
    direction_of(mapping, nearest).map_or(0.0, |(_, jacobian)| jacobian.max(f32::MIN_POSITIVE))
}

/// 4π sin(πρ)/ρ, with its limit 4π² at the centre.
fn probe_jacobian(rho: f32) -> f32 {
    if rho < 1e-4 { 4.0 * PI * PI } else { 4.0 * PI * (PI * rho).sin() / rho }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_mappings_invert_and_integrate_to_the_whole_sphere() {
        for mapping in [EnvironmentMapping::LatLong, EnvironmentMapping::Probe] {
            for uv in [Vec2::new(0.2, 0.3), Vec2::new(0.7, 0.6), Vec2::new(0.45, 0.5)] {
                let (d, _) = direction_of(mapping, uv).unwrap();
                assert!((d.length() - 1.0).abs() < 1e-5);
                assert!((uv_of(mapping, d).0 - uv).length() < 1e-4, "{mapping:?} {uv}");
            }
            // ∫ Jacobian du dv over the image is 4π.
            let n = 800;
            let total: f64 = (0..n * n)
                .map(|i| {
                    let uv = Vec2::new(
                        ((i % n) as f32 + 0.5) / n as f32,
                        ((i / n) as f32 + 0.5) / n as f32,
                    );
                    f64::from(direction_of(mapping, uv).map_or(0.0, |(_, j)| j))
                })
                .sum::<f64>()
                / (n * n) as f64;
            let sphere = 4.0 * std::f64::consts::PI;
            assert!((total - sphere).abs() < 0.01 * sphere, "{mapping:?}: {total}");
        }
        // The probe looks along −z at its centre, +x to the right, +y up.
        let probe = EnvironmentMapping::Probe;
        assert!((uv_of(probe, Vec3::NEG_Z).0 - Vec2::splat(0.5)).length() < 1e-6);
        assert!((uv_of(probe, Vec3::X).0 - Vec2::new(0.75, 0.5)).length() < 1e-6);
        assert!((uv_of(probe, Vec3::Y).0 - Vec2::new(0.5, 0.25)).length() < 1e-6);
        assert!(direction_of(probe, Vec2::new(0.02, 0.02)).is_none(), "a corner is outside");
    }
}
