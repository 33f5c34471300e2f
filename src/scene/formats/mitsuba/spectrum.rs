//! `<spectrum>` → RGB as Mitsuba's RGB variants convert it.

use super::tree::Element;
use super::values::{ColorUse, numbers};
use crate::scene::error::SceneError;
use glam::DVec3;

pub(super) fn to_rgb(element: &Element, _usage: ColorUse) -> Result<DVec3, SceneError> {
    let text = element.required("value")?;
    if !text.contains(':') {
        return match numbers(element, text)?[..] {
            [v] => Ok(DVec3::splat(v)),
            _ => Err(element.error("a constant spectrum is one number")),
        };
    }
    Err(element.error("wavelength:value spectra are not supported yet"))
}
