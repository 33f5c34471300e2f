//! An MTL material's statements → the values they give, each with its line; what is not
//! understood (an unknown statement, one given twice, extra values) becomes a note. The
//! mapping of the values onto a `MaterialDesc` is `mtl_mapping`.

use super::mtl_notes::Note;
use glam::Vec3;

/// One statement of a material's block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Statement<'a> {
    /// As written (MTL readers take keywords in any case; so does embray).
    pub keyword: &'a str,
    /// What follows the keyword, trimmed.
    pub value: &'a str,
    pub line: usize,
}

/// The statements of the material whose `newmtl` is on line `newmtl_line` (from 1), which
/// begins at byte `offset`, up to the next `newmtl`; comments and blank lines left out. (Read
/// from the offset: skipping the lines before it made a file of n materials cost n².)
pub(super) fn statements(text: &str, newmtl_line: usize, offset: usize) -> Vec<Statement<'_>> {
    text[offset..]
        .lines()
        .enumerate()
        .skip(1)
        .map(|(i, line)| (newmtl_line + i, line.trim()))
        .take_while(|(_, line)| line.split_whitespace().next() != Some("newmtl"))
        .filter_map(|(line, text)| {
            let keyword = text.split_whitespace().next()?;
            (!keyword.starts_with('#')).then(|| Statement {
                keyword,
                value: text[keyword.len()..].trim(),
                line,
            })
        })
        .collect()
}

/// A value and the line that gave it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct At<T> {
    pub value: T,
    pub line: usize,
}

/// What a material's statements say, validated where embray uses the value.
#[derive(Debug, Default)]
pub(super) struct Given<'a> {
    pub kd: Option<At<Vec3>>,
    pub ks: Option<At<Vec3>>,
    pub ke: Option<At<Vec3>>,
    pub ka: Option<At<Vec3>>,
    pub tf: Option<At<Vec3>>,
    pub ns: Option<At<f32>>,
    pub ni: Option<At<f32>>,
    pub d: Option<At<f32>>,
    pub tr: Option<At<f32>>,
    pub pr: Option<At<f32>>,
    pub pm: Option<At<f32>>,
    pub illum: Option<At<u8>>,
    pub map_kd: Option<Statement<'a>>,
    pub map_ks: Option<Statement<'a>>,
    pub map_ke: Option<Statement<'a>>,
    pub map_d: Option<Statement<'a>>,
    /// `bump`, `map_Bump` or `map_bump`.
    pub bump: Option<Statement<'a>>,
    pub norm: Option<Statement<'a>>,
}

/// A problem with a value: its line and what is wrong.
pub(super) type Problem = (usize, String);

/// Statements embray knows but does not use, with what they are.
const UNSUPPORTED: [(&str, &str); 18] = [
    ("map_ka", "an ambient colour texture"),
    ("map_ns", "a texture of the specular exponent"),
    ("map_tr", "a transparency texture"),
    ("map_pr", "a roughness texture"),
    ("map_pm", "a metallic texture"),
    ("map_ps", "a sheen texture"),
    ("map_pc", "a clearcoat texture"),
    ("map_aat", "texture antialiasing"),
    ("disp", "a displacement map"),
    ("decal", "a decal texture"),
    ("refl", "a reflection map"),
    ("map_refl", "a reflection map"),
    ("sharpness", "the sharpness of reflection maps"),
    ("ps", "sheen"),
    ("pc", "a clearcoat"),
    ("pcr", "a clearcoat's roughness"),
    ("aniso", "anisotropy"),
    ("anisor", "the rotation of anisotropy"),
];

