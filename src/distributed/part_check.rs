//! What a part file's metadata must hold before anything is made of it: numbers within what
//! a render can have, the display image's settings as the command line would accept them,
//! and AOVs the part recorded. A header edited by hand is a damaged part, not an image.

use super::metadata::{PartMeta, option_value};
use super::part::MAX_PARTS;
use crate::output::Aovs;

/// Checks `meta`; the problem, worded to follow "part file '…' is damaged: ".
pub(super) fn check_meta(meta: &PartMeta) -> Result<(), String> {
    check_sizes(meta)?;
    check_timing(meta)?;
    meta.png.look().map_err(|problem| format!("its PNG settings: {problem}"))?;
    check_aovs(meta)
}

/// The numbers are within what a render can have, so that laying out and reading the file
/// is bounded (a hostile header cannot ask for a huge allocation).
fn check_sizes(meta: &PartMeta) -> Result<(), String> {
    use crate::limits::{MAX_RESOLUTION, MAX_SAMPLES, MAX_SPP};
    let pixels = meta.width as u64 * meta.height as u64;
    let side = 1..=MAX_RESOLUTION;
    let part = meta.part;
    let samples = pixels.saturating_mul(u64::from(meta.spp.max(1)));
    if !side.contains(&meta.width) || !side.contains(&meta.height) || samples > MAX_SAMPLES {
        return Err(format!("its image size {}x{} is out of range", meta.width, meta.height));
    }
    if meta.spp == 0 || meta.spp > MAX_SPP {
        return Err(format!("its spp {} is out of range", meta.spp));
    }
    if !(1..=4096).contains(&meta.tile_size) {
        return Err(format!("its tile size {} is out of range", meta.tile_size));
    }
    if part.count == 0 || part.count > MAX_PARTS || part.index >= part.count {
        return Err(format!("its part {part} is out of range"));
    }
    Ok(())
}

/// The part's times are durations a render can take (finite, not negative, under a century)
/// and its thread count one a render can have: they are summed and printed by the merge.
fn check_timing(meta: &PartMeta) -> Result<(), String> {
    let t = &meta.timing;
    let century = 100.0 * 365.25 * 86400.0;
    for (name, seconds) in [
        ("build_seconds", t.build_seconds),
        ("render_seconds", t.render_seconds),
        ("cpu_seconds", t.cpu_seconds),
    ] {
        if !(0.0..=century).contains(&seconds) {
            let value = crate::excerpt::short_number(seconds.to_string());
            return Err(format!("its {name} {value} is out of range (0 to {century:e})"));
        }
    }
    if t.threads > crate::limits::MAX_THREADS {
        return Err(format!("its thread count {} is out of range", t.threads));
    }
    Ok(())
}

/// The AOVs parse, and those the part computes only on request were requested: a part
/// rendered without albedo holds albedo sums of zero, which a merged EXR would pass off as
/// an albedo channel.
fn check_aovs(meta: &PartMeta) -> Result<(), String> {
    let aovs = Aovs::parse(&meta.aovs).map_err(|problem| format!("its AOVs: {problem}"))?;
    let recorded = option_value(&meta.options, "first_hit_albedo");
    if aovs.albedo && recorded != Some("true") {
        return Err(format!(
            "its AOVs '{}' include albedo, but it was rendered without recording albedo \
             (first_hit_albedo: {}), so it holds no albedo sums for the channels albedo.R, \
             albedo.G, albedo.B",
            crate::excerpt::excerpt(&meta.aovs),
            recorded.unwrap_or("not given")
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A part's times out of range (a negative render time, 1e308 s, NaN, or a thread count
    /// beyond the limit) make it damaged; they were summed and printed (309 digits).
    #[test]
    fn times_out_of_range_are_refused() {
        let json = include_str!("part_check_meta.json");
        let meta: PartMeta = serde_json::from_str(json).unwrap();
        check_meta(&meta).unwrap();
        let with = |edit: fn(&mut PartMeta)| {
            let mut edited = meta.clone();
            edit(&mut edited);
            check_meta(&edited).unwrap_err()
        };
        assert!(with(|m| m.timing.render_seconds = -5.0).contains("render_seconds -5"));
        assert!(with(|m| m.timing.cpu_seconds = 1e308).contains("cpu_seconds 1e308"));
        assert!(with(|m| m.timing.build_seconds = f64::NAN).contains("build_seconds NaN"));
        assert!(with(|m| m.timing.threads = 1 << 20).contains("thread count 1048576"));
    }
}
