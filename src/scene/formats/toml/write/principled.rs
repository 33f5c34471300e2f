//! A principled material's `type` and its `principled` table (an inline table, so that it
//! may stand among the material's other keys), the parameters that differ from Mitsuba's
//! defaults only.

use super::TomlWriteError;
use super::textures::texture_table;
use crate::scene::desc::{MaterialDesc, ParamDesc, PrincipledDesc};
use std::fmt::Write as _;

/// `principled` or `principledthin`, for a principled material.
pub(super) fn kind(m: &MaterialDesc) -> Option<&'static str> {
    m.principled.as_ref().map(|p| if p.thin { "principledthin" } else { "principled" })
}

pub(super) fn write(m: &MaterialDesc, out: &mut String) -> Result<(), TomlWriteError> {
    let Some(p) = m.principled.as_deref() else { return Ok(()) };
    let defaults = PrincipledDesc::new(p.thin);
    let mut fields = Vec::new();
    for ((name, value), (_, default)) in p.params().into_iter().zip(defaults.params()) {
        // A solid one's η always: its default depends on `specular`, which is not kept.
        let always = name == "eta" && !p.thin;
        if value == default && !always {
            continue;
        }
        let value = match value {
            ParamDesc::Constant(number) => format!("{number:?}"),
            ParamDesc::Texture(texture) => texture_table(texture, false, false)?,
        };
        fields.push(format!("{name} = {value}"));
    }
    let rates = &p.sampling_rates;
    // Every rate's default is 1.
    let mut rate = |name: &str, value: f32| {
        if value != 1.0 {
            fields.push(format!("{name} = {value:?}"));
        }
    };
    if p.thin {
        rate("specular_reflectance_sampling_rate", rates.specular_reflectance);
        rate("specular_transmittance_sampling_rate", rates.specular_transmittance);
        rate("diffuse_transmittance_sampling_rate", rates.diffuse_transmittance);
    } else {
        if rates.specular_reflectance != rates.specular_transmittance {
            return Err(TomlWriteError::Unsupported {
                item: format!("material '{}'", m.name),
                problem: "its two specular sampling rates differ".to_owned(),
            });
        }
        rate("main_specular_sampling_rate", rates.specular_reflectance);
        rate("clearcoat_sampling_rate", rates.clearcoat);
    }
    rate("diffuse_reflectance_sampling_rate", rates.diffuse_reflectance);
    if !fields.is_empty() {
        let _ = writeln!(out, "principled = {{ {} }}", fields.join(", "));
    }
    Ok(())
}
