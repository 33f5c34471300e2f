//! `<sampler>`: the sample count, seed and jitter it asks for. The sampler's type does not
//! choose embray's (`--sampler` does, Owen-scrambled Sobol by default: the same estimate with
//! less noise; README, Mitsuba 3 scenes), so `strength` is checked and not used.

use super::tree::Element;
use super::values::{boolean, integer, refuse_unread};
use crate::scene::error::SceneError;

/// What a sampler asks of the render.
pub(super) struct Sampler {
    pub sample_count: u32,
    pub seed: u64,
    /// False puts each sample at its stratum's centre (stratified, multijitter, orthogonal).
    pub jitter: bool,
}

impl Default for Sampler {
    fn default() -> Self {
        Sampler { sample_count: 4, seed: 0, jitter: true }
    }
}

/// Mitsuba's samplers and the parameters each reads.
fn parameters(kind: &str) -> Option<&'static [&'static str]> {
    Some(match kind {
        "independent" | "ldsampler" => &["sample_count", "seed"],
        "stratified" | "multijitter" => &["sample_count", "seed", "jitter"],
        "orthogonal" => &["sample_count", "seed", "jitter", "strength"],
        _ => return None,
    })
}

pub(super) fn sampler(element: &Element) -> Result<Sampler, SceneError> {
    let kind = element.required("type")?;
    let Some(known) = parameters(kind) else {
        return Err(element.error(format!(
            "the sampler type '{}' is not one of Mitsuba's (independent, stratified, \
             multijitter, orthogonal, ldsampler)",
            crate::excerpt::excerpt(kind)
        )));
    };
    refuse_unread(element, &format!("the {kind} sampler"), known, &[])?;
    let named = |name: &str| element.children.iter().find(|c| c.attr("name") == Some(name));
    let sample_count = integer(element, "sample_count")?.unwrap_or(4);
    // Checked here, where the file and line are known, rather than as the render's spp.
    let max = crate::limits::MAX_SPP;
    if !(1..=i64::from(max)).contains(&sample_count) {
        let at = named("sample_count").unwrap_or(element);
        let range = format!("sample_count is {sample_count}, but must be 1 to {max}");
        return Err(at.error(range));
    }
    // Mitsuba reads the seed as an unsigned 32-bit number.
    let seed = integer(element, "seed")?;
    if let Some(seed) = seed.filter(|seed| !(0..=i64::from(u32::MAX)).contains(seed)) {
        let at = named("seed").unwrap_or(element);
        return Err(at.error(format!("seed is {seed}, but must be 0 to {}", u32::MAX)));
    }
    let jitter = boolean(element, "jitter")?.unwrap_or(true);
    if let Some(strength) = integer(element, "strength")?.filter(|s| *s < 1) {
        let at = named("strength").unwrap_or(element);
        return Err(at.error(format!("strength is {strength}, but must be at least 1")));
    }
    let seed = seed.unwrap_or(0) as u64;
    Ok(Sampler { sample_count: sample_count as u32, seed, jitter })
}
