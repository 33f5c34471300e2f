//! `<spectrum>` → linear sRGB as Mitsuba 3's RGB variants convert it: a constant is grey (an
//! emitter's is D65's white); a wavelength:value list is integrated against the CIE 1931
//! observer (times D65 unless it is emission), converted from XYZ and clamped. Its values are
//! range-checked as a constant's are. (A spectrum file arrives here as such a list: `spd`.)

use super::cie::{D65, MAX_NM, MIN_NM, SAMPLES, X_BAR, Y_BAR, Z_BAR};
use super::scalars::{ColorUse, numbers};
use super::tree::Element;
use crate::scene::error::SceneError;
use glam::{DMat3, DVec3};

/// CIE XYZ → linear sRGB.
const SRGB_FROM_XYZ: DMat3 = DMat3::from_cols_array(&[
    3.240479, -0.969256, 0.055648, -1.537150, 1.875991, -0.204043, -0.498535, 0.041556, 1.057311,
]);

/// A unit-valued spectrum integrates to a luminance of 1.
const Y_NORMALIZATION: f64 = 1.0 / 106.750_259_399_414_06;
const D65_NORMALIZATION: f64 = 1.0 / 98.99741751876255;

pub(super) fn to_rgb(element: &Element, usage: ColorUse) -> Result<DVec3, SceneError> {
    let text = element.required("value")?;
    if !text.contains(':') {
        return match numbers(element, text)?[..] {
            [v] if usage == ColorUse::Emission => Ok(v * (SRGB_FROM_XYZ * DVec3::ONE)),
            [v] => Ok(DVec3::splat(v)),
            _ => Err(element.error("a constant spectrum is one number")),
        };
    }
    let mut wavelengths = Vec::new();
    let mut values = Vec::new();
    for pair in text.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let Some((w, v)) = pair.split_once(':') else {
            return Err(element.error(format!("'{pair}' is not wavelength:value")));
        };
        match (&numbers(element, w)?[..], &numbers(element, v)?[..]) {
            (&[w], &[v]) => {
                if wavelengths.last().is_some_and(|&last| w <= last) {
                    return Err(element.error("the wavelengths must increase"));
                }
                wavelengths.push(w);
                values.push(v);
            }
            _ => return Err(element.error(format!("'{pair}' is not wavelength:value"))),
        }
    }
    if wavelengths.len() < 2 {
        return Err(element.error("a spectrum needs at least two wavelength:value pairs"));
    }
    refuse_out_of_range(element, usage, &wavelengths, &values)?;
    let (bounded, d65) = match usage {
        ColorUse::Reflectance => (true, true),
        ColorUse::Unbounded => (false, true),
        ColorUse::Emission => (false, false),
    };
    Ok(list_to_srgb(&wavelengths, &values, bounded, d65))
}

/// How far past its range a spectrum's sample may lie: a measurement's noise.
const NOISE: f64 = 1e-3;

/// Refuses a value a constant of the same use would be refused for (a reflectance outside
/// [0, 1], negative emission), rather than let the conversion clamp it unseen as Mitsuba
/// does (with a warning). Only the wavelengths the conversion reads count, and a
/// measurement's noise (1e-3) is let through. A conductor's index is not checked, as its
/// constant is not.
fn refuse_out_of_range(
    element: &Element,
    usage: ColorUse,
    wavelengths: &[f64],
    values: &[f64],
) -> Result<(), SceneError> {
    let (bounds, within): (&str, fn(f64) -> bool) = match usage {
        ColorUse::Reflectance => {
            ("in [0, 1] (a reflectance)", |v| (-NOISE..=1.0 + NOISE).contains(&v))
        }
        ColorUse::Emission => (">= 0 (emission)", |v| v >= -NOISE),
        ColorUse::Unbounded => return Ok(()),
    };
    let read = |(nm, _): &(&f64, &f64)| (MIN_NM..=MAX_NM).contains(*nm);
    let mut samples = wavelengths.iter().zip(values).filter(read);
    let Some((nm, value)) = samples.find(|(_, v)| !within(**v)) else {
        return Ok(());
    };
    let name = crate::excerpt::excerpt(element.attr("name").unwrap_or("the spectrum"));
    Err(element.error(format!("`{name}` is {value} at {nm} nm, but must be {bounds}")))
}

/// A table of `SAMPLES` values over [MIN_NM, MAX_NM] at `nm`, interpolated (0 outside).
fn lookup(table: &[f64; SAMPLES], nm: f64) -> f64 {
    if !(MIN_NM..=MAX_NM).contains(&nm) {
        return 0.0;
    }
    let t = (nm - MIN_NM) * ((SAMPLES - 1) as f64 / (MAX_NM - MIN_NM));
    let i0 = (t as usize).min(SAMPLES - 2);
    let w1 = t - i0 as f64;
    (1.0 - w1) * table[i0] + w1 * table[i0 + 1]
}

/// Mitsuba's `spectrum_list_to_srgb`: 1000 wavelengths over the CIE range, the spectrum
/// interpolated linearly (0 outside the listed range), times D65 when `d65`; `bounded`
/// results are clamped to [0, 1], others to >= 0.
pub(super) fn list_to_srgb(wavelengths: &[f64], values: &[f64], bounded: bool, d65: bool) -> DVec3 {
    const STEPS: usize = 1000;
    let mut xyz = DVec3::ZERO;
    let (first, last) = (wavelengths[0], wavelengths[wavelengths.len() - 1]);
    for i in 0..STEPS {
        let w = MIN_NM + (i as f64 / (STEPS - 1) as f64) * (MAX_NM - MIN_NM);
        if w < first || w > last {
            continue;
        }
        let k = wavelengths[..wavelengths.len() - 1].partition_point(|&x| x <= w).max(1) - 1;
        let (w0, w1, v0, v1) = (wavelengths[k], wavelengths[k + 1], values[k], values[k + 1]);
        let v = ((w - w1) * v0 + (w0 - w) * v1) / (w0 - w1);
        let illuminant = if d65 { lookup(&D65, w) * D65_NORMALIZATION } else { 1.0 };
        let cmf = DVec3::new(lookup(&X_BAR, w), lookup(&Y_BAR, w), lookup(&Z_BAR, w));
        xyz += cmf * v * illuminant;
    }
    xyz *= (MAX_NM - MIN_NM) * Y_NORMALIZATION / STEPS as f64;
    let rgb = SRGB_FROM_XYZ * xyz;
    if bounded { rgb.clamp(DVec3::ZERO, DVec3::ONE) } else { rgb.max(DVec3::ZERO) }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat reflectance of 1 under D65 is white, and one of 0.5 is mid grey; flat emission
    /// of 1 is D65's white point seen without D65 (Mitsuba prints (1.2048, 0.9483, 0.9089)).
    #[test]
    fn flat_spectra_give_mitsubas_colours() {
        let flat = |v: f64, bounded, d65| list_to_srgb(&[360.0, 830.0], &[v, v], bounded, d65);
        let white = flat(1.0, false, true);
        assert!((white - DVec3::ONE).abs().max_element() < 0.01, "{white}");
        let grey = flat(0.5, true, true);
        assert!((grey - DVec3::splat(0.5)).abs().max_element() < 0.005, "{grey}");
        let emission = flat(1.0, false, false);
        let expected = DVec3::new(1.204794, 0.948291, 0.908916);
        assert!((emission - expected).abs().max_element() < 0.01, "{emission}");
    }
}
