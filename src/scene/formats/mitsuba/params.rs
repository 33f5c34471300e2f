//! A Mitsuba scene's `$name` parameters (`-D` first, then `<default>`s) and their
//! substitution into attribute values, in time near linear in the value: only the names
//! found after a `$` are tried (trying every name on every value was n² for n defaults).

use crate::excerpt::excerpt;
use crate::limits::MAX_XML_VALUE;
use std::cmp::Reverse;
use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};

pub(super) struct Params {
    values: HashMap<String, String>,
    /// How many names have each length (in bytes): the lengths tried after a `$`.
    lengths: BTreeMap<usize, usize>,
}

/// The order names are replaced in: the longest first, then by name.
type Order<'a> = (Reverse<usize>, &'a str);

fn escaped(text: &str, at: usize) -> bool {
    at > 0 && text.as_bytes()[at - 1] == b'\\'
}

impl Params {
    pub fn new(defines: &[(String, String)]) -> Self {
        let mut params = Params { values: HashMap::new(), lengths: BTreeMap::new() };
        for (name, value) in defines {
            params.add(name.clone(), value.clone());
        }
        params
    }

    /// `name`'s value, unless it has one already (a `-D` value stays, and so does the first
    /// `<default>`, as in Mitsuba).
    pub fn add(&mut self, name: String, value: String) {
        if !self.values.contains_key(&name) {
            *self.lengths.entry(name.len()).or_default() += 1;
            self.values.insert(name, value);
        }
    }