impl<'a> Given<'a> {
    /// Reads `statements`; a value that embray uses and that is out of range is an error.
    pub fn read(statements: &[Statement<'a>], notes: &mut Vec<Note>) -> Result<Self, Problem> {
        let mut given = Given::default();
        // (canonical keyword, value, line) of each statement read, for repeats.
        let mut seen: Vec<(String, &str, usize)> = Vec::new();
        for st in statements {
            let lower = st.keyword.to_ascii_lowercase();
            let canonical = match lower.as_str() {
                "map_bump" => "bump",
                other => other,
            };
            let known = match canonical {
                "kd" => set(&mut given.kd, colour(st, notes, 0.0..=1.0)?),
                "ks" => set(&mut given.ks, colour(st, notes, 0.0..=1.0)?),
                "ke" => set(&mut given.ke, colour(st, notes, 0.0..=f32::MAX)?),
                // Read only to be warned about: a value that cannot be read is no error.
                "ka" | "tf" => {
                    let slot = if canonical == "ka" { &mut given.ka } else { &mut given.tf };
                    match colour(st, notes, f32::MIN..=f32::MAX) {
                        Ok(c) => set(slot, c),
                        Err(_) => {
                            let message = format!("{} is not understood (3 numbers)", st.keyword);
                            notes.push(Note::new(st.line, message));
                            true
                        }
                    }
                }
                "ns" => set(&mut given.ns, number(st, notes, 0.0..=f32::MAX)?),
                // Checked where glass reads it: exporters write `Ni 0` for opaque materials.
                "ni" => set(&mut given.ni, number(st, notes, f32::MIN..=f32::MAX)?),
                "d" => set(&mut given.d, number(st, notes, 0.0..=1.0)?),
                "tr" => set(&mut given.tr, number(st, notes, 0.0..=1.0)?),
                "pr" => set(&mut given.pr, number(st, notes, 0.0..=1.0)?),
                "pm" => set(&mut given.pm, number(st, notes, 0.0..=1.0)?),
                "illum" => {
                    let value = st.value.split_whitespace().next().and_then(|w| w.parse().ok());
                    let Some(value) = value else {
                        return Err((st.line, "illum needs a whole number from 0 to 255".into()));
                    };
                    extra_values(st, 1, notes);
                    set(&mut given.illum, At { value, line: st.line })
                }
                "map_kd" => set(&mut given.map_kd, *st),
                "map_ks" => set(&mut given.map_ks, *st),
                "map_ke" => set(&mut given.map_ke, *st),
                "map_d" => set(&mut given.map_d, *st),
                "bump" => set(&mut given.bump, *st),
                "norm" => set(&mut given.norm, *st),
                _ => false,
            };
            if !known {
                let message = match UNSUPPORTED.iter().find(|(k, _)| *k == canonical) {
                    Some((_, what)) => format!("{} ({what}) is not supported", st.keyword),
                    None => {
                        notes.push(Note::unknown(st.line, st.keyword));
                        continue;
                    }
                };
                notes.push(Note::new(st.line, message));
                continue;
            }
            match seen.iter_mut().find(|(k, _, _)| k == canonical) {
                Some(earlier) => {
                    // Sponza gives its normal maps as both `bump` and `map_bump`: no news.
                    if earlier.1 != st.value {
                        notes.push(Note::new(
                            earlier.2,
                            // No line in the message: the same statement given twice in
                            // every material is one warning.
                            format!("{} is given again later, which is used", st.keyword),
                        ));
                    }
                    *earlier = (canonical.to_owned(), st.value, st.line);
                }
                None => seen.push((canonical.to_owned(), st.value, st.line)),
            }
        }
        Ok(given)
    }
}

/// Sets `slot` (a later statement replaces an earlier one, as tobj does); always `true`.
fn set<T>(slot: &mut Option<T>, value: T) -> bool {
    *slot = Some(value);
    true
}

/// Notes values beyond the `used` first.
fn extra_values(st: &Statement, used: usize, notes: &mut Vec<Note>) {
    let count = st.value.split_whitespace().count();
    if count > used {
        notes.push(Note::new(
            st.line,
            format!(
                "{} takes {used} value(s); the {} after them are not used",
                st.keyword,
                count - used
            ),
        ));
    }
}

fn out_of_range(range: &std::ops::RangeInclusive<f32>) -> String {
    match (*range.start(), *range.end()) {
        (lo, hi) if hi == f32::MAX && lo == 0.0 => "must be finite and >= 0".to_owned(),
        (_, hi) if hi == f32::MAX => "must be finite".to_owned(),
        (lo, hi) => format!("must be in [{lo}, {hi}]"),
    }
}

/// `keyword r g b`, each in `range`.
fn colour(
    st: &Statement,
    notes: &mut Vec<Note>,
    range: std::ops::RangeInclusive<f32>,
) -> Result<At<Vec3>, Problem> {
    let words: Vec<&str> = st.value.split_whitespace().take(3).collect();
    let values: Option<Vec<f32>> = words.iter().map(|w| w.parse::<f32>().ok()).collect();
    let values = values
        .filter(|v| v.len() == 3)
        .ok_or_else(|| (st.line, format!("{} needs 3 numbers", st.keyword)))?;
    for (i, &c) in values.iter().enumerate() {
        if !c.is_finite() || !range.contains(&c) {
            let message = format!("{}[{i}] is {c}, but {}", st.keyword, out_of_range(&range));
            return Err((st.line, message));
        }
    }
    extra_values(st, 3, notes);
    Ok(At { value: Vec3::from_slice(&values), line: st.line })
}

/// `keyword x`, in `range`.
fn number(
    st: &Statement,
    notes: &mut Vec<Note>,
    range: std::ops::RangeInclusive<f32>,
) -> Result<At<f32>, Problem> {
    let value = st.value.split_whitespace().next().and_then(|w| w.parse::<f32>().ok());
    let value = value.ok_or_else(|| (st.line, format!("{} needs a number", st.keyword)))?;
    if !value.is_finite() || !range.contains(&value) {
        let message = format!("{} is {value}, but {}", st.keyword, out_of_range(&range));
        return Err((st.line, message));
    }
    extra_values(st, 1, notes);
    Ok(At { value, line: st.line })
}
