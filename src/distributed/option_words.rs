//! Render options as a user writes them (`--offset 1,1,1`, `--clamp 0.5`), for messages
//! about parts that differ. A part file records its options as `RenderOptions`' debug text
//! (the part files' format and the EXR's `options` attribute, kept as they are), which no
//! user ever wrote: `DVec3(1.0, 1.0, 1.0)`, `Some(0.5)`, `Epsilon(1.0)`.

use crate::accel::{BackendKind, BatchMode, BuildQuality, Intersection};
use crate::choice::Choice;
use crate::render_options::PathBatching;
use crate::render_space::RenderSpace;
use crate::sampling::SamplerKind;
use crate::scene::desc::IntegratorKind;
use crate::shading::bsdf::Energy;

/// The first option two fingerprints (`options_fingerprint`) disagree on, each side as a
/// user would write it (`--offset 1,1,1` and `--offset 0,0,0`); `None` when they agree.
pub fn options_difference(a: &str, b: &str) -> Option<(String, String)> {
    let (fa, fb) = (fields(a), fields(b));
    if fa.len() != fb.len() {
        return (a != b).then(|| (a.to_owned(), b.to_owned()));
    }
    match fa.iter().zip(&fb).find(|(x, y)| x != y) {
        Some(((name, x), (_, y))) => Some((as_written(name, x), as_written(name, y))),
        None => (a != b).then(|| (a.to_owned(), b.to_owned())),
    }
}

/// The fields of a debug text `Name { a: 1, b: Inner { c: X(1.0, 2.0) } }` as (path,
/// value) pairs, nested structs flattened (`b.c`); commas inside brackets do not split.
fn fields(text: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    flatten("", text, &mut out);
    out
}

fn flatten(prefix: &str, text: &str, out: &mut Vec<(String, String)>) {
    let body = match (text.find('{'), text.trim_end().strip_suffix('}')) {
        (Some(open), Some(inner)) if open < inner.len() => &inner[open + 1..],
        _ => return out.push((prefix.to_owned(), text.trim().to_owned())),
    };
    for item in split_top_level(body) {
        let Some((name, value)) = item.split_once(": ") else { continue };
        let path = if prefix.is_empty() { name.to_owned() } else { format!("{prefix}.{name}") };
        let struct_value = value.starts_with(|c: char| c.is_ascii_uppercase())
            && value.split_once(' ').is_some_and(|(_, rest)| rest.starts_with('{'));
        if struct_value {
            flatten(&path, value, out);
        } else {
            out.push((path, value.to_owned()));
        }
    }
}

/// `text` split at the commas outside any brackets, each piece trimmed.
fn split_top_level(text: &str) -> Vec<&str> {
    let (mut pieces, mut depth, mut start) = (Vec::new(), 0i32, 0);
    for (i, c) in text.char_indices() {
        match c {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            ',' if depth == 0 => {
                pieces.push(text[start..i].trim());
                start = i + 1;
            }
            _ => {}
        }
    }
    pieces.push(text[start..].trim());
    pieces.into_iter().filter(|p| !p.is_empty()).collect()
}

/// The name of `C`'s value whose debug text is `debug` (`Fast` → `fast`).
fn choice<C: Choice + std::fmt::Debug>(debug: &str) -> String {
    let found = C::ALL.iter().find(|c| format!("{c:?}") == debug);
    found.map_or_else(|| debug.to_owned(), |c| c.name().to_owned())
}

/// A number as a user types it (`1.0` → `1`).
fn number(debug: &str) -> String {
    debug.trim().parse::<f64>().map_or_else(|_| debug.trim().to_owned(), |v| v.to_string())
}

/// The inside of `Name(…)`, if `debug` is that.
fn inside<'a>(debug: &'a str, name: &str) -> Option<&'a str> {
    debug.strip_prefix(name)?.strip_prefix('(')?.strip_suffix(')')
}

/// A flag that is given or not.
fn flag(name: &str, given: &str) -> String {
    if given == "true" { name.to_owned() } else { format!("no {name}") }
}