    /// The names that follow an unescaped `$` in `value[range]`, or up to `back` bytes
    /// before it, or right after it, added to `found`.
    fn names_in<'a>(
        &'a self,
        value: &str,
        range: std::ops::Range<usize>,
        back: usize,
        found: &mut BTreeSet<Order<'a>>,
    ) {
        let mut start = range.start.saturating_sub(back);
        while !value.is_char_boundary(start) {
            start -= 1;
        }
        let end = (range.end + 1).min(value.len());
        for (offset, _) in value[start..end].match_indices('$') {
            let at = start + offset;
            if escaped(value, at) {
                continue;
            }
            let tail = &value[at + 1..];
            for &length in self.lengths.keys().take_while(|&&length| length <= tail.len()) {
                let Some(candidate) = tail.get(..length) else { continue };
                if let Some((name, _)) = self.values.get_key_value(candidate) {
                    found.insert((Reverse(length), name.as_str()));
                }
            }
        }
    }

    /// `value` with every `$name` replaced by its parameter, as Mitsuba 3 substitutes: the
    /// longest names first (with `res` and `res_x` both defined, `$res_x` is the latter; with
    /// only `res`, `48_x`), an occurrence after a backslash left alone; a `$` left unescaped
    /// after that names an undefined parameter; `\$` then becomes `$`. The names replaced
    /// are added to `named`. Only names found after a `$` are tried: those in the value, then
    /// those that replacements bring (a name is tried after the ones before it in order).
    pub fn substitute(&self, value: &str, named: &mut HashSet<String>) -> Result<String, String> {
        if !value.contains('$') {
            return Ok(value.to_owned());
        }
        let mut value = value.to_owned();
        let mut pending = BTreeSet::new();
        self.names_in(&value, 0..value.len(), 0, &mut pending);
        while let Some(order) = pending.pop_first() {
            let name = order.1;
            let key = format!("${name}");
            let replacement = &self.values[name];
            let mut from = 0;
            let mut brought = BTreeSet::new();
            while let Some(found) = value[from..].find(&key) {
                let at = from + found;
                if escaped(&value, at) {
                    from = at + key.len();
                    continue;
                }
                value.replace_range(at..at + key.len(), replacement);
                if value.len() > MAX_XML_VALUE {
                    // Defaults made of defaults double at each: 2^n bytes from n lines.
                    return Err(format!(
                        "a value grows past {MAX_XML_VALUE} bytes as $names are replaced"
                    ));
                }
                from = at + replacement.len();
                named.insert(name.to_owned());
                // A name replaced later is no longer than this one: one that the
                // replacement completes begins at most its length before it.
                self.names_in(&value, at..from, key.len(), &mut brought);
            }
            pending.extend(brought.into_iter().filter(|&later| later > order));
        }
        if let Some((at, _)) = value.match_indices('$').find(|&(at, _)| !escaped(&value, at)) {
            let name: String = value[at + 1..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if name.is_empty() {
                return Err(
                    "a `$` must be followed by a parameter's name (write `\\$` for a dollar sign)"
                        .to_owned(),
                );
            }
            return Err(format!(
                "${} is not a parameter (give it with -D {}=VALUE or a <default>; known: {})",
                excerpt(&name),
                excerpt(&name),
                self.known()
            ));
        }
        let mut value = value.replace("\\$", "$");
        // Grown by doubling: a value kept with twice its length reserved held twice what the
        // memory check counts.
        value.shrink_to_fit();
        Ok(value)
    }

    /// The names, sorted, at most the first 20 of them.
    fn known(&self) -> String {
        const SHOWN: usize = 20;
        let mut names: Vec<&String> = self.values.keys().collect();
        names.sort_unstable();
        let more = names.len().saturating_sub(SHOWN);
        let shown: Vec<String> = names.iter().take(SHOWN).map(|n| excerpt(n)).collect();
        match (shown.is_empty(), more) {
            (true, _) => "none".to_owned(),
            (false, 0) => shown.join(", "),
            (false, more) => format!("{}, and {more} more", shown.join(", ")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(pairs: &[(&str, &str)]) -> Params {
        let defines: Vec<(String, String)> =
            pairs.iter().map(|(n, v)| (n.to_string(), v.to_string())).collect();
        Params::new(&defines)
    }

    #[test]
    fn longest_names_first_escapes_kept_and_unknown_names_refused() {
        let both = params(&[("res", "48"), ("res_x", "64")]);
        let mut named = HashSet::new();
        assert_eq!(both.substitute("$res_x $res \\$res", &mut named).unwrap(), "64 48 $res");
        let mut named_sorted: Vec<_> = named.into_iter().collect();
        named_sorted.sort();
        assert_eq!(named_sorted, ["res", "res_x"]);
        let short = params(&[("res", "48")]);
        assert_eq!(short.substitute("$res_x", &mut HashSet::new()).unwrap(), "48_x");
        // A value that names a parameter replaced later is replaced in turn.
        let chain = params(&[("long", "$b"), ("b", "2")]);
        assert_eq!(chain.substitute("$long", &mut HashSet::new()).unwrap(), "2");
        // A replacement may complete a name begun before it (`cc` before `xy` in order).
        let completed = params(&[("cc", "y"), ("xy", "Z")]);
        assert_eq!(completed.substitute("$x$cc", &mut HashSet::new()).unwrap(), "Z");
        // ...but not one already past in order (`ab` before `cc`): as Mitsuba, left unknown.
        let past = params(&[("cc", "b"), ("ab", "Z")]);
        let err = past.substitute("$a$cc", &mut HashSet::new()).unwrap_err();
        assert!(err.contains("$ab is not a parameter"), "{err}");
        let err = short.substitute("$spp", &mut HashSet::new()).unwrap_err();
        assert!(err.contains("$spp is not a parameter") && err.contains("known: res"), "{err}");
        let err = short.substitute("5$", &mut HashSet::new()).unwrap_err();
        assert!(err.contains("must be followed by a parameter's name"), "{err}");
    }

    #[test]
    fn many_defaults_are_substituted_in_linear_time() {
        // As Mitsuba reads `<default name="pK" value="$p0"/>`: each value substituted first.
        let mut many = params(&[("p0", "1")]);
        for i in 1..40_000 {
            let value = many.substitute("$p0", &mut HashSet::new()).unwrap();
            many.add(format!("p{i}"), value);
        }
        let start = std::time::Instant::now();
        let mut named = HashSet::new();
        for i in 0..40_000 {
            assert_eq!(many.substitute(&format!("$p{i}"), &mut named).unwrap(), "1");
        }
        // Each value tries a few lengths, not 40,000 names (which took minutes).
        assert!(start.elapsed().as_secs() < 20, "{:?}", start.elapsed());
        let err = many.substitute("$q", &mut named).unwrap_err();
        assert!(err.contains("and 39980 more"), "{err}");
    }
}