/// One option field (`accel.intersection`) with its debug value, as the command line
/// writes it; a field no flag sets says where it comes from.
fn as_written(name: &str, value: &str) -> String {
    let with = |flag: &str, written: String| format!("{flag} {written}");
    match name {
        "spp" | "max_depth" | "seed" | "light_samples" => {
            with(&format!("--{}", name.replace('_', "-")), value.to_owned())
        }
        "rr_depth" => format!("the scene's rr_depth {value}"),
        "jitter" if value == "false" => "--no-jitter (or the scene's jitter off)".to_owned(),
        "jitter" => "jittered samples".to_owned(),
        "backend" => with("--backend", choice::<BackendKind>(value)),
        "render_space" => with("--render-space", choice::<RenderSpace>(value)),
        "offset" => {
            let inner = inside(value, "DVec3").unwrap_or(value);
            with("--offset", inner.split(',').map(number).collect::<Vec<_>>().join(","))
        }
        "count_traversal" | "accel.count_traversal" => flag("--stats (on Embree)", value),
        "accel.build_quality" => with("--build-quality", choice::<BuildQuality>(value)),
        "accel.compact" => flag("--compact", value),
        "accel.batch" => with("--batch", choice::<BatchMode>(value)),
        "accel.intersection" => with("--intersection", choice::<Intersection>(value)),
        "effects_mode" => {
            flag("--force-all-effects", if value == "ForceAll" { "true" } else { "" })
        }
        "integrator" => format!("the scene's {} integrator", choice::<IntegratorKind>(value)),
        "paths" => with("--paths", choice::<PathBatching>(value)),
        "spawn" => match inside(value, "Epsilon") {
            Some(epsilon) => with("--spawn", format!("epsilon={}", number(epsilon))),
            None => with("--spawn", value.to_lowercase()),
        },
        "sampler" => with("--sampler", choice::<SamplerKind>(value)),
        "energy" => with("--energy", choice::<Energy>(value)),
        "clamp" => match inside(value, "Some") {
            Some(limit) => with("--clamp", number(limit)),
            None => "no --clamp".to_owned(),
        },
        "first_hit_albedo" if value == "true" => {
            "albedo recorded (--aovs albedo or --denoise)".to_owned()
        }
        "first_hit_albedo" => "no albedo recorded".to_owned(),
        _ => format!("{name}: {value}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::RenderOptions;
    use crate::shading::spawn::SpawnMode;
    use glam::DVec3;

    #[test]
    fn differing_options_read_as_the_command_line_writes_them() {
        let desc = crate::scene::load(&crate::bundled::default_scene()).unwrap();
        let base = RenderOptions::for_scene(&desc);
        let fingerprint = |o: &RenderOptions| super::super::options_fingerprint(o);
        let differ = |changed: RenderOptions| {
            options_difference(&fingerprint(&changed), &fingerprint(&base)).unwrap()
        };
        let pair = |a: &str, b: &str| (a.to_owned(), b.to_owned());
        let offset = RenderOptions { offset: DVec3::splat(1.0), ..base.clone() };
        assert_eq!(differ(offset), pair("--offset 1,1,1", "--offset 0,0,0"));
        let clamp = RenderOptions { clamp: Some(0.5), ..base.clone() };
        assert_eq!(differ(clamp), pair("--clamp 0.5", "no --clamp"));
        let spawn = RenderOptions { spawn: SpawnMode::Epsilon(1.0), ..base.clone() };
        assert_eq!(differ(spawn), pair("--spawn epsilon=1", "--spawn robust"));
        let mut accel = base.clone();
        accel.accel.intersection = Intersection::Fast;
        assert_eq!(differ(accel), pair("--intersection fast", "--intersection robust"));
        let mut quality = base.clone();
        quality.accel.build_quality = BuildQuality::High;
        assert_eq!(differ(quality), pair("--build-quality high", "--build-quality medium"));
        let spp = RenderOptions { spp: base.spp + 1, ..base.clone() };
        let expected = pair(&format!("--spp {}", base.spp + 1), &format!("--spp {}", base.spp));
        assert_eq!(differ(spp), expected);
        assert_eq!(options_difference(&fingerprint(&base), &fingerprint(&base)), None);
    }
}
